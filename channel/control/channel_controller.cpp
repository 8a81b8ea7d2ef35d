#include "channel/control/channel_controller.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <utility>

namespace mcnc::channel {

ChannelController::ChannelController(ChannelSetup setup, interp::CommandSource& source,
                                     motion::MotionPlanner& planner)
    : setup_(std::move(setup)),
      source_(source),
      planner_(planner),
      queued_(std::max<std::size_t>(planner.window_blocks(), 1) + 8),
      coordination_(setup_, *this, out_, commanded_, queued_) {}

void ChannelController::axis_lost(std::size_t axis) noexcept {
  if (lost_axis_ == 0) {
    lost_axis_ = axis + 1;
  }
}

void ChannelController::tell_lost_axis() noexcept {
  if (lost_axis_ != 0 && !lost_axis_told_ && out_.state != ChannelState::alarm) {
    lost_axis_told_ = true;
    raise(kAlarmAxisLost,
          lost_axis_ > setup_.axis_count ? "spindle node lost: no feedback"
                                         : "axis node lost: no feedback",
          out_.line, 0, static_cast<int>(lost_axis_));
  }
}

void ChannelController::set_single_block(bool on) noexcept {
  single_block_ = on;
  planner_.set_single_block(on);
}

void ChannelController::set_feed_override(double percent) noexcept {
  feed_override_ =
      std::isfinite(percent) ? std::clamp(percent, 0.0, 200.0) / 100.0 : feed_override_;
}

void ChannelController::set_rapid_override(double percent) noexcept {
  rapid_override_ =
      std::isfinite(percent) ? std::clamp(percent, 0.0, 100.0) / 100.0 : rapid_override_;
}

void ChannelController::set_spindle_override(double percent) noexcept {
  spindle_override_ =
      std::isfinite(percent) ? std::clamp(percent, 50.0, 120.0) / 100.0 : spindle_override_;
}

void ChannelController::set_state(ChannelState state) noexcept {
  if (out_.state == state) {
    return;
  }
  // A run starts (from idle or reset) or a reset ends one: what was asked for before is stale.
  const bool starts = state == ChannelState::running &&
                      (out_.state == ChannelState::idle || out_.state == ChannelState::reset);
  run_epoch_ += starts || state == ChannelState::reset ? 1 : 0;
  out_.state = state;
  if (state == ChannelState::idle || state == ChannelState::reset || state == ChannelState::alarm) {
    coordination_.leave_position_control();
  }
  ChannelEvent event;
  event.kind = ChannelEventKind::state_changed;
  event.state = state;
  out_.add_event(event);
}

void ChannelController::raise(int number, const char* text, int line, int column, int axis,
                              std::string_view file) noexcept {
  alarm_.number = number;
  std::snprintf(alarm_.text.data(), alarm_.text.size(), "%s", text);
  if (file.empty()) {
    alarm_.file = out_.file;
  } else {
    std::snprintf(alarm_.file.data(), alarm_.file.size(), "%.*s", static_cast<int>(file.size()),
                  file.data());
  }
  alarm_.line = line;
  alarm_.column = column;
  alarm_.axis = axis;
  ++alarm_count_;
  ChannelEvent event;
  event.kind = ChannelEventKind::alarm;
  event.line = line;
  event.alarm_number = number;
  out_.add_event(event);
  set_state(ChannelState::alarm);
  halted_ = true;
  coordination_.on_alarm();  // a caller waiting for its G145 stops too; it takes no axis
}

void ChannelController::raise_program_alarm(const interp::ProgramAlarm& alarm) noexcept {
  raise(alarm.number, alarm.text.c_str(), alarm.line, alarm.column, 0, alarm.program);
}

bool ChannelController::all_enabled(std::span<const AxisFeedbackView> feedback) const noexcept {
  for (std::size_t i = 0; i < setup_.axis_count + setup_.spindle_count; ++i) {
    if (i >= feedback.size() || !feedback[i].present || !feedback[i].enabled || feedback[i].alarm) {
      return false;
    }
  }
  return true;
}

bool ChannelController::in_position(std::span<const AxisFeedbackView> feedback,
                                    const AxisVector& at) const noexcept {
  // An oscillating axis (G81.1) never stands still: its stroke is not the path's to wait for.
  const std::uint32_t oscillating = planner_.output().oscillating;
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    if (i >= feedback.size()) {
      return false;
    }
    if ((oscillating >> i) & 1U) {
      continue;
    }
    // Under a G160 torque limit the axis may press against what holds it, its command beyond
    // by up to Q: it stands where it is held (decision 101).
    const double width = i < setup_.in_position.size() ? setup_.in_position[i] : 0.0;
    // A cam's slave (G51.8) never stands while the lift moves it: the path's part of its
    // command is what must have arrived.
    const bool cam =
        setup_.cam.master != 0 && i == setup_.cam.slave_slot && feedback[i].coupled_to != 0;
    // So does the EGB's work axis (G81.4) while it turns with the tool; stopped, it stands
    // where the channel commands it plus the offset the gear box left.
    const bool egb = setup_.egb.tool != 0 && i == setup_.egb.work_slot;
    const double now = cam || (egb && feedback[i].coupled_to != 0)
                           ? feedback[i].channel_cmd()
                           : feedback[i].act - (egb ? feedback[i].superimposed : 0.0);
    // In torque mode (G10 L14 P10) the node's command follows the motor wherever it stops.
    if (coordination_.torque_limit(i) == 0.0 && !coordination_.in_torque_mode(i) &&
        std::fabs(now - at[i]) > width) {
      return false;
    }
  }
  return true;
}

