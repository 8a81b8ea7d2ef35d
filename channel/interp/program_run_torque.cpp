// G10 L14 (spec dafeng §2.9.1-2.9.4, L4768-5209): the torque data of the axes. P6 sets the
// load ratios of G31 P98/P99 (program_run_skip.cpp); P9 limits the drives' torque (L5094-5142).
// P0/P1 watch the load, P2-P5 start the load timers and P20-P51 read them (L4770-4849); P10-P12
// switch torque mode (run_torque_mode, below). P7/P8 watch the drilling/tapping cycles'
// in-feeds for overload (program_run_overload.cpp).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::interp {

namespace {
// The longest load filter J a program may name: an hour.
constexpr double kMaxLoadFilterSeconds = 3600.0;
// The longest time format ② may compare a load timer with: a day.
constexpr double kMaxLoadTimerSeconds = 86400.0;
// The highest motor speed G10 L14 P11 may name.
constexpr double kMaxTorqueModeRpm = 100000.0;
// Format ② (L4794-4812): P20/P21 read timer 2 ... P50/P51 timer 5.
bool is_timer_check(double p) {
  for (int timer = 2; timer <= 5; ++timer) {
    if (p == timer * 10.0 || p == timer * 10.0 + 1.0) {
      return true;
    }
  }
  return false;
}
}  // namespace

bool ProgramRun::run_torque_data(int column) {
  BlockWord* p = word('P');
  if (p->value == 6.0) {
    return run_load_ratio(column);
  }
  if (p->value == 9.0) {
    return run_torque_limit(column);
  }
  if (p->value >= 0.0 && p->value <= 5.0 && p->value == static_cast<int>(p->value)) {
    return run_load_watch(column);
  }
  if (is_timer_check(p->value)) {
    return run_load_timer_check(column);
  }
  if (p->value == 10.0 || p->value == 11.0 || p->value == 12.0) {
    return run_torque_mode(column);
  }
  if (p->value == 7.0 || p->value == 8.0) {
    return run_overload_watch(column);
  }
  return fail(alarm::kBadWordValue,
              "G10 L14 P" + std::to_string(static_cast<long long>(p->value)) +
                  " is not a torque function: P0/P1 watch the load, P2-P5 and P20-P51 time it, "
                  "P6 sets the load ratios of G31 P98/P99, P7/P8 watch the drilling/tapping "
                  "cycles, P9 the torque limits, P10-P12 switch torque mode",
              p->column);
}

bool ProgramRun::read_axis_percents(const char* what, AxisVector& values, std::uint32_t& given) {
  return read_axis_values(what, "% of the rated torque", kMaxTorquePercent, values, given);
}

bool ProgramRun::read_axis_values(const char* what, const char* unit, double max,
                                  AxisVector& values, std::uint32_t& given) {
  // Formats ① and ② (L4771-4776, L4794-4797) and P9 (L5098-5100): one value per axis, by its
  // absolute address.
  given = 0;
  return for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const std::string code = "G10 L14 P" + std::to_string(static_cast<int>(word('P')->value));
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  code + " takes " + what +
                      " by absolute addresses (X, Z, A ...), not by U, W "
                      "or UA",
                  w.column);
    }
    if (!(w.value >= 0.0 && w.value <= max)) {
      return fail(alarm::kBadWordValue,
                  code + " " + std::string(1, config_.axes[static_cast<std::size_t>(axis)].name) +
                      " (" + what + ", " + unit + ") must be 0-" +
                      std::to_string(static_cast<long long>(max)),
                  w.column);
    }
    values[static_cast<std::size_t>(axis)] = w.value;
    given |= 1U << axis;
    return true;
  });
}

bool ProgramRun::run_torque_limit(int column) {
  // G10 L14 P9 α (L5094-5142): each axis named has its drive's torque limited to α % of the
  // motor's rated torque from the next block on, 0 cancels it; modal (the later software's
  // reading, L5107-5108): G00 and G01 keep it. Without axes it says nothing: alarm.
  AxisVector limits{};
  std::uint32_t given = 0;
  if (!read_axis_percents("the torque limits", limits, given)) {
    return false;
  }
  if (given == 0) {
    return fail(alarm::kCycleWordMissing,
                "G10 L14 P9 needs the torque limit of an axis (Z135; Z0 cancels it)", column);
  }
  Command& c = emit(Op::torque_limit);
  c.torque_data_axes = given;
  c.torque_data = limits;
  return true;
}

bool ProgramRun::run_load_watch(int /*column*/) {
  // G10 L14 P0/P1 α J (L4770-4849): the axes named watched at α % of the rated torque, P0 in
  // every move, P1 in G01 only; J the seconds the load must stay above (D15: seconds, as the
  // example's J2). A new P0/P1 replaces the set (L4860); without axes it cancels it (L4866).
  // P2-P5 (L4783-4789, L4822-4835): the same without an alarm; each starts its load timer
  // (diagnostics 0530-0533) from 0 over the axes named, P2/P3 in G01 moves, P4/P5 in every
  // move; without axes the timer stops.
  const int p = static_cast<int>(word('P')->value);
  const bool every_move = p == 0 || p == 4 || p == 5;
  double filter_s = 0.0;
  if (BlockWord* j = word('J')) {
    j->used = true;
    if (!(j->value >= 0.0 && j->value <= kMaxLoadFilterSeconds)) {
      return fail(alarm::kBadWordValue, "G10 L14 J (the filter time, s) must be 0-3600", j->column);
    }
    filter_s = j->value;
  }
  AxisVector loads{};
  std::uint32_t given = 0;
  if (!read_axis_percents("the reference loads", loads, given)) {
    return false;
  }
  Command& c = emit(Op::load_watch);
  c.torque_data_axes = given;
  c.torque_data = loads;
  c.every_move = every_move;
  c.filter_s = filter_s;
  if (p >= 2) {
    c.load_timer = p;
    load_timer_axes_[static_cast<std::size_t>(p - 2)] = given;
  }
  return true;
}

