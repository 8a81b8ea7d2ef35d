#include "channel/coordination/spindle_mode.hpp"

#include "channel/interp/program_alarms.hpp"

#include <cmath>

namespace mcnc::coordination {

void SpindleMode::begin(bool position) noexcept {
  to_position_ = position;
  still_cycles_ = 0;
  waited_ = 0;
  seen_ = false;
  last_act_ = 0.0;
}

SpindleModeStep SpindleMode::step(const SpindleModeInputs& in) noexcept {
  if (!in.has_c_axis) {
    alarm_.set(interp::alarm::kSpindleControl, "the spindle has no C axis for position control");
    return SpindleModeStep::alarm;
  }
  if (!to_position_) {
    position_ = false;
    return SpindleModeStep::done;
  }
  if (position_) {
    return SpindleModeStep::done;  // already under position control
  }
  if (in.follows) {
    alarm_.set(kAlarmSlaveSpindle,
               "the spindle follows another spindle (G114.1): its master's channel cancels that "
               "with G113 before position control");
    return SpindleModeStep::alarm;
  }
  still_cycles_ = seen_ && std::fabs(in.act - last_act_) <= rest_width_ ? still_cycles_ + 1 : 0;
  seen_ = true;
  last_act_ = in.act;
  if (still_cycles_ < kStillCycles) {
    if (static_cast<double>(++waited_) * cycle_s_ > kRestTimeout) {
      alarm_.set(kAlarmSpindleNotAtRest,
                 "position control: the spindle did not come to rest within 10 s");
      return SpindleModeStep::alarm;
    }
    return SpindleModeStep::waiting;
  }
  c_base_ = 360.0 * std::floor(in.act / 360.0);
  c_start_ = in.act - c_base_;
  position_ = true;
  return SpindleModeStep::done;
}

}  // namespace mcnc::coordination