void ChannelController::hold_outputs(bool valid) noexcept {
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    out_.setpoints[i] = CommandedAxis{commanded_[i], 0.0, 0.0, valid};
  }
}

void ChannelController::forget_program_run() noexcept {
  coordination_.abandon_run();
  mdi_run_ = false;
  spindle_queued_ = 0;  // a program (re)starts with its spindle stopped
  halted_ = false;
  queued_.clear();
  end_pulled_ = false;
  end_started_ = false;
  source_alarm_.reset();
  out_.keep_file(nullptr);  // no block of the run has started
  out_.program_end = false;
  out_.end_code = -1;
}

void ChannelController::finish_reset() noexcept {
  resetting_ = false;
  source_.abandon();
  coordination_.stop_serving(CallOutcome::aborted);  // its caller goes on with an alarm
  coordination_.release_polygon();
  coordination_.cancel_programmed_torque_limits();
  if (setup_.reset_leaves_torque_mode) {
    coordination_.leave_torque_mode();  // param 5520.1
  }
  forget_program_run();
  halted_ = estopped_;  // an emergency stop stays
  pending_alarm_.reset();
  out_.block = 0;
  out_.line = 0;
  position_known_ = false;  // re-read where the axes are once they are enabled again
  after_reset_ = true;
  set_state(ChannelState::reset);
}

const CycleOutput& ChannelController::cycle(std::uint64_t cycle,
                                            std::span<const AxisFeedbackView> feedback) noexcept {
  out_.event_count = 0;
  coordination_.begin_cycle(feedback);
  run_cycle(cycle, coordination_.views());
  coordination_.end_cycle();
  return out_;
}