bool ProgramRun::run_load_timer_check(int column) {
  // G10 L14 P20-P51 α R (L4792-4835): each axis named compares the seconds load timer P/10
  // counted above its reference with α: P20/P30/P40/P50 hold when less, P21/P31/P41/P51 when
  // more. The axes it holds for go to #R as bits (bit i for channel axis i+1: the example's Z,
  // the third axis, reads 4, L4890-4892), nothing is written when none; without R it holds is an
  // alarm. The timers run in the channel: the block is a read-ahead stop, and the channel hands
  // back the axes when every block before it ended (set_load_timer_result). Without it (a dry run,
  // `mcnc interp`) #R is not written.
  const int p = static_cast<int>(word('P')->value);
  const int timer = p / 10;
  const std::string code = "G10 L14 P" + std::to_string(p);
  std::int64_t variable = 0;
  if (!read_result_variable('R', code.c_str(), "the axes that meet the condition", variable)) {
    return false;
  }
  AxisVector seconds{};
  std::uint32_t given = 0;
  if (!read_axis_values("the time above the load", "s", kMaxLoadTimerSeconds, seconds, given)) {
    return false;
  }
  if (given == 0) {
    return fail(alarm::kCycleWordMissing,
                code + " needs the time of an axis to compare its load timer with (Z15)", column);
  }
  const std::uint32_t timed = load_timer_axes_[static_cast<std::size_t>(timer - 2)];
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    if (((given >> a) & 1U) != 0 && ((timed >> a) & 1U) == 0) {
      return fail(alarm::kCycleWordMissing,
                  code + " " + std::string(1, config_.axes[a].name) + ": load timer " +
                      std::to_string(timer) + " does not time axis " +
                      std::string(1, config_.axes[a].name) + " (give G10 L14 P" +
                      std::to_string(timer) + " with its reference load before it)",
                  column);
    }
  }
  Command& c = emit(Op::load_timer_check);
  c.load_timer = timer;
  c.timer_longer = p % 10 == 1;
  c.timer_variable = variable;
  c.torque_data_axes = given;
  c.torque_data = seconds;
  c.barrier = true;  // the program reads #R after it
  load_timer_variable_ = variable;
  return true;
}

bool ProgramRun::run_torque_mode(int column) {
  // G10 L14 P10/P11/P12 α (L5143-5209): P10 α the axes named to torque mode, α % of the rated
  // torque (the sign turns the motor), α0 back to position mode; P11 α their motor speed in
  // torque mode (rpm, unsigned; param 5521 where none); P12 α back to position mode with the
  // torque limit α (<= 0, -1 recommended: none). Absolute addresses only; no axis 1152.
  const int p = static_cast<int>(word('P')->value);
  const std::string code = "G10 L14 P" + std::to_string(p);
  AxisVector values{};
  std::uint32_t given = 0;
  const bool ok = for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const auto a = static_cast<std::size_t>(axis);
    const std::string name(1, config_.axes[a].name);
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  code +
                      " takes its values by absolute addresses (X, Z, B ...), not by U, W or "
                      "UB",
                  w.column);
    }
    const bool in_range = p == 10   ? std::fabs(w.value) <= kMaxTorquePercent
                          : p == 11 ? w.value > 0.0 && w.value <= kMaxTorqueModeRpm
                                    : w.value <= kMaxTorquePercent;
    if (!in_range) {
      return fail(alarm::kBadWordValue,
                  code + " " + name +
                      (p == 10   ? " (the torque, % of the rated torque) must be -1000 to 1000"
                       : p == 11 ? " (the motor speed, rpm) must be above 0 and up to 100000"
                                 : " (the torque limit, % of the rated torque) must be up to "
                                   "1000, or -1 for none"),
                  w.column);
    }
    if (p == 10 && w.value != 0.0 && torque_mode_speed_[a] <= 0.0 &&
        config_.axes[a].torque_mode_speed <= 0.0) {
      return fail(alarm::kCycleWordMissing,
                  code + " " + name + ": no motor speed for torque mode (G10 L14 P11 " + name +
                      " first, or param 5521: torque_mode_speed of the axis)",
                  w.column);
    }
    values[a] = p == 12 ? std::max(w.value, 0.0) : w.value;
    given |= 1U << axis;
    return true;
  });
  if (!ok) {
    return false;
  }
  if (given == 0) {
    return fail(alarm::kCycleWordMissing, code + " needs an axis (B50)", column);
  }
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    if (p == 11 && ((given >> a) & 1U) != 0) {
      torque_mode_speed_[a] = values[a];
    }
  }
  Command& c = emit(Op::torque_mode);
  c.torque_mode_p = p;
  c.torque_data_axes = given;
  c.torque_data = values;
  // Back in position mode the axis stands where the torque left it: the blocks after it start
  // from there (the channel's position at the stop).
  c.barrier = p != 11;
  return true;
}

void ProgramRun::set_load_timer_result(std::uint32_t axes) {
  if (axes != 0 && load_timer_variable_ != 0) {
    (void)vars_.write(load_timer_variable_, macro::MacroValue::of(static_cast<double>(axes)));
  }
}

}  // namespace mcnc::interp
