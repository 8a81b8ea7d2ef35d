#include "channel/coordination/skip_probe.hpp"

#include "channel/interp/program_alarms.hpp"

namespace mcnc::coordination {

void SkipProbe::begin(int input) noexcept {
  input_ = input;
  signal_ = 0;
  phase_ = SkipPhase::arming;
  waited_ = 0;
  skipped_ = false;
  lost_ = false;
  torque_ = false;
  load_ = 0;
  multi_ = false;
  latch_count_ = 0;
  skip_at_ = {};
}

void SkipProbe::begin_multi(int input, std::size_t axis, int most) noexcept {
  begin(input);
  multi_ = true;
  torque_axis_ = axis;
  most_ = most < 1
              ? 1
              : (static_cast<std::size_t>(most) > kMaxLatches ? kMaxLatches
                                                              : static_cast<std::size_t>(most));
}

bool SkipProbe::watch_multi(std::span<const AxisFeedbackView> feedback) noexcept {
  if (phase_ != SkipPhase::moving || torque_axis_ >= feedback.size()) {
    return false;
  }
  const AxisFeedbackView& f = feedback[torque_axis_];
  const std::uint32_t edges = f.probe_count - seen_count_;
  if (edges == 0) {
    return false;
  }
  seen_count_ = f.probe_count;
  if (edges > 1) {
    // The drive holds one position until its next report: the others are gone.
    lost_ = true;
    alarm_.set(kAlarmEdgesLost,
               "G31.8: %u edges on input %d within one cycle, the drive reports one position a "
               "cycle",
               edges, input_);
    phase_ = SkipPhase::stopping;
    return true;
  }
  latched_[latch_count_++] = f.probe_pos;
  skipped_ = true;
  if (latch_count_ < most_) {
    return false;
  }
  phase_ = SkipPhase::stopping;
  return true;
}

void SkipProbe::begin_torque(std::size_t axis) noexcept {
  begin(0);
  torque_ = true;
  torque_axis_ = axis;
}

void SkipProbe::begin_load(int input, bool or_input) noexcept {
  begin(input);
  load_ = or_input ? 99 : 98;
}

void SkipProbe::begin_signal(int signal) noexcept {
  begin(0);
  signal_ = signal;
}

SkipArming SkipProbe::arm_signal(bool on, bool gone) noexcept {
  if (gone) {
    alarm_.set(interp::alarm::kSkipInput, "G31 P%d: the PLC node is gone", signal_);
    return SkipArming::alarm;
  }
  if (!on) {
    return SkipArming::armed;
  }
  if (++waited_ > arm_cycles_) {
    alarm_.set(kAlarmProbeNotArmed, "G31 P%d: the PLC's skip signal G0014.%d is on before the move",
               signal_, signal_ - 1);
    return SkipArming::alarm;
  }
  return SkipArming::waiting;
}

bool SkipProbe::watch_signal(std::span<const AxisFeedbackView> feedback, bool on,
                             bool gone) noexcept {
  if (phase_ != SkipPhase::moving || !(on || gone)) {
    return false;
  }
  // Where every axis stood when the signal was seen: the signal crossed the PLC's cycle and
  // DDS on its way, so this is later than where it came by that travel (decision 92).
  for (std::size_t j = 0; j < axis_count_ && j < feedback.size() && j < kMaxAxes; ++j) {
    skip_at_[j] = feedback[j].act;
  }
  if (gone) {
    lost_ = true;
    alarm_.set(interp::alarm::kSkipInput, "G31 P%d: the PLC node is gone", signal_);
  } else {
    skipped_ = true;
  }
  phase_ = SkipPhase::stopping;
  return true;
}

SkipArming SkipProbe::arm(std::span<const AxisFeedbackView> feedback,
                          std::uint32_t probes) noexcept {
  bool armed = true;
  bool any = false;
  for (std::size_t i = 0; i < axis_count_ && i < feedback.size() && i < kMaxAxes; ++i) {
    if (((probes >> i) & 1U) != 0) {
      any = true;
      armed = armed && feedback[i].probe == ProbeSeen::armed;
    }
  }
  const int axis = static_cast<int>(torque_axis_) + 1;
  if (!any) {
    if (load_ != 0) {
      alarm_.set(interp::alarm::kSkipInput,
                 "G31 P%d: no axis of the move that this channel commands takes a torque limit "
                 "(torque_skip)%s",
                 load_, load_ == 99 ? " or has its touch probe on the input" : "");
    } else if (torque_) {
      alarm_.set(interp::alarm::kSkipInput,
                 "G160: the channel does not command axis %d, or its drive takes no torque limit "
                 "(torque_skip)",
                 axis);
    } else if (multi_) {
      alarm_.set(interp::alarm::kSkipInput,
                 "G31.8: the axis it moves (%d) is not this channel's to command, or its touch "
                 "probe is not on input %d",
                 axis, input_);
    } else {
      alarm_.set(interp::alarm::kSkipInput,
                 "G31: no axis this channel commands has its touch probe on input %d", input_);
    }
    return SkipArming::alarm;
  }
  if (armed) {
    if (multi_ && torque_axis_ < feedback.size()) {
      seen_count_ = feedback[torque_axis_].probe_count;  // edges count from here
    }
    return SkipArming::armed;
  }
  if (++waited_ > arm_cycles_) {
    if (load_ != 0) {
      alarm_.set(kAlarmProbeNotArmed, "G31 P%d: the torque limits of its axes did not arm", load_);
    } else if (torque_) {
      alarm_.set(kAlarmProbeNotArmed, "G160: the torque limit of axis %d did not arm", axis);
    } else {
      alarm_.set(kAlarmProbeNotArmed, "G31: the touch probe on input %d did not arm", input_);
    }
    return SkipArming::alarm;
  }
  return SkipArming::waiting;
}

bool SkipProbe::watch(std::span<const AxisFeedbackView> feedback, std::uint32_t probes) noexcept {
  if (phase_ != SkipPhase::moving) {
    return false;
  }
  for (std::size_t i = 0; i < axis_count_ && i < feedback.size() && i < kMaxAxes; ++i) {
    if (((probes >> i) & 1U) != 0 && feedback[i].probe == ProbeSeen::latched) {
      // The latching axis where its drive latched it, the others where they stood in the same
      // feedback.
      for (std::size_t j = 0; j < axis_count_ && j < feedback.size() && j < kMaxAxes; ++j) {
        skip_at_[j] = feedback[j].act;
      }
      skip_at_[i] = feedback[i].probe_pos;
      skipped_ = true;
      phase_ = SkipPhase::stopping;
      return true;
    }
  }
  return false;
}

}  // namespace mcnc::coordination
