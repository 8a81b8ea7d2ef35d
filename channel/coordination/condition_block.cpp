#include "channel/coordination/condition_block.hpp"

#include "channel/interp/program_alarms.hpp"

#include <cmath>

namespace mcnc::coordination {
namespace {

ConditionWaitLimits limits_of(const ConditionSpec& spec, const ConditionSetup& setup) noexcept {
  ConditionWaitLimits limits;
  limits.width_s = spec.input ? spec.width_s : -1.0;
  limits.dwell_s = spec.dwell_s;
  limits.timeout_s = spec.input ? spec.timeout_s : setup.speed_arrival_timeout_s;
  return limits;
}

}  // namespace

ConditionBlock::ConditionBlock(const ConditionSpec& spec, const ConditionSetup& setup) noexcept
    : spec_(spec), setup_(setup), wait_(limits_of(spec, setup), setup.cycle_s) {}

ConditionStep ConditionBlock::step(const ConditionInputs& in) noexcept {
  const ConditionSpec& c = spec_;
  bool holds = false;
  if (c.input) {
    if (in.input_bit < 0 || in.input_bit > 63 || in.plc_gone) {
      alarm_.set(interp::alarm::kInputPort, "G04 I%s%d: %s", c.on ? "" : "-", c.port,
                 in.plc_gone ? "the PLC node is gone" : "the PLC has no input with this port");
      return ConditionStep::alarm;
    }
    holds = (((in.plc_inputs >> in.input_bit) & 1U) != 0) == c.on;
  } else {
    if (!in.spindle_present) {
      alarm_.set(interp::alarm::kNoSuchSpindle,
                 "G04 PS%d=: no feedback of spindle %d in this channel", c.spindle, c.spindle);
      return ConditionStep::alarm;
    }
    // degrees per second to revolutions per minute; the direction does not count.
    constexpr double kRpmPerDegreePerSecond = 60.0 / 360.0;
    const double rpm = std::fabs(in.spindle_vel) * kRpmPerDegreePerSecond;
    holds = std::fabs(rpm - c.rpm) <= setup_.speed_arrival_rpm;
  }
  switch (wait_.step(holds)) {
    case WaitOutcome::waiting:
      return ConditionStep::waiting;
    case WaitOutcome::timed_out:
      // With a dwell time the time ends the block (spec [AMBIGUOUS], decision 68); without
      // one, an input or a speed that never comes is an alarm, as M01 I/J's (L6045-6049).
      if (c.dwell_s >= 0.0) {
        return ConditionStep::done;
      }
      if (c.input) {
        alarm_.set(kAlarmInputTimeout, "G04 I%s%d: input %d not %s within %.3f s (J)",
                   c.on ? "" : "-", c.port, c.port, c.on ? "on" : "off", c.timeout_s);
      } else {
        alarm_.set(kAlarmSpeedTimeout,
                   "G04 PS%d=%.0f: spindle %d not within %.0f rpm of it after %.3f s "
                   "(speed_arrival, parameters 1057/1059)",
                   c.spindle, c.rpm, c.spindle, setup_.speed_arrival_rpm,
                   setup_.speed_arrival_timeout_s);
      }
      return ConditionStep::alarm;
    case WaitOutcome::met:
    case WaitOutcome::dwell_over:
      break;
  }
  return ConditionStep::done;
}

}  // namespace mcnc::coordination
