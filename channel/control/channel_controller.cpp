#include "channel/control/channel_controller.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace mcnc::channel {

const char* to_string(ChannelState state) noexcept {
  switch (state) {
    case ChannelState::reset:
      return "reset";
    case ChannelState::idle:
      return "idle";
    case ChannelState::running:
      return "running";
    case ChannelState::hold:
      return "hold";
    case ChannelState::waiting:
      return "waiting";
    case ChannelState::alarm:
      return "alarm";
  }
  return "reset";
}

ChannelController::ChannelController(ChannelSetup setup, interp::CommandSource& source,
                                     motion::BlockPlanner& planner)
    : setup_(std::move(setup)), source_(source), planner_(planner) {}

void ChannelController::axis_lost(std::size_t axis) noexcept {
  if (lost_axis_ == 0) {
    lost_axis_ = axis + 1;
  }
}

void ChannelController::set_state(ChannelState state) noexcept {
  if (out_.state == state) {
    return;
  }
  out_.state = state;
  ChannelEvent event;
  event.kind = ChannelEventKind::state_changed;
  event.state = state;
  push_event(event);
}

void ChannelController::push_event(const ChannelEvent& event) noexcept {
  if (out_.event_count < ChannelOutput::kMaxEvents) {
    out_.events[out_.event_count++] = event;
  }
}

void ChannelController::raise(int number, const char* text, int line, int column,
                              int axis) noexcept {
  alarm_.number = number;
  std::snprintf(alarm_.text.data(), alarm_.text.size(), "%s", text);
  alarm_.line = line;
  alarm_.column = column;
  alarm_.axis = axis;
  ++alarm_count_;
  ChannelEvent event;
  event.kind = ChannelEventKind::alarm;
  event.line = line;
  event.alarm_number = number;
  push_event(event);
  set_state(ChannelState::alarm);
  phase_ = Phase::done;
}

void ChannelController::raise_program_alarm(const interp::ProgramAlarm& alarm) noexcept {
  raise(alarm.number, alarm.text.c_str(), alarm.line, alarm.column, 0);
}

bool ChannelController::all_enabled(std::span<const AxisFeedbackView> feedback) const noexcept {
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    if (i >= feedback.size() || !feedback[i].present || !feedback[i].enabled) {
      return false;
    }
  }
  return true;
}

bool ChannelController::in_position(std::span<const AxisFeedbackView> feedback) const noexcept {
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    if (i >= feedback.size()) {
      return false;
    }
    const double width = i < setup_.in_position.size() ? setup_.in_position[i] : 0.0;
    if (std::fabs(feedback[i].act - commanded_[i]) > width) {
      return false;
    }
  }
  return true;
}

void ChannelController::hold_outputs(bool valid) noexcept {
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    out_.setpoints[i] = AxisSetpointOut{commanded_[i], 0.0, 0.0, valid};
  }
}

