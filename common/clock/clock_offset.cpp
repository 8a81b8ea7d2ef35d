#include "common/clock/clock_offset.hpp"

namespace mcnc::clock {

bool ClockOffsetFilter::add(const ClockExchange& e) noexcept {
  const std::int64_t at_host = e.t4_ns - e.t1_ns;
  const std::int64_t at_reference = e.t3_ns - e.t2_ns;
  if (at_host < 0 || at_reference < 0 || at_reference > at_host) {
    return false;
  }
  // offset = ((t1 - t2) + (t4 - t3)) / 2, each difference first so that nothing overflows.
  const std::int64_t offset = ((e.t1_ns - e.t2_ns) + (e.t4_ns - e.t3_ns)) / 2;
  window_[next_] = Entry{offset, at_host - at_reference};
  next_ = (next_ + 1) % kWindow;
  if (count_ < kWindow) {
    ++count_;
  }
  return true;
}

std::optional<ClockOffset> ClockOffsetFilter::estimate() const noexcept {
  if (count_ < kMinSamples) {
    return std::nullopt;
  }
  const Entry* best = &window_[0];
  for (std::uint32_t i = 1; i < count_; ++i) {
    if (window_[i].round_trip_ns < best->round_trip_ns) {
      best = &window_[i];
    }
  }
  return ClockOffset{best->offset_ns, (best->round_trip_ns + 1) / 2, count_};
}

}  // namespace mcnc::clock
