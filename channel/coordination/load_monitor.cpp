#include "channel/coordination/load_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::coordination {

LoadMonitor::LoadMonitor(std::span<const AxisSlot> slots) noexcept {
  for (std::size_t i = 0; i < slots.size() && i < kMaxAxes; ++i) {
    names_[i] = slots[i].address;
  }
}

void LoadMonitor::raise(std::size_t axis, const char* why, double load) noexcept {
  const int p = p_ >= 0 ? p_ : watch_ == LoadWatch::every_move ? 0 : 1;
  char name[8];
  if (names_[axis] != 0) {
    std::snprintf(name, sizeof name, "%c", names_[axis]);
  } else {
    std::snprintf(name, sizeof name, "%zu", axis + 1);
  }
  if (why == nullptr) {
    alarm_.set(kAlarmOverload, "G10 L14 P%d: the load of axis %s, %g %%, is above %g %% (overload)",
               p, name, load, reference_[axis]);
  } else {
    alarm_.set(kAlarmOverload, "G10 L14 P%d: the drive of axis %s %s", p, name, why);
  }
  alarm_.axis = static_cast<int>(axis + 1);
}

void LoadMonitor::set(LoadWatch watch, std::uint32_t axes, const Percent& reference,
                      std::uint64_t filter_cycles, int p) noexcept {
  p_ = p;
  watch_ = axes != 0 ? watch : LoadWatch::off;
  axes_ = watch_ != LoadWatch::off ? axes : 0;
  reference_ = reference;
  filter_cycles_ = std::max<std::uint64_t>(filter_cycles, 1);
  over_ = {};
}

bool LoadMonitor::step(std::span<const AxisFeedbackView> feedback,
                       const MoveUnderWay& move) noexcept {
  const bool kind =
      watch_ == LoadWatch::every_move || (watch_ == LoadWatch::feed_moves && move.feed);
  for (std::size_t i = 0; i < feedback.size() && i < kMaxAxes; ++i) {
    const bool watched = kind && ((axes_ >> i) & 1U) != 0 && ((move.moves >> i) & 1U) != 0;
    if (!watched) {
      over_[i] = 0;
      continue;
    }
    const AxisFeedbackView& f = feedback[i];
    if (!f.load_known) {
      raise(i, "does not report its load", 0.0);
      return true;
    }
    over_[i] = std::fabs(f.load) > reference_[i] ? over_[i] + 1 : 0;
    if (over_[i] >= filter_cycles_) {
      raise(i, nullptr, std::fabs(f.load));
      return true;
    }
  }
  return false;
}

}  // namespace mcnc::coordination