const ChannelOutput& ChannelController::cycle(std::uint64_t cycle,
                                              std::span<const AxisFeedbackView> feedback) noexcept {
  out_.event_count = 0;
  if (first_cycle_) {
    first_cycle_ = false;
    ChannelEvent initial;
    initial.kind = ChannelEventKind::state_changed;
    initial.state = out_.state;
    push_event(initial);
  }
  if (pending_alarm_) {
    raise_program_alarm(*pending_alarm_);
    pending_alarm_.reset();
  }

  if (estop_requested_) {
    // Latched in any state, also before the axes came up: reset, and stay there.
    estop_requested_ = false;
    phase_ = Phase::done;
    start_requested_ = false;
    set_state(ChannelState::reset);
    position_known_ = false;  // the drives stop on their own ramps; re-read before moving again
  }
  if ((out_.state == ChannelState::reset || out_.state == ChannelState::alarm) &&
      phase_ == Phase::done) {
    hold_outputs(false);
    return out_;
  }

  // An axis alarm or a lost axis stops the channel in any state.
  if (out_.state != ChannelState::alarm) {
    for (std::size_t i = 0; i < setup_.axis_count && i < feedback.size(); ++i) {
      if (feedback[i].alarm) {
        char text[96];
        std::snprintf(text, sizeof text, "axis %zu of the channel has an alarm: motion stopped",
                      i + 1);
        raise(kAlarmAxisAlarm, text, current_.line, 0, static_cast<int>(i + 1));
        break;
      }
    }
    if (lost_axis_ != 0 && out_.state != ChannelState::alarm) {
      raise(kAlarmAxisLost, "axis node lost: no feedback", current_.line, 0,
            static_cast<int>(lost_axis_));
    }
  }
  if (out_.state == ChannelState::alarm) {
    hold_outputs(position_known_);
    return out_;
  }

  // Until every axis reports in, the channel does not know where it is and commands nothing.
  if (!position_known_) {
    if (!all_enabled(feedback)) {
      hold_outputs(false);
      return out_;
    }
    for (std::size_t i = 0; i < setup_.axis_count; ++i) {
      commanded_[i] = feedback[i].cmd;
    }
    position_known_ = true;
    if (out_.state == ChannelState::reset) {
      set_state(ChannelState::idle);
    }
  }

  if (out_.state == ChannelState::idle && start_requested_) {
    start_requested_ = false;
    source_.rewind(commanded_);
    phase_ = Phase::fetch;
    out_.program_end = false;
    out_.end_code = -1;
    out_.run_start_cycle = cycle;
    set_state(ChannelState::running);
  }

  if (out_.state == ChannelState::running) {
    run_blocks(cycle, feedback);
  }
  if (out_.state != ChannelState::running) {
    hold_outputs(out_.state != ChannelState::reset);
  }
  return out_;
}

void ChannelController::run_blocks(std::uint64_t cycle,
                                   std::span<const AxisFeedbackView> feedback) noexcept {
  // A few zero-time blocks may finish in one cycle; the bound keeps the cycle short.
  for (int guard = 0; guard < 16 && out_.state == ChannelState::running; ++guard) {
    switch (phase_) {
      case Phase::fetch: {
        auto pulled = source_.next();
        if (!pulled) {
          raise(kAlarmPlannerRejected, "program ended without M30 or M02", current_.line, 0, 0);
          return;
        }
        if (const auto* alarm = std::get_if<interp::ProgramAlarm>(&*pulled)) {
          raise_program_alarm(*alarm);
          return;
        }
        current_ = std::get<interp::CanonicalCommand>(*pulled);
        out_.block = current_.block;
        out_.line = current_.line;
        ChannelEvent started;
        started.kind = ChannelEventKind::block_started;
        started.line = current_.line;
        started.block = current_.block;
        push_event(started);
        if (current_.kind == interp::CommandKind::program_end) {
          phase_ = Phase::ending;
          continue;
        }
        if (!planner_.begin(current_, commanded_)) {
          raise(kAlarmPlannerRejected, "block cannot be planned (feed or target invalid)",
                current_.line, 0, 0);
          return;
        }
        phase_ = Phase::moving;
        continue;
      }
      case Phase::moving: {
        motion::MotionSample sample;
        const motion::StepResult result = planner_.step(setup_.cycle_s, sample);
        for (std::size_t i = 0; i < setup_.axis_count; ++i) {
          commanded_[i] = sample.pos[i];
          out_.setpoints[i] = AxisSetpointOut{sample.pos[i], sample.vel[i], sample.acc[i], true};
        }
        if (result == motion::StepResult::block_done) {
          phase_ = Phase::settling;
        }
        return;  // one motion sample per cycle
      }
      case Phase::settling:
      case Phase::ending: {
        hold_outputs(true);
        if (!in_position(feedback)) {
          return;  // exact stop: wait for every axis inside its in-position width
        }
        ChannelEvent ended;
        ended.kind = ChannelEventKind::block_ended;
        ended.line = current_.line;
        ended.block = current_.block;
        ended.pos = commanded_;
        push_event(ended);
        if (phase_ == Phase::ending) {
          out_.program_end = true;
          out_.end_code = current_.end_code;
          out_.end_cycle = cycle;
          ChannelEvent end;
          end.kind = ChannelEventKind::program_end;
          end.line = current_.line;
          end.end_code = current_.end_code;
          push_event(end);
          phase_ = Phase::done;
          set_state(ChannelState::idle);
          return;
        }
        phase_ = Phase::fetch;
        continue;
      }
      case Phase::done:
        return;
    }
  }
}

}  // namespace mcnc::channel
