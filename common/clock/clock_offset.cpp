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
  if (count_ < kMinSamples) {
    return true;
  }
  const Entry* best = &window_[0];
  for (std::uint32_t i = 1; i < count_; ++i) {
    if (window_[i].round_trip_ns < best->round_trip_ns) {
      best = &window_[i];
    }
  }
  const ClockOffset candidate{best->offset_ns, (best->round_trip_ns + 1) / 2, count_};
  const std::int64_t allowance =
      held_ ? held_->error_ns + (e.t4_ns - held_at_ns_) / 1'000'000 * kDriftPpm : 0;
  if (!held_ || candidate.error_ns <= allowance) {
    held_ = candidate;
    held_at_ns_ = e.t4_ns;
  } else {
    held_->samples = count_;
  }
  return true;
}

}  // namespace mcnc::clock
