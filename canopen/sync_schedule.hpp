#pragma once
// When a SYNC producer sends (CiA 301 §7.2.5: SYNC every communication cycle period): SYNC n
// at start + n x period + offset, a fixed point inside each cycle. A producer that wakes late
// sends the latest SYNC that is due and skips the ones it missed, so the drives never get a
// burst of SYNCs that would each step them a full cycle. The start may move while SYNCs go out
// (a host's estimate of the machine's clock refined): the SYNCs after it follow, by a bounded
// step each, so that no cycle of the drives is much shorter or longer than the period. Pure:
// times in, indices out.
#include <cstdint>

namespace mcnc::canopen {

class SyncSchedule {
 public:
  SyncSchedule(std::int64_t start_ns, std::int64_t period_ns, std::int64_t offset_ns) noexcept
      : start_ns_(start_ns), period_ns_(period_ns > 0 ? period_ns : 1), offset_ns_(offset_ns) {}

  // Moves the start toward `target_ns` by at most 1 % of the period; call it once per SYNC.
  // SYNC n is then due at the start + n x period + offset. An index once handed out is never
  // handed out again: a start moved earlier does not repeat a SYNC.
  void follow_start(std::int64_t target_ns) noexcept {
    const std::int64_t step = period_ns_ / 100 > 0 ? period_ns_ / 100 : 1;
    const std::int64_t gap = target_ns - start_ns_;
    start_ns_ += gap > step ? step : (gap < -step ? -step : gap);
  }
  [[nodiscard]] std::int64_t start_ns() const noexcept { return start_ns_; }

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
