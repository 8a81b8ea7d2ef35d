// G10 L14 (spec dafeng §2.9.1-2.9.4, L4768-5209): the torque data of the axes. P6 sets the
// load ratios of G31 P98/P99 (program_run_skip.cpp); P9 limits the drives' torque (L5094-5142).
// P0/P1 watch the load (L4770-4849). The timers of P2-P5 and P20-P51, the drilling/tapping
// overloads (P7/P8) and torque mode (P10-P12) are not implemented.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <string>

namespace mcnc::interp {

namespace {
// The longest load filter J a program may name: an hour.
constexpr double kMaxLoadFilterSeconds = 3600.0;
}  // namespace

bool ProgramRun::run_torque_data(int column) {
  BlockWord* p = word('P');
  if (p->value == 6.0) {
    return run_load_ratio(column);
  }
  if (p->value == 9.0) {
    return run_torque_limit(column);
  }
  if (p->value == 0.0 || p->value == 1.0) {
    return run_load_watch(column);
  }
  return fail(alarm::kNotInThisVersion,
              "G10 L14 P" + std::to_string(static_cast<long long>(p->value)) +
                  " (load timers, overload detection or torque mode) is not implemented; G10 "
                  "L14 P0/P1 watch the load, P6 sets the load ratios of G31 P98/P99, P9 the "
                  "torque limits",
              p->column);
}

bool ProgramRun::read_axis_percents(const char* what, AxisVector& values, std::uint32_t& given) {
  // Format ① (L4771-4776) and P9 (L5098-5100): one value per axis, by its absolute address.
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
    if (!(w.value >= 0.0 && w.value <= kMaxTorquePercent)) {
      return fail(alarm::kBadWordValue,
                  code + " " + std::string(1, config_.axes[static_cast<std::size_t>(axis)].name) +
                      " (" + what + ", % of the rated torque) must be 0-1000",
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
  const bool every_move = word('P')->value == 0.0;
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
  return true;
}

}  // namespace mcnc::interp
