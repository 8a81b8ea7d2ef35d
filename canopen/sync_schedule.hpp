#pragma once
// When a SYNC producer sends (CiA 301 §7.2.5: SYNC every communication cycle period): SYNC n
// at start + n x period + offset, a fixed point inside each cycle. A producer that wakes late
// sends the latest SYNC that is due and skips the ones it missed, so the drives never get a
// burst of SYNCs that would each step them a full cycle. Pure: times in, indices out.
#include <cstdint>

namespace mcnc::canopen {

class SyncSchedule {
 public:
  SyncSchedule(std::int64_t start_ns, std::int64_t period_ns, std::int64_t offset_ns) noexcept
      : start_ns_(start_ns), period_ns_(period_ns > 0 ? period_ns : 1), offset_ns_(offset_ns) {}

  // When SYNC n is due.
  [[nodiscard]] std::int64_t due(std::uint64_t n) const noexcept {
    return start_ns_ + static_cast<std::int64_t>(n) * period_ns_ + offset_ns_;
  }
  // The SYNC to send at `now` when the next unsent one is `next`: `next` once its time has come
  // (or later: the latest one due), nothing (false) before.
  bool to_send(std::int64_t now, std::uint64_t next, std::uint64_t& index) const noexcept {
    if (now < due(next)) {
      return false;
    }
    const auto latest = static_cast<std::uint64_t>((now - start_ns_ - offset_ns_) / period_ns_);
    index = latest > next ? latest : next;
    return true;
  }

 private:
  std::int64_t start_ns_;
  std::int64_t period_ns_;
  std::int64_t offset_ns_;
};

}  // namespace mcnc::canopen
