#include "channel/coordination/load_timers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::coordination {

LoadTimers::LoadTimers(std::span<const AxisSlot> slots) noexcept {
  for (std::size_t i = 0; i < slots.size() && i < kMaxAxes; ++i) {
    names_[i] = slots[i].address;
  }
}

void LoadTimers::axis_name(std::size_t axis, char (&name)[8]) const noexcept {
  if (names_[axis] != 0) {
    std::snprintf(name, sizeof name, "%c", names_[axis]);
  } else {
    std::snprintf(name, sizeof name, "%zu", axis + 1);
  }
}

void LoadTimers::start(int timer, std::uint32_t axes, const Values& reference,
                       std::uint64_t filter_cycles) noexcept {
  if (!valid(timer)) {
    return;
  }
  Timer& t = timers_[static_cast<std::size_t>(timer - kFirst)];
  t = Timer{};
  t.axes = axes;
  t.reference = reference;
  t.filter_cycles = std::max<std::uint64_t>(filter_cycles, 1);
}

void LoadTimers::clear() noexcept {
  timers_ = {};
}

bool LoadTimers::step(std::span<const AxisFeedbackView> feedback,
                      const MoveUnderWay& move) noexcept {
  for (std::size_t k = 0; k < timers_.size(); ++k) {
    Timer& t = timers_[k];
    // P2/P3 (timers 2 and 3) time G01 moves, P4/P5 every move (L4783-4789).
    const bool kind = static_cast<int>(k) + kFirst >= 4 || move.feed;
    for (std::size_t i = 0; i < feedback.size() && i < kMaxAxes; ++i) {
      const bool timed = kind && ((t.axes >> i) & 1U) != 0 && ((move.moves >> i) & 1U) != 0;
      if (!timed) {
        t.above[i] = 0;
        continue;
      }
      const AxisFeedbackView& f = feedback[i];
      if (!f.load_known) {
        char name[8];
        axis_name(i, name);
        alarm_.set(kAlarmLoadTime, "G10 L14 P%d: the drive of axis %s does not report its load",
                   static_cast<int>(k) + kFirst, name);
        alarm_.axis = static_cast<int>(i + 1);
        return false;
      }
      if (!(std::fabs(f.load) > t.reference[i])) {
        t.above[i] = 0;
        continue;
      }
      ++t.above[i];
      if (t.above[i] == t.filter_cycles) {
        t.counted[i] += t.above[i];  // the run lasted J: it counts from its start
      } else if (t.above[i] > t.filter_cycles) {
        ++t.counted[i];
      }
    }
  }
  return true;
}

std::uint64_t LoadTimers::cycles(int timer, std::size_t axis) const noexcept {
  return valid(timer) && axis < kMaxAxes
             ? timers_[static_cast<std::size_t>(timer - kFirst)].counted[axis]
             : 0;
}

std::uint32_t LoadTimers::check(int timer, bool longer, std::uint32_t axes, const Values& seconds,
                                double cycle_s, bool variable) noexcept {
  if (!valid(timer)) {
    return 0;
  }
  const Timer& t = timers_[static_cast<std::size_t>(timer - kFirst)];
  std::uint32_t met = 0;
  for (std::size_t i = 0; i < kMaxAxes; ++i) {
    if (((axes >> i) & 1U) == 0) {
      continue;
    }
    const double counted = static_cast<double>(t.counted[i]) * cycle_s;
    if (longer ? counted > seconds[i] : counted < seconds[i]) {
      if (met == 0 && !variable) {
        char name[8];
        axis_name(i, name);
        alarm_.set(kAlarmLoadTime,
                   "G10 L14 P%d: the load of axis %s was above %g %% for %.3f s, %s than %g s",
                   timer * 10 + (longer ? 1 : 0), name, t.reference[i], counted,
                   longer ? "more" : "less", seconds[i]);
        alarm_.axis = static_cast<int>(i + 1);
      }
      met |= 1U << i;
    }
  }
  return met;
}

}  // namespace mcnc::coordination