const CycleOutput& ChannelController::run_cycle(
    std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept {
  if (out_.state != ChannelState::hold && out_.state != ChannelState::waiting) {
    out_.spindle_rpm = 0.0;  // running sets it again; a feed hold keeps the spindle turning
    out_.spindle_direction = 0;
  }
  if (first_cycle_) {
    first_cycle_ = false;
    ChannelEvent initial;
    initial.kind = ChannelEventKind::state_changed;
    initial.state = out_.state;
    out_.add_event(initial);
  }
  if (pending_alarm_) {
    raise_program_alarm(*pending_alarm_);
    pending_alarm_.reset();
  }
  take_calls(cycle);
  // The operator's feed hold and cycle start (in hold), in the cycle they come: a channel that
  // does not run keeps no hold for later.
  if (hold_requested_ && out_.state == ChannelState::running) {
    set_state(ChannelState::hold);
  } else if (resume_requested_ && out_.state == ChannelState::hold) {
    set_state(ChannelState::running);
    planner_.resume();  // a single block stop goes on too
  }
  hold_requested_ = false;
  resume_requested_ = false;
  if (const char* why = coordination_.take_loss();
      why != nullptr && out_.state != ChannelState::alarm) {
    raise(kAlarmCoordinationLost, why, out_.line, 0, 0);
  }

  // Across hosts a lost axis or partner and the launchers' E-stop for the host that went come
  // together, in either order: the loss is still told, which axis or channel went.
  if (estop_requested_) {
    coordination_.run_held_if_partner_lost(cycle, feedback);
  }
  if (estop_requested_ || estopped_) {
    tell_lost_axis();
  }
  if (estop_requested_) {
    // Latched in any state, also before the axes came up: reset, and stay there.
    estop_requested_ = false;
    estopped_ = true;
    halted_ = true;
    resetting_ = false;  // no reset ramp after an emergency stop: the drives stop themselves
    start_requested_ = false;
    mdi_requested_ = false;
    coordination_.stop_serving(CallOutcome::aborted);
    coordination_.withdraw_waits();
    coordination_.release_polygon();
    set_state(ChannelState::reset);
    position_known_ = false;  // the drives stop on their own ramps; re-read before moving again
  }
  if (reset_requested_) {
    reset_requested_ = false;
    hold_requested_ = false;
    resume_requested_ = false;
    if ((out_.state == ChannelState::running || out_.state == ChannelState::hold) &&
        !planner_.at_rest()) {
      planner_.reset();  // ramp down first
      resetting_ = true;
    } else {
      finish_reset();
    }
  }
  if (resetting_) {
    const motion::MotionOutput& m = planner_.step(motion::CycleInput{});
    for (std::size_t i = 0; i < setup_.axis_count; ++i) {
      commanded_[i] = m.sample.pos[i];
      out_.setpoints[i] = CommandedAxis{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
    }
    if (!planner_.at_rest() && m.state != motion::MotionState::fault) {
      return out_;
    }
    finish_reset();
  }
  if ((out_.state == ChannelState::reset || out_.state == ChannelState::alarm) && halted_) {
    hold_outputs(false);
    return out_;
  }

  // An axis alarm or a lost axis stops the channel in any state (after a reset: once the axes
  // are back).
  if (out_.state != ChannelState::alarm && !after_reset_) {
    for (std::size_t i = 0; i < setup_.axis_count + setup_.spindle_count && i < feedback.size();
         ++i) {
      if (feedback[i].alarm) {
        char text[96];
        if (i < setup_.axis_count) {
          std::snprintf(text, sizeof text, "axis %zu of the channel has an alarm: motion stopped",
                        i + 1);
        } else {
          std::snprintf(text, sizeof text,
                        "spindle %zu of the channel has an alarm: motion stopped",
                        i - setup_.axis_count + 1);
        }
        raise(kAlarmAxisAlarm, text, out_.line, 0, static_cast<int>(i + 1));
        break;
      }
    }
    tell_lost_axis();
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
      commanded_[i] = feedback[i].channel_cmd();
    }
    position_known_ = true;
    after_reset_ = false;
    if (out_.state == ChannelState::reset) {
      set_state(ChannelState::idle);
    }
  }

  if (const auto* refusal = coordination_.calls().take_refusal(); refusal != nullptr && in_run()) {
    raise(*refusal, out_.line);  // a call without wait (H0) its target refused
  }
  if (out_.state == ChannelState::idle && start_requested_ && !program_pending_) {
    start_requested_ = false;
    coordination_.settle_slots();
    coordination_.take_gear_box_angle();
    // A start builds the run's interpreter (the allocation a start makes): out of memory is an
    // alarm, not the end of the process. An alarm of the blocks themselves comes as the
    // source's first pull, as a program's does.
    bool out_of_memory = false;
    try {
      if (mdi_requested_) {
        (void)source_.start_mdi(commanded_);
      } else {
        source_.rewind(commanded_);
      }
    } catch (...) {
      out_of_memory = true;
    }
    planner_.restart(commanded_);
    forget_program_run();
    mdi_run_ = mdi_requested_;
    mdi_requested_ = false;
    single_block_stop_ = 0;
    out_.run_start_cycle = cycle;
    set_state(ChannelState::running);
    if (out_of_memory) {
      raise(kAlarmPlannerRejected, "the interpreter ran out of memory", out_.line, 0, 0);
    }
  }

  const bool in_program = out_.state == ChannelState::running ||
                          out_.state == ChannelState::waiting || out_.state == ChannelState::hold;
  if (in_program) {
    run_blocks(cycle, feedback);
  }
  if (out_.state != ChannelState::running && out_.state != ChannelState::waiting &&
      out_.state != ChannelState::hold) {
    hold_outputs(out_.state != ChannelState::reset);
  }
  return out_;
}

// Pulls what the look-ahead takes: up to the window, the program end or an alarm. A bad block
// is an alarm only when the blocks before it have run (what a control shows when it gets there);
// it never reaches the planner. Past `pulls_before_settled` a cycle it pulls on only while more
// blocks could change the next cycle's motion: the planner's push is the costliest part of a
// cycle, and a refill of the whole 64 after a read-ahead stop was the longest cycle.
void ChannelController::fill(std::uint64_t cycle) noexcept {
  // The interpreter allocates (its strings, its call stack): the only thing in the cycle that
  // can throw. Out of memory stops the program with an alarm rather than the process.
  try {
    for (std::size_t k = 0;
         k < setup_.pulls_per_cycle && !end_pulled_ && !source_alarm_ && !coordination_.holds() &&
         planner_.accepts() && !queued_.full() && source_.ready();
         ++k) {
      if (k >= setup_.pulls_before_settled && k % setup_.pulls_before_settled == 0 &&
          !planner_.window_end_binds()) {
        return;
      }
      // Read where the source holds it (the read-ahead's ring): a command is not copied.
      const interp::PullResult* pulled = source_.take();
      if (pulled == nullptr) {
        source_alarm_ = interp::ProgramAlarm{kAlarmPlannerRejected,
                                             "program ended without M30 or M02", "", out_.line, 0};
        return;
      }
      if (const auto* alarm = std::get_if<interp::ProgramAlarm>(pulled)) {
        source_alarm_ = *alarm;
        return;
      }
      const auto* c = std::get_if<interp::Command>(pulled);
      if (c == nullptr) {
        return;
      }
      if (c->op == interp::Op::end) {
        end_ = *c;
        end_pulled_ = true;
        return;
      }
      if (auto away = coordination_.foreign_move(planner_.queue_end(), *c)) {
        source_alarm_ = std::move(away);
        return;
      }
      const StopRules rules{
          setup_.channel_id,
          setup_.slots,
          setup_.plc,
          setup_.spindle_may_follow,
          {setup_.speed_arrival_rpm, setup_.speed_arrival_timeout_s, setup_.cycle_s}};
      if (coordination_.hold(read_ahead_stop(*c, rules, spindle_queued_, source_alarm_)) ||
          coordination_.hold_cut_until_locked(*c, cycle)) {
        return;
      }
      if (source_alarm_ || !queue_command(*c)) {
        return;
      }
    }
  } catch (...) {
    raise(kAlarmPlannerRejected, "the interpreter ran out of memory", out_.line, 0, 0);
  }
}

bool ChannelController::queue_command(const interp::Command& c) noexcept {
  const AxisVector start = planner_.queue_end();  // where the block starts
  if (planner_.push(c) != motion::PushResult::accepted) {
    source_alarm_ = interp::ProgramAlarm{
        kAlarmPlannerRejected, "block cannot be planned (feed or target invalid)", "", c.line, 0};
    return false;
  }
  queued_.push(c, start);
  return true;
}

// Block events in program order, each block's end before the next one's start. Events that do
// not fit in this cycle's output come in the next.
void ChannelController::block_events(const motion::MotionOutput& m,
                                     std::span<const AxisFeedbackView> feedback) noexcept {
  constexpr std::size_t kKeepFree = 4;  // for a program end in the same cycle
  while (out_.event_count + kKeepFree < CycleOutput::kMaxEvents) {
    const BlockQueue::Due due = queued_.due(m, planner_.idle());
    const QueuedBlock& q = queued_.front();
    if (due == BlockQueue::Due::none ||
        (due == BlockQueue::Due::end_if_in_position && !in_position(feedback, q.to))) {
      return;
    }
    ChannelEvent event;
    event.line = q.line;
    event.block = q.n;
    if (due == BlockQueue::Due::start) {
      event.kind = ChannelEventKind::block_started;
      event.file = q.file;
      event.text = q.text;
      out_.modal = q.modal;
      coordination_.block_started(q);
      queued_.started();
    } else {
      event.kind = ChannelEventKind::block_ended;
      event.pos = q.to;
      coordination_.block_ended();
      queued_.ended();
    }
    out_.add_event(event);
  }
}

void ChannelController::run_blocks(std::uint64_t cycle,
                                   std::span<const AxisFeedbackView> feedback) noexcept {
  const bool in_pos = in_position(feedback, commanded_);
  if (coordination_.watch_load(feedback)) {
    return;  // overloaded: the axes stay where they were commanded last
  }
  if (coordination_.watch_gear_box(cycle)) {
    return;  // the work axis stopped off its gear: nothing moves on
  }
  fill(cycle);
  coordination_.watch_skip(feedback);
  coordination_.watch_overload(feedback);
  motion::CycleInput input;
  input.in_position = in_pos;
  input.feed_hold = out_.state == ChannelState::hold;
  input.feed_override = feed_override_;
  input.rapid_override = rapid_override_;
  input.spindle_override = spindle_override_;
  const motion::MotionOutput& m = planner_.step(input);
  out_.spindle_rpm = m.spindle_rpm;
  out_.spindle_direction = m.spindle_direction;
  if (m.state == motion::MotionState::fault) {
    raise(kAlarmPlannerRejected, "block cannot be planned (the axes' limits leave no profile)",
          m.line, 0, 0);
    return;
  }
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    commanded_[i] = m.sample.pos[i];
    out_.setpoints[i] = CommandedAxis{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
  }
  if (m.block != 0) {
    out_.block = m.block;
    out_.line = m.line;
  }
  if (coordination_.skip_stopping() && planner_.idle()) {
    // An in-feed an overload stopped presses against what stopped it, its command beyond: the
    // command follows the axis back to where it is held, so that the block ends there and the
    // retract starts from where the tool stands.
    // Once: the planner restarts only where a command moved.
    const std::uint32_t pressed = coordination_.overload_stopped_axes();
    bool followed = false;
    for (std::size_t i = 0; i < setup_.axis_count && i < feedback.size(); ++i) {
      if (((pressed >> i) & 1U) != 0 && commanded_[i] != feedback[i].act) {
        commanded_[i] = feedback[i].act;
        followed = true;
      }
    }
    if (followed) {
      planner_.restart(commanded_, true);
      hold_outputs(true);
    }
    queued_.end_newest_at(commanded_);  // the skipped move ends where it stopped
  }
  block_events(m, feedback);
  if (m.state == motion::MotionState::block_stop && out_.state == ChannelState::running) {
    set_state(ChannelState::hold);  // single block: at the block's end until a cycle start
    single_block_stop_ = m.completed_block;
  }
  if (out_.state == ChannelState::hold || !planner_.idle() || !queued_.empty()) {
    return;  // in feed hold nothing new starts
  }
  // Single block: the motion before a block that moves nothing (the planner ran dry there)
  // stops too, before that block runs.
  if (single_block_ && coordination_.holds_before_motion() &&
      m.completed_block > single_block_stop_) {
    single_block_stop_ = m.completed_block;
    set_state(ChannelState::hold);
    return;
  }
  // Everything pulled so far has run.
  if (coordination_.holds()) {
    coordination_.run_held(cycle, feedback);
    return;
  }
  if (source_alarm_) {
    raise_program_alarm(*source_alarm_);
    source_alarm_.reset();
    return;
  }
  if (end_pulled_) {
    end_program(cycle, in_pos);
  }
}

void ChannelController::end_program(std::uint64_t cycle, bool in_pos) noexcept {
  // MDI blocks that end with their text have no end block of their own: no start, no end.
  const bool end_block = !(mdi_run_ && end_.code == 0);
  end_started_ = end_started_ || !end_block;
  if (!end_started_) {
    end_started_ = true;
    out_.block = end_.n;
    out_.line = end_.line;
    ChannelEvent started;
    started.kind = ChannelEventKind::block_started;
    started.line = end_.line;
    started.file = end_.file;
    started.text = end_.block_text;
    started.block = end_.n;
    out_.add_event(started);
  }
  if (!in_pos) {
    return;  // the program ends when every axis stands in position
  }
  if (end_block) {
    ChannelEvent ended;
    ended.kind = ChannelEventKind::block_ended;
    ended.line = end_.line;
    ended.block = end_.n;
    ended.pos = commanded_;
    out_.add_event(ended);
  }
  // MDI blocks are no program: their end is no program end (the launcher's run goes on).
  const bool mdi = mdi_run_;
  mdi_run_ = false;
  if (!mdi) {
    out_.program_end = true;
    out_.end_code = end_.code;
    out_.end_cycle = cycle;
  }
  ChannelEvent end;
  end.kind = mdi ? ChannelEventKind::mdi_end : ChannelEventKind::program_end;
  end.line = end_.line;
  end.end_code = end_.code;
  out_.add_event(end);
  set_state(ChannelState::idle);
  if (coordination_.calls().served() != nullptr) {
    coordination_.release_caller(CallOutcome::released);  // without G145 too
    if (coordination_.calls().repeat_served()) {
      start_served_call(cycle);
    }
  }
}

void ChannelController::take_calls(std::uint64_t cycle) noexcept {
  coordination::SubCall& calls = coordination_.calls();
  for (const CallRequest& call : calls.incoming()) {
    const bool free = calls.served() == nullptr && out_.state == ChannelState::idle &&
                      position_known_ && !halted_ && !reset_requested_ && !estop_requested_ &&
                      !start_requested_;
    if (!free) {
      coordination_.push_release(calls.refusal(call));
      continue;
    }
    calls.serve(call);
    start_served_call(cycle);
  }
  calls.clear_incoming();
}

void ChannelController::start_served_call(std::uint64_t cycle) noexcept {
  const CallRequest& call = coordination_.calls().served()->call;
  std::optional<interp::ProgramAlarm> alarm;
  // Loading the called program reads and parses it (on the read-ahead thread, or here for a
  // source that computes on the caller's thread): out of memory is an alarm.
  try {
    std::array<std::pair<int, double>, interp::kSubcallArgs> args{};
    std::size_t given = 0;
    for (int n = 1; n <= interp::kSubcallArgs; ++n) {
      if ((call.args_given >> (n - 1)) & 1U) {
        args[given++] = {n, call.args[static_cast<std::size_t>(n - 1)]};
      }
    }
    coordination_.settle_slots();
    alarm = source_.call(call.program, std::span(args.data(), given), commanded_);
  } catch (...) {
    alarm =
        interp::ProgramAlarm{kAlarmPlannerRejected, "the interpreter ran out of memory", "", 0, 0};
  }
  planner_.restart(commanded_);
  forget_program_run();
  out_.run_start_cycle = cycle;
  set_state(ChannelState::running);
  if (alarm) {
    raise_program_alarm(*alarm);
  }
}

void ChannelController::restart_at_commanded() noexcept {
  source_.adopt_position(commanded_);
  planner_.restart(commanded_, true);  // an oscillating axis goes on
  hold_outputs(true);  // this cycle's setpoints came from the planner before it knew
}

}  // namespace mcnc::channel
