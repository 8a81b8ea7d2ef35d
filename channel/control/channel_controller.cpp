#include "channel/control/channel_controller.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>

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

const char* to_string(CallOutcome outcome) noexcept {
  switch (outcome) {
    case CallOutcome::released:
      return "released";
    case CallOutcome::refused:
      return "refused";
    case CallOutcome::failed:
      return "failed";
    case CallOutcome::aborted:
      return "aborted";
  }
  return "released";
}

const char* to_string(AxisRequestKind kind) noexcept {
  switch (kind) {
    case AxisRequestKind::release:
      return "release";
    case AxisRequestKind::acquire:
      return "acquire";
    case AxisRequestKind::restore:
      return "restore";
    case AxisRequestKind::withdraw:
      return "withdraw";
  }
  return "release";
}

ChannelController::ChannelController(ChannelSetup setup, interp::CommandSource& source,
                                     motion::MotionPlanner& planner)
    : setup_(std::move(setup)), source_(source), planner_(planner), barrier_(setup_.channel_id) {
  queued_.resize(std::max<std::size_t>(planner.window_blocks(), 1) + 8);
  for (std::size_t i = 0; i < setup_.slots.size() && i < slot_use_.size(); ++i) {
    const AxisSlot& slot = setup_.slots[i];
    slot_use_[i] = slot.exchange_slot      ? SlotUse::virtual_axis
                   : slot.follows_at_start ? SlotUse::follows
                                           : SlotUse::commanded;
  }
  if (setup_.spindle_c_slot && *setup_.spindle_c_slot < slot_use_.size()) {
    slot_use_[*setup_.spindle_c_slot] = SlotUse::speed_control;  // the spindle starts turnable
  }
}

void ChannelController::axis_lost(std::size_t axis) noexcept {
  if (lost_axis_ == 0) {
    lost_axis_ = axis + 1;
  }
}

void ChannelController::on_arrival(const coordination::SyncArrival& arrival) noexcept {
  (void)barrier_.on_arrival(arrival);  // a full table makes the next evaluation an alarm
}

void ChannelController::set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept {
  if (channel < 1 || channel > coordination::kMaxChannels) {
    return;
  }
  partners_[channel] = status;
  const bool automatic =
      status.known && (status.state == ChannelState::running ||
                       status.state == ChannelState::hold || status.state == ChannelState::waiting);
  active_.set(channel, automatic);
  halted_partners_.set(channel, status.known && status.state == ChannelState::alarm);
  // A call of ours the target now runs: from here its status says whose call it runs.
  if (outstanding_[channel] != 0 && status.call_id == outstanding_[channel]) {
    outstanding_[channel] = 0;
  }
}

void ChannelController::on_call(const SubCall& call) noexcept {
  if (incoming_count_ < kMaxIncoming) {
    incoming_[incoming_count_++] = call;
  } else {
    push_release(CallRelease{call.call_id, call.caller, setup_.channel_id, CallOutcome::refused});
  }
}

void ChannelController::on_call_release(const CallRelease& release) noexcept {
  for (std::uint64_t& o : outstanding_) {
    if (o == release.call_id) {
      o = 0;
    }
  }
  if (call_block_ && call_block_->phase == CallPhase::sent &&
      call_block_->call.call_id == release.call_id) {
    call_ended_ = release;
  } else if (release.outcome == CallOutcome::refused) {
    refused_ = release;  // a call without wait: an alarm all the same
  }
}

void ChannelController::on_aux_answer(const AuxAnswer& answer) noexcept {
  if (aux_block_ && aux_block_->sent && aux_block_->request.id == answer.id) {
    aux_answer_ = answer;
  }  // else the answer to a request a reset abandoned
}

void ChannelController::plc_lost() noexcept {
  plc_lost_ = true;
}

void ChannelController::partner_lost(std::uint32_t channel) noexcept {
  if (channel >= 1 && channel <= coordination::kMaxChannels) {
    lost_partners_.set(channel);
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
    leave_position_control();
  }
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
  halted_ = true;
  release_caller(CallOutcome::failed);  // a caller waiting for this channel's G145 stops too
  withdraw_waits();                     // a stopped channel does not take an axis
}

void ChannelController::raise_program_alarm(const interp::ProgramAlarm& alarm) noexcept {
  raise(alarm.number, alarm.text.c_str(), alarm.line, alarm.column, 0);
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
  for (std::size_t i = 0; i < setup_.axis_count; ++i) {
    if (i >= feedback.size()) {
      return false;
    }
    const double width = i < setup_.in_position.size() ? setup_.in_position[i] : 0.0;
    if (std::fabs(feedback[i].act - at[i]) > width) {
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

void ChannelController::forget_program_run() noexcept {
  withdraw_waits();
  mdi_run_ = false;
  exchange_block_.reset();
  aux_block_.reset();
  aux_answer_.reset();
  coupling_block_.reset();
  control_block_.reset();
  skip_block_.reset();
  wait_block_.reset();
  spindle_queued_ = 0;  // a program (re)starts with its spindle stopped
  halted_ = false;
  queued_head_ = 0;
  queued_count_ = 0;
  queued_started_ = 0;
  end_pulled_ = false;
  end_started_ = false;
  source_alarm_.reset();
  sync_block_.reset();
  sync_arrived_ = false;
  barrier_.cancel();
  call_block_.reset();
  call_ended_.reset();
  release_block_.reset();
  out_.program_end = false;
  out_.end_code = -1;
}

void ChannelController::finish_reset() noexcept {
  resetting_ = false;
  source_.abandon();
  release_caller(CallOutcome::aborted);  // a caller waiting for this channel goes on with an alarm
  serving_.reset();
  forget_program_run();
  halted_ = estopped_;  // an emergency stop stays
  pending_alarm_.reset();
  out_.block = 0;
  out_.line = 0;
  position_known_ = false;  // re-read where the axes are once they are enabled again
  after_reset_ = true;
  set_state(ChannelState::reset);
}

const ChannelOutput& ChannelController::cycle(std::uint64_t cycle,
                                              std::span<const AxisFeedbackView> feedback) noexcept {
  out_.event_count = 0;
  out_.arrival_due = false;
  out_.call_due = false;
  out_.release_count = 0;
  out_.axis_request_count = 0;
  out_.aux_due = false;
  out_.spindle_sync_due = false;
  out_.axis_sync_due = false;
  const bool was_position = under_position_control();
  received_ = feedback;
  update_slots();
  build_views(feedback);
  run_cycle(cycle,
            std::span<const AxisFeedbackView>(views_.data(), std::min(feedback.size(), kMaxViews)));
  // Only an axis the channel commands follows its setpoints; the others hold where they are.
  for (std::size_t i = 0; i < setup_.axis_count && exchanges(); ++i) {
    if (slot_use_[i] != SlotUse::commanded) {
      out_.setpoints[i].valid = false;
    }
  }
  // G31: the probes on the block's input stay armed while it arms and moves.
  if (skip_block_ && skip_block_->phase != SkipBlock::Phase::stopping && in_run()) {
    for (std::size_t i = 0; i < setup_.axis_count; ++i) {
      if (probe_on_input(i, skip_block_->command.input)) {
        out_.setpoints[i].probe = skip_block_->arm;
      }
    }
  }
  out_.spindle_position = false;
  if (const auto c = setup_.spindle_c_slot; c && slot_use_[*c] == SlotUse::commanded) {
    out_.spindle_position = true;
    out_.setpoints[*c].pos += c_base_;
  } else if (c && was_position) {
    // Position control ended in this cycle (M17, the end, a reset): C's last position still
    // goes out, so the spindle stands where the program put it, not a sample short.
    out_.spindle_position = true;
    out_.setpoints[*c] = AxisSetpointOut{commanded_[*c] + c_base_, 0.0, 0.0, true};
  }
  return out_;
}

const ChannelOutput& ChannelController::run_cycle(
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
    push_event(initial);
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
  const std::uint64_t writes_lost = setup_.shared_writes ? setup_.shared_writes->lost() : 0;
  if ((coordination_lost_ || writes_lost > writes_lost_seen_) &&
      out_.state != ChannelState::alarm) {
    raise(kAlarmCoordinationLost,
          coordination_lost_ ? "events from another channel were lost (receive queue full)"
                             : "shared variable writes were lost (more than the log holds)",
          out_.line, 0, 0);
  }
  coordination_lost_ = false;
  writes_lost_seen_ = writes_lost;

  if (estop_requested_) {
    // Latched in any state, also before the axes came up: reset, and stay there.
    estop_requested_ = false;
    estopped_ = true;
    halted_ = true;
    resetting_ = false;  // no reset ramp after an emergency stop: the drives stop themselves
    start_requested_ = false;
    mdi_requested_ = false;
    release_caller(CallOutcome::aborted);
    serving_.reset();
    withdraw_waits();
    set_state(ChannelState::reset);
    position_known_ = false;  // the drives stop on their own ramps; re-read before moving again
  }
  if (reset_requested_) {
    reset_requested_ = false;
    hold_requested_ = false;
    resume_requested_ = false;
    if ((out_.state == ChannelState::running || out_.state == ChannelState::hold) &&
        !planner_.idle()) {
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
      out_.setpoints[i] = AxisSetpointOut{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
    }
    if (!planner_.idle() && m.state != motion::MotionState::fault) {
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
    if (lost_axis_ != 0 && out_.state != ChannelState::alarm) {
      raise(kAlarmAxisLost,
            lost_axis_ > setup_.axis_count ? "spindle node lost: no feedback"
                                           : "axis node lost: no feedback",
            out_.line, 0, static_cast<int>(lost_axis_));
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
    after_reset_ = false;
    if (out_.state == ChannelState::reset) {
      set_state(ChannelState::idle);
    }
  }

  if (refused_ && (out_.state == ChannelState::running || out_.state == ChannelState::waiting ||
                   out_.state == ChannelState::hold)) {
    char text[96];
    std::snprintf(text, sizeof text, "G144: channel %u refused the call (it was busy)",
                  refused_->target);
    refused_.reset();
    raise(kAlarmCallRefused, text, out_.line, 0, 0);
  }
  refused_.reset();
  if (out_.state == ChannelState::idle && start_requested_ && !program_pending_) {
    start_requested_ = false;
    settle_slots();
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
// it never reaches the planner.
void ChannelController::fill() noexcept {
  // The interpreter allocates (its strings, its call stack): the only thing in the cycle that
  // can throw. Out of memory stops the program with an alarm rather than the process.
  try {
    for (std::size_t k = 0;
         k < setup_.pulls_per_cycle && !end_pulled_ && !source_alarm_ && !sync_block_ &&
         !call_block_ && !release_block_ && !exchange_block_ && !aux_block_ && !coupling_block_ &&
         !control_block_ && !skip_block_ && !wait_block_ && planner_.accepts() &&
         queued_count_ < queued_.size() && source_.ready();
         ++k) {
      auto pulled = source_.next();
      if (!pulled) {
        source_alarm_ = interp::ProgramAlarm{kAlarmPlannerRejected,
                                             "program ended without M30 or M02", "", out_.line, 0};
        return;
      }
      if (const auto* alarm = std::get_if<interp::ProgramAlarm>(&*pulled)) {
        source_alarm_ = *alarm;
        return;
      }
      const auto* c = std::get_if<interp::Command>(&*pulled);
      if (c == nullptr) {
        return;
      }
      if (c->op == interp::Op::end) {
        end_ = *c;
        end_pulled_ = true;
        return;
      }
      if (c->op == interp::Op::sync) {
        // Read-ahead stops here: the interpreter evaluates nothing after the mark until the
        // channel pulls past it (spec dafeng §3.0).
        SyncBlock b;
        b.block = held(*c);
        b.has_p = c->has_p;
        b.p = c->p;
        b.all_channels = c->all_channels;
        for (std::uint32_t ch = 1; ch <= coordination::kMaxChannels; ++ch) {
          b.participants.set(ch, c->has_channel(static_cast<int>(ch)));
        }
        sync_block_ = b;
        return;
      }
      if (c->op == interp::Op::subcall) {
        CallBlock b;
        b.block = held(*c);
        b.call.caller = setup_.channel_id;
        b.call.target = static_cast<std::uint32_t>(c->channel);
        b.call.program = c->program;
        b.call.wait = c->wait;
        b.call.repeat = c->repeat;
        for (const auto& [var, value] : c->args) {
          if (var >= 1 && var <= interp::kSubcallArgs) {
            b.call.args[static_cast<std::size_t>(var - 1)] = value;
            b.call.args_given |= 1U << (var - 1);
          }
        }
        call_block_ = b;
        return;
      }
      if (c->op == interp::Op::subcall_release) {
        release_block_ = held(*c);
        return;
      }
      if (c->op == interp::Op::axis_release || c->op == interp::Op::axis_acquire ||
          c->op == interp::Op::axis_restore) {
        ExchangeBlock b;
        b.block = held(*c);
        b.op = c->op;
        b.force = c->force;
        if (c->op != interp::Op::axis_restore) {
          std::size_t slot = setup_.slots.size();
          for (std::size_t i = 0; i < setup_.slots.size(); ++i) {
            slot = setup_.slots[i].address == c->axis ? i : slot;
          }
          if (slot == setup_.slots.size()) {
            source_alarm_ = interp::ProgramAlarm{
                kAlarmNotOwner,
                std::string("axis ") + c->axis + " of this channel is not exchanged", "", c->line,
                0};
            return;
          }
          b.slot = slot;
        }
        exchange_block_ = b;
        return;
      }
      // A spindle start or reversal asks the PLC; a speed change of a turning spindle does not.
      const bool spindle_start =
          c->op == interp::Op::spindle &&
          ((c->spindle_direction == interp::SpindleDirection::cw && spindle_queued_ != 1) ||
           (c->spindle_direction == interp::SpindleDirection::ccw && spindle_queued_ != -1));
      if (c->op == interp::Op::spindle && c->channel == 0 && c->spindle <= 1) {
        spindle_queued_ = c->spindle_direction == interp::SpindleDirection::cw     ? 1
                          : c->spindle_direction == interp::SpindleDirection::ccw  ? -1
                          : c->spindle_direction == interp::SpindleDirection::keep ? spindle_queued_
                                                                                   : 0;
      }
      if (c->op == interp::Op::spindle_sync || c->op == interp::Op::spindle_unsync) {
        CouplingBlock b;
        b.block = held(*c);
        b.spindle = SpindleSyncOut{c->op == interp::Op::spindle_sync,
                                   c->op == interp::Op::spindle_sync ? c->sync_k : 0, c->sync_p,
                                   c->sync_q, c->sync_r};
        coupling_block_ = b;
        return;
      }
      if (c->op == interp::Op::spindle_mode) {
        ControlBlock b;
        b.block = held(*c);
        b.position = c->position_control;
        control_block_ = b;
        return;
      }
      if (c->op == interp::Op::axis_couple || c->op == interp::Op::axis_decouple) {
        CouplingBlock b;
        b.block = held(*c);
        b.axis = true;
        b.axis_sync.on = c->op == interp::Op::axis_couple;
        b.axis_sync.master = static_cast<std::uint32_t>(c->master);
        b.slave = static_cast<std::uint32_t>(c->slave);
        coupling_block_ = b;
        return;
      }
      if ((setup_.plc && (c->op == interp::Op::aux || c->op == interp::Op::tool)) ||
          (spindle_start && (setup_.plc || setup_.spindle_may_follow))) {
        // Sent when every block before it ended; the next block waits for the answer.
        AuxBlock b;
        b.block = held(*c);
        b.request.kind = c->op == interp::Op::tool ? AuxKind::t_code : AuxKind::m_code;
        b.request.code = c->op == interp::Op::tool ? c->tool * 100 + c->offset
                         : spindle_start
                             ? (c->spindle_direction == interp::SpindleDirection::cw ? 3 : 4)
                             : c->code;
        b.spindle = spindle_start;
        b.command = *c;
        aux_block_ = b;
        return;
      }
      if (const auto away = moves_foreign_slot(*c)) {
        const std::uint32_t owner = *away < received_.size() ? received_[*away].owner : 0;
        char text[160];
        if (slot_use_[*away] == SlotUse::speed_control) {
          std::snprintf(text, sizeof text,
                        "%c is the spindle under speed control: position control first",
                        setup_.slots[*away].address);
          source_alarm_ =
              interp::ProgramAlarm{interp::alarm::kSpindleControl, text, "", c->line, 0};
          return;
        }
        if (slot_use_[*away] == SlotUse::follows) {
          const std::uint32_t master = *away < received_.size() ? received_[*away].coupled_to : 0;
          std::snprintf(text, sizeof text,
                        "%c follows axis %u (G51.4): G50.4 Q%u before the program moves it",
                        setup_.slots[*away].address, master, setup_.slots[*away].id);
          source_alarm_ = interp::ProgramAlarm{kAlarmAxisFollows, text, "", c->line, 0};
          return;
        }
        if (owner == setup_.channel_id) {
          std::snprintf(text, sizeof text,
                        "%c came back to this channel during the program: G141 or G142 takes "
                        "it over before it moves",
                        setup_.slots[*away].address);
        } else {
          std::snprintf(text, sizeof text,
                        "%c is %s%.0u: acquire it (G141) or restore (G142) before moving it",
                        setup_.slots[*away].address,
                        owner == 0 ? "released and no channel has it" : "with channel ", owner);
        }
        source_alarm_ = interp::ProgramAlarm{kAlarmAxisAway, text, "", c->line, 0};
        return;
      }
      if (c->op == interp::Op::wait_input || c->op == interp::Op::wait_spindle) {
        // G04 I / G04 PS stop the read-ahead (spec L6907): the next block waits for them.
        const bool input = c->op == interp::Op::wait_input;
        coordination::ConditionWaitLimits limits;
        limits.width_s = input ? c->width_s : -1.0;
        limits.dwell_s = c->dwell_s;
        limits.timeout_s = input ? c->timeout_s : setup_.speed_arrival_timeout_s;
        wait_block_.emplace(
            WaitBlock{held(*c), *c, coordination::ConditionWait(limits, setup_.cycle_s)});
        return;
      }
      if (c->skip) {
        // G31 stops the read-ahead (spec L6907): its move starts once its probes are armed.
        SkipBlock b;
        b.command = *c;
        b.arm = c->input_on ? ProbeArm::rising : ProbeArm::falling;
        skip_block_ = b;
        return;
      }
      if (!queue_command(*c)) {
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
  QueuedBlock& q = queued_[(queued_head_ + queued_count_) % queued_.size()];
  // A spindle command takes effect where the planner reaches it; as a block it does not move
  // and passes at once.
  const bool spindle = c.op == interp::Op::spindle;
  q = QueuedBlock{
      c.n,
      c.line,
      c.op == interp::Op::dwell || spindle ? start : c.to,
      c.exact_stop || c.op == interp::Op::rapid || c.op == interp::Op::dwell,
      spindle || ((c.op == interp::Op::rapid || c.op == interp::Op::linear) && c.to == start),
      c.file,
      c.block_text,
      c.modal};
  ++queued_count_;
  return true;
}

// Block events in program order, each block's end before the next one's start: a block
// starts when the planner is in it (or past it), ends when the path passed its end (a stop
// there: and every axis is in position); a block that does not move passes at once. Events
// that do not fit in this cycle's output come in the next.
void ChannelController::block_events(const motion::MotionOutput& m,
                                     std::span<const AxisFeedbackView> feedback) noexcept {
  // An idle planner has run everything it took.
  const std::uint64_t done = planner_.idle() ? ~std::uint64_t{0} : m.completed_block;
  constexpr std::size_t kKeepFree = 4;  // for a program end in the same cycle
  while (out_.event_count + kKeepFree < ChannelOutput::kMaxEvents && queued_count_ > 0) {
    const QueuedBlock& q = queued_[queued_head_];
    if (queued_started_ == 0) {
      if (q.n > m.block && q.n > done && !q.still) {
        return;
      }
      ChannelEvent started;
      started.kind = ChannelEventKind::block_started;
      started.line = q.line;
      started.file = q.file;
      started.text = q.text;
      started.block = q.n;
      push_event(started);
      out_.modal = q.modal;
      queued_started_ = 1;
      continue;
    }
    // A block the path stopped at is an exact stop, whatever made it stop (G09/G61, a rapid,
    // a dwell or the program end after it, a corner the look-ahead would not blend).
    const bool stopped_here = q.n == m.completed_block && m.path_velocity <= 0.0;
    if (!q.still &&
        (q.n > done || ((q.exact_stop || stopped_here) && !in_position(feedback, q.to)))) {
      return;
    }
    ChannelEvent ended;
    ended.kind = ChannelEventKind::block_ended;
    ended.line = q.line;
    ended.block = q.n;
    ended.pos = q.to;
    push_event(ended);
    queued_head_ = (queued_head_ + 1) % queued_.size();
    --queued_count_;
    queued_started_ = 0;
  }
}

void ChannelController::run_blocks(std::uint64_t cycle,
                                   std::span<const AxisFeedbackView> feedback) noexcept {
  const bool in_pos = in_position(feedback, commanded_);
  fill();
  watch_skip(feedback);
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
    out_.setpoints[i] = AxisSetpointOut{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
  }
  if (m.block != 0) {
    out_.block = m.block;
    out_.line = m.line;
  }
  if (skip_block_ && skip_block_->phase == SkipBlock::Phase::stopping && planner_.idle() &&
      queued_count_ > 0) {
    // The skipped move ends where it stopped, not at its programmed end.
    queued_[(queued_head_ + queued_count_ - 1) % queued_.size()].to = commanded_;
  }
  block_events(m, feedback);
  if (m.state == motion::MotionState::block_stop && out_.state == ChannelState::running) {
    set_state(ChannelState::hold);  // single block: at the block's end until a cycle start
    single_block_stop_ = m.completed_block;
  }
  if (out_.state == ChannelState::hold || !planner_.idle() || queued_count_ > 0) {
    return;  // in feed hold nothing new starts
  }
  // Single block: the motion before a block that moves nothing (the planner ran dry there)
  // stops too, before that block runs.
  const bool held_block = sync_block_ || call_block_ || exchange_block_ || aux_block_ ||
                          coupling_block_ || control_block_ || release_block_ || wait_block_ ||
                          (skip_block_ && skip_block_->phase == SkipBlock::Phase::arming);
  if (single_block_ && held_block && m.completed_block > single_block_stop_) {
    single_block_stop_ = m.completed_block;
    set_state(ChannelState::hold);
    return;
  }
  // Everything pulled so far has run.
  if (sync_block_) {
    run_sync();
    return;
  }
  if (call_block_) {
    run_call(cycle);
    return;
  }
  if (exchange_block_) {
    run_exchange(cycle);
    return;
  }
  if (aux_block_) {
    run_aux();
    return;
  }
  if (coupling_block_) {
    run_coupling(cycle);
    return;
  }
  if (control_block_) {
    run_control();
    return;
  }
  if (skip_block_) {
    run_skip(feedback);
    return;
  }
  if (wait_block_) {
    run_wait();
    return;
  }
  if (release_block_) {
    // G145: the caller goes on; this program goes on too (spec dafeng §3.4).
    start_held(*release_block_);
    release_caller(CallOutcome::released);  // no caller, or released before: nothing
    push_event(block_event(*release_block_, ChannelEventKind::block_ended));
    release_block_.reset();
    return;
  }
  if (source_alarm_) {
    raise_program_alarm(*source_alarm_);
    source_alarm_.reset();
    return;
  }
  if (!end_pulled_) {
    return;
  }
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
    push_event(started);
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
    push_event(ended);
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
  push_event(end);
  set_state(ChannelState::idle);
  if (serving_) {
    release_caller(CallOutcome::released);  // the end releases a caller without G145 too
    if (serving_->repeats_left > 0) {
      --serving_->repeats_left;
      start_served_call(cycle);
    } else {
      serving_.reset();
    }
  }
}

}  // namespace mcnc::channel

namespace mcnc::channel {

ChannelEvent ChannelController::block_event(const HeldBlock& b,
                                            ChannelEventKind kind) const noexcept {
  ChannelEvent event;
  event.kind = kind;
  event.line = b.line;
  event.file = b.file;
  event.text = b.text;
  event.block = b.n;
  event.pos = commanded_;
  return event;
}

void ChannelController::start_held(HeldBlock& b) noexcept {
  if (b.started) {
    return;
  }
  b.started = true;
  out_.block = b.n;
  out_.line = b.line;
  out_.modal = b.modal;
  push_event(block_event(b, ChannelEventKind::block_started));
}

void ChannelController::run_sync() noexcept {
  SyncBlock& b = *sync_block_;
  if (!sync_arrived_) {
    start_held(b.block);
    if (b.has_p && writes_pending()) {
      return;  // the shared writes before the mark go out first
    }
    if (b.has_p) {
      out_.arrival = barrier_.arrive(b.p, b.participants, b.all_channels);
      out_.arrival_due = true;
      sync_arrived_ = true;
      push_event(block_event(b.block, ChannelEventKind::sync_arrive));
      set_state(ChannelState::waiting);
    }
  }
  if (b.has_p) {
    int number = 0;
    const char* what = nullptr;
    const coordination::SyncState state = barrier_.evaluate(active_, halted_partners_);
    std::uint32_t other = barrier_.conflict_channel();  // the channel a conflict names
    switch (state) {
      case coordination::SyncState::none:
      case coordination::SyncState::waiting: {
        const coordination::ChannelSet gone = barrier_.missing() & lost_partners_;
        if (gone.none()) {
          return;
        }
        other = 1;
        while (!gone.test(other)) {
          ++other;
        }
        number = kAlarmSyncPartnerLost;
        what = "is gone while this channel waits for it";
        break;
      }
      case coordination::SyncState::mismatch:
        number = kAlarmSyncMismatch;
        what = "waits at the same mark with other participants (sync mismatch)";
        break;
      case coordination::SyncState::deadlock:
        number = kAlarmSyncDeadlock;
        what = "waits at another mark that can never be released (sync deadlock)";
        break;
      case coordination::SyncState::full:
        number = kAlarmSyncTableFull;
        what = "has more different marks than the table holds (128)";
        break;
      case coordination::SyncState::released:
        push_event(block_event(b.block, ChannelEventKind::sync_release));
        set_state(ChannelState::running);
        break;
    }
    if (what != nullptr) {
      char text[160];
      std::snprintf(text, sizeof text, "G04.1 P%d: channel %u %s", b.p, other, what);
      raise(number, text, b.block.line, 0, 0);
      return;
    }
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  sync_block_.reset();
  sync_arrived_ = false;
}

}  // namespace mcnc::channel

namespace mcnc::channel {

void ChannelController::push_release(const CallRelease& release) noexcept {
  if (out_.release_count < ChannelOutput::kMaxReleases) {
    out_.releases[out_.release_count++] = release;
  }
  ChannelEvent event;
  event.kind = ChannelEventKind::subcall_release;
  event.call_id = release.call_id;
  event.call_outcome = release.outcome;
  event.line = out_.line;
  push_event(event);
}

void ChannelController::release_caller(CallOutcome outcome) noexcept {
  if (!serving_ || serving_->released) {
    return;
  }
  serving_->released = true;
  push_release(
      CallRelease{serving_->call.call_id, serving_->call.caller, setup_.channel_id, outcome});
}

void ChannelController::take_calls(std::uint64_t cycle) noexcept {
  for (std::size_t i = 0; i < incoming_count_; ++i) {
    const SubCall& call = incoming_[i];
    const bool free = !serving_ && out_.state == ChannelState::idle && position_known_ &&
                      !halted_ && !reset_requested_ && !estop_requested_ && !start_requested_;
    if (!free) {
      push_release(CallRelease{call.call_id, call.caller, setup_.channel_id, CallOutcome::refused});
      continue;
    }
    serving_ = ServedCall{call, std::max(call.repeat, 1) - 1, false};
    start_served_call(cycle);
  }
  incoming_count_ = 0;
}

void ChannelController::start_served_call(std::uint64_t cycle) noexcept {
  const SubCall& call = serving_->call;
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
    settle_slots();
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

bool ChannelController::calls_back(std::uint32_t target) const noexcept {
  // The chain of callers that wait for their call, from this channel's up: each partner's
  // status names its own caller, and a caller that waits is in state waiting. A caller that
  // did not wait (H0) or was released (G145) may be called: it is no circle.
  std::uint32_t caller =
      serving_ && serving_->call.wait && !serving_->released ? serving_->call.caller : 0;
  for (std::size_t step = 0; step < coordination::kMaxChannels && caller != 0; ++step) {
    if (caller == target) {
      return true;
    }
    const PartnerStatus& p =
        caller <= coordination::kMaxChannels ? partners_[caller] : partners_[0];
    const std::uint32_t next = p.known && p.call_id != 0 ? p.call_caller : 0;
    const bool next_waits = next != 0 && next <= coordination::kMaxChannels &&
                            partners_[next].known && partners_[next].state == ChannelState::waiting;
    caller = next_waits ? next : 0;
  }
  return false;
}

void ChannelController::run_call(std::uint64_t cycle) noexcept {
  CallBlock& b = *call_block_;
  start_held(b.block);
  char text[128];
  if (b.phase == CallPhase::reached) {
    const std::uint32_t target = b.call.target;
    if (target == setup_.channel_id || calls_back(target)) {
      std::snprintf(text, sizeof text, "G144 N%u: channel %u %s: a call cycle", target, target,
                    target == setup_.channel_id
                        ? "is this channel"
                        : "waits for the call this channel runs (directly or through others)");
      raise(kAlarmCallCycle, text, b.block.line, 0, 0);
      return;
    }
    const PartnerStatus none{};
    const PartnerStatus& t =
        target >= 1 && target <= coordination::kMaxChannels ? partners_[target] : none;
    const bool outstanding = target <= coordination::kMaxChannels && outstanding_[target] != 0;
    if (target <= coordination::kMaxChannels && lost_partners_.test(target)) {
      std::snprintf(text, sizeof text, "G144 N%u: channel %u is gone", target, target);
      raise(kAlarmCallFailed, text, b.block.line, 0, 0);
      return;
    }
    const bool free = t.known && t.state == ChannelState::idle && t.call_id == 0 && !outstanding;
    if (!free) {
      // Still finishing a call of ours (after its G145, on the way to M99), or not up yet:
      // wait until it is idle (spec dafeng §3.4 decide 1). Anything else is busy.
      const bool finishing_ours = t.known && t.call_id != 0 && t.call_caller == setup_.channel_id &&
                                  t.state != ChannelState::alarm;
      if (outstanding || finishing_ours || !t.known || t.state == ChannelState::reset) {
        if (!b.waiting_for_target) {
          b.waiting_for_target = true;
          b.waiting_since = cycle;
        }
        if (setup_.call_wait_cycles != 0 && cycle - b.waiting_since >= setup_.call_wait_cycles) {
          std::snprintf(text, sizeof text, "G144 N%u: channel %u did not become free in time",
                        target, target);
          raise(kAlarmCallTimeout, text, b.block.line, 0, 0);
          return;
        }
        set_state(ChannelState::waiting);
        return;
      }
      std::snprintf(
          text, sizeof text, "G144 N%u: channel %u is busy (%s)", target, target,
          t.call_id != 0 ? "running a program another channel called" : to_string(t.state));
      raise(kAlarmCallBusy, text, b.block.line, 0, 0);
      return;
    }
    if (writes_pending()) {
      return;  // the called program sees what this channel wrote before the call
    }
    b.call.call_id = (std::uint64_t{setup_.channel_id} << 40) | ++calls_made_;
    outstanding_[target] = b.call.call_id;
    out_.call = b.call;
    out_.call_due = true;
    push_event(block_event(b.block, ChannelEventKind::subcall));
    if (b.call.wait) {
      b.phase = CallPhase::sent;
      set_state(ChannelState::waiting);
      return;
    }
  } else {
    if (!call_ended_ && b.call.target <= coordination::kMaxChannels &&
        lost_partners_.test(b.call.target)) {
      call_ended_ = CallRelease{b.call.call_id, setup_.channel_id, b.call.target,
                                CallOutcome::aborted};  // its process is gone
    }
    if (!call_ended_) {
      return;  // H1: until the called channel's G145 or end
    }
    const CallOutcome outcome = call_ended_->outcome;
    call_ended_.reset();
    if (outcome != CallOutcome::released) {
      std::snprintf(text, sizeof text,
                    outcome == CallOutcome::refused
                        ? "G144: channel %u refused the call (it was busy)"
                        : (outcome == CallOutcome::failed
                               ? "G144: the program called in channel %u stopped with an alarm"
                               : "G144: channel %u was reset before it released this channel"),
                    b.call.target);
      raise(outcome == CallOutcome::refused ? kAlarmCallRefused : kAlarmCallFailed, text,
            b.block.line, 0, 0);
      return;
    }
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  set_state(ChannelState::running);
  call_block_.reset();
}

}  // namespace mcnc::channel

namespace mcnc::channel {

void ChannelController::update_slots() noexcept {
  if (!exchanges()) {
    return;
  }
  for (std::size_t s = 0; s < setup_.axis_count && s < received_.size(); ++s) {
    if (s == setup_.spindle_c_slot) {
      continue;  // the spindle is the channel's for good; run_control() decides
    }
    const AxisFeedbackView& f = received_[s];
    // A borrowed axis granted after the channel stopped waiting for it (its withdraw crossed
    // the grant): given back at once, so that nobody waits for a channel that does not use it.
    const bool asked = exchange_block_ && exchange_block_->sent &&
                       exchange_block_->op == interp::Op::axis_acquire &&
                       exchange_block_->slot == s;
    if (f.present && setup_.slots[s].exchange_slot && slot_use_[s] == SlotUse::virtual_axis &&
        f.owner == setup_.channel_id && !asked && !unasked_released_[s]) {
      unasked_released_[s] = true;
      push_axis_request(AxisRequestKind::release, s, false);
    }
    unasked_released_[s] = unasked_released_[s] && f.owner == setup_.channel_id;
    if (f.present && slot_use_[s] == SlotUse::commanded && setup_.slots[s].may_follow &&
        f.coupled_to != 0) {
      // Its node follows a master (a G51.4 whose block a reset forgot): not the program's.
      slot_use_[s] = SlotUse::follows;
      raise_if_queued_moves(s, "follows another axis (G51.4): this program still moves it");
      continue;
    }
    if (!f.present || slot_use_[s] != SlotUse::commanded || f.owner == setup_.channel_id) {
      continue;
    }
    // Another channel has the axis now (G141 P1 takes it at rest): the channel stops commanding
    // it, and a block still queued that moves it cannot run.
    slot_use_[s] = SlotUse::away;
    char why[64];
    std::snprintf(why, sizeof why, "was taken by channel %u: this program still moves it", f.owner);
    raise_if_queued_moves(s, why);
  }
}

void ChannelController::raise_if_queued_moves(std::size_t s, const char* why) noexcept {
  int moving_line = 0;  // the first queued block that moves it
  for (std::size_t k = 0; k < queued_count_ && moving_line == 0; ++k) {
    const QueuedBlock& q = queued_[(queued_head_ + k) % queued_.size()];
    moving_line = std::fabs(q.to[s] - commanded_[s]) > 1e-9 ? q.line : 0;
  }
  if (moving_line != 0 &&
      (out_.state == ChannelState::running || out_.state == ChannelState::hold)) {
    char text[128];
    std::snprintf(text, sizeof text, "%c %s", setup_.slots[s].address, why);
    raise(slot_use_[s] == SlotUse::follows ? kAlarmAxisFollows : kAlarmAxisAway, text, moving_line,
          0, static_cast<int>(s + 1));
  }
}

void ChannelController::build_views(std::span<const AxisFeedbackView> received) noexcept {
  for (std::size_t i = 0; i < received.size() && i < kMaxViews; ++i) {
    views_[i] = received[i];
    if (i == setup_.spindle_c_slot && slot_use_[i] == SlotUse::commanded) {
      views_[i].cmd -= c_base_;  // the spindle's degrees as C
      views_[i].act -= c_base_;
    }
    if (exchanges() && i < setup_.axis_count && slot_use_[i] != SlotUse::commanded) {
      // Not commanded by this channel now: for the program it stands where the channel last
      // put it, in position. Its alarms are its owner's; a following axis is still this
      // channel's, with its alarms.
      views_[i].cmd = commanded_[i];
      views_[i].act = commanded_[i];
      if (slot_use_[i] != SlotUse::follows) {
        views_[i].enabled = true;
        views_[i].alarm = false;
      }
    }
  }
}

void ChannelController::settle_slots() noexcept {
  if (!exchanges()) {
    return;
  }
  for (std::size_t s = 0; s < setup_.axis_count && s < received_.size(); ++s) {
    if (s == setup_.spindle_c_slot) {
      continue;  // commanded only between M18 and M17 (run_control)
    }
    const AxisFeedbackView& f = received_[s];
    if (f.present && f.owner == setup_.channel_id) {
      if (setup_.slots[s].may_follow && f.coupled_to != 0) {
        slot_use_[s] = SlotUse::follows;  // G51.4 outlives a reset and a restart of the channel
      } else if (slot_use_[s] != SlotUse::commanded) {
        commanded_[s] = f.cmd;  // the machine position travels with the axis
        slot_use_[s] = SlotUse::commanded;
      }
    } else {
      slot_use_[s] = setup_.slots[s].exchange_slot ? SlotUse::virtual_axis : SlotUse::away;
    }
  }
}

void ChannelController::sync_positions() noexcept {
  source_.adopt_position(commanded_);
  planner_.restart(commanded_);
  hold_outputs(true);  // this cycle's setpoints came from the planner before it knew
}

std::optional<std::size_t> ChannelController::moves_foreign_slot(
    const interp::Command& c) const noexcept {
  if (!exchanges() || (c.op != interp::Op::rapid && c.op != interp::Op::linear &&
                       c.op != interp::Op::arc && c.op != interp::Op::thread)) {
    return std::nullopt;
  }
  const AxisVector& from = planner_.queue_end();
  for (std::size_t s = 0; s < setup_.axis_count; ++s) {
    if ((slot_use_[s] == SlotUse::away || slot_use_[s] == SlotUse::follows ||
         slot_use_[s] == SlotUse::speed_control) &&
        std::fabs(c.to[s] - from[s]) > 1e-9) {
      return s;
    }
  }
  return std::nullopt;
}

bool ChannelController::away_on_own_account(std::size_t s) const noexcept {
  const std::uint32_t self = setup_.channel_id;
  const std::uint32_t home = setup_.slots[s].home;
  const AxisFeedbackView& r = received_[s];
  return home == self ? r.owner != self
                      : r.owner == self || (r.released_by == self && r.owner != home);
}

bool ChannelController::exchange_refused(const ExchangeBlock& b) noexcept {
  const char* code = b.op == interp::Op::axis_release   ? "G140"
                     : b.op == interp::Op::axis_acquire ? "G141"
                                                        : "G142";
  for (std::size_t s = 0; s < setup_.axis_count && s < received_.size(); ++s) {
    const AxisFeedbackView& r = received_[s];
    if (b.op != interp::Op::axis_restore && s != b.slot) {
      continue;
    }
    // G142 goes to every exchangeable axis: a node where the channel has no say refuses it, and
    // only one whose axis is away on this channel's account matters.
    const bool refused =
        r.request_refused && (b.op != interp::Op::axis_restore || away_on_own_account(s));
    if (!r.request_full && !refused) {
      continue;
    }
    char text[160];
    std::snprintf(text, sizeof text,
                  r.request_full
                      ? "%s %c: the axis node could not keep the request (more channels wait for "
                        "the axis than it holds)"
                      : "%s %c: the axis node refused the request (the axis is not this "
                        "channel's to release or restore; channel %u has it)",
                  code, setup_.slots[s].address, r.owner);
    raise(kAlarmRequestRefused, text, b.block.line, 0, static_cast<int>(s + 1));
    return true;
  }
  return false;
}

void ChannelController::push_axis_request(AxisRequestKind kind, std::size_t slot,
                                          bool force) noexcept {
  if (out_.axis_request_count < ChannelOutput::kMaxAxisRequests) {
    out_.axis_requests[out_.axis_request_count++] = AxisRequestOut{kind, slot, force};
  }
}

void ChannelController::withdraw_waits() noexcept {
  if (!exchange_block_ || !exchange_block_->sent ||
      exchange_block_->op == interp::Op::axis_release) {
    return;
  }
  exchange_block_->sent = false;
  push_axis_request(AxisRequestKind::withdraw,
                    exchange_block_->op == interp::Op::axis_acquire ? exchange_block_->slot
                                                                    : AxisRequestOut::kAllSlots,
                    false);
}

void ChannelController::run_exchange(std::uint64_t cycle) noexcept {
  ExchangeBlock& b = *exchange_block_;
  start_held(b.block);
  const std::uint32_t self = setup_.channel_id;
  const AxisFeedbackView none{};
  const AxisFeedbackView& f =
      b.op != interp::Op::axis_restore && b.slot < received_.size() ? received_[b.slot] : none;
  const char letter = b.op != interp::Op::axis_restore ? setup_.slots[b.slot].address : ' ';
  if (!b.sent) {
    bool done = !exchanges();  // no exchange in this channel: G142 has nothing to restore
    if (b.op == interp::Op::axis_release && !done &&
        (slot_use_[b.slot] != SlotUse::commanded || f.owner != self)) {
      char text[128];
      std::snprintf(text, sizeof text, "G140 %c: the axis is not this channel's (%s%.0u has it)",
                    letter, f.owner == 0 ? "nobody" : "channel ", f.owner);
      raise(kAlarmNotOwner, text, b.block.line, 0, static_cast<int>(b.slot + 1));
      return;
    }
    if (b.op == interp::Op::axis_acquire && slot_use_[b.slot] == SlotUse::commanded &&
        f.owner == self) {
      done = true;  // already this channel's
    }
    if (!done) {
      const AxisRequestKind kind = b.op == interp::Op::axis_release   ? AxisRequestKind::release
                                   : b.op == interp::Op::axis_acquire ? AxisRequestKind::acquire
                                                                      : AxisRequestKind::restore;
      push_axis_request(kind, b.op == interp::Op::axis_restore ? AxisRequestOut::kAllSlots : b.slot,
                        b.force);
      b.sent = true;
      b.sent_cycle = cycle;
      set_state(ChannelState::waiting);
      return;
    }
  } else {
    if (!answer_visible(b.sent_cycle, cycle)) {
      return;
    }
    if (exchange_refused(b)) {
      return;
    }
    switch (b.op) {
      case interp::Op::axis_release:
        if (f.owner == self) {
          return;
        }
        slot_use_[b.slot] =
            setup_.slots[b.slot].exchange_slot ? SlotUse::virtual_axis : SlotUse::away;
        break;
      case interp::Op::axis_acquire:
        if (f.owner != self) {
          return;  // waits until the owner releases (or, P1, the axis is at rest)
        }
        settle_slots();
        sync_positions();
        break;
      default:
        // G142 ends once no axis is away on this channel's account (spec dafeng §3.3
        // decide 1): its own axes are back, none borrowed is still its, none it released is
        // still elsewhere.
        for (std::size_t s = 0; s < setup_.axis_count && s < received_.size(); ++s) {
          if (away_on_own_account(s)) {
            return;
          }
        }
        settle_slots();
        sync_positions();
        break;
    }
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  set_state(ChannelState::running);
  exchange_block_.reset();
}

}  // namespace mcnc::channel

namespace mcnc::channel {

void ChannelController::run_aux() noexcept {
  AuxBlock& b = *aux_block_;
  if (!b.spindle) {
    start_held(b.block);  // a spindle start has its block events from the queue once allowed
  }
  const std::size_t first_spindle = setup_.axis_count;
  if (b.spindle && !b.sent && first_spindle < received_.size() &&
      received_[first_spindle].coupled_to != 0) {
    raise(kAlarmSlaveSpindle,
          "the spindle follows another spindle (G114.1): its master's channel cancels that "
          "with G113 first",
          b.block.line, 0, 0);
    return;
  }
  if (b.spindle && !setup_.plc) {
    const interp::Command command = b.command;  // no PLC to ask: it turns now
    aux_block_.reset();
    (void)queue_command(command);
    return;
  }
  if (!b.sent) {
    b.request.id = (std::uint64_t{setup_.channel_id} << 40) | ++aux_requests_;
    out_.aux = b.request;
    out_.aux_due = true;
    b.sent = true;
    return;
  }
  if (!aux_answer_ && plc_lost_) {
    AuxAnswer gone;
    gone.id = b.request.id;
    gone.outcome = AuxOutcome::refused;
    std::snprintf(gone.reason.data(), gone.reason.size(), "the PLC node is gone");
    aux_answer_ = gone;
  }
  if (!aux_answer_) {
    return;  // FIN wait
  }
  const AuxAnswer answer = *aux_answer_;
  aux_answer_.reset();
  if (answer.outcome != AuxOutcome::done) {
    char text[160];
    const bool t = b.request.kind == AuxKind::t_code;
    std::snprintf(text, sizeof text, "%c%0*d %s by the PLC: %s", t ? 'T' : 'M', t ? 4 : 2,
                  b.request.code, answer.outcome == AuxOutcome::refused ? "refused" : "not done",
                  answer.reason.data());
    raise(answer.outcome == AuxOutcome::refused ? kAlarmAuxRefused : kAlarmAuxTimeout, text,
          b.block.line, 0, 0);
    return;
  }
  if (b.spindle) {
    const interp::Command command = b.command;
    aux_block_.reset();
    (void)queue_command(command);  // a refusal is a source alarm, raised in its turn
    return;
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  aux_block_.reset();
}

}  // namespace mcnc::channel

namespace mcnc::channel {

void ChannelController::run_coupling(std::uint64_t cycle) noexcept {
  CouplingBlock& b = *coupling_block_;
  start_held(b.block);
  if (!b.sent) {
    const CouplingStart start = b.axis ? start_axis_sync(b) : start_spindle_sync(b);
    if (start == CouplingStart::refused) {
      return;  // the alarm is raised
    }
    if (start == CouplingStart::send) {
      if (b.axis) {
        out_.axis_sync = b.axis_sync;
        out_.axis_sync_due = true;
      } else {
        out_.spindle_sync = b.spindle;
        out_.spindle_sync_due = true;
      }
      b.sent = true;
      b.sent_cycle = cycle;
      return;
    }
  } else if (!answer_visible(b.sent_cycle, cycle) ||
             !(b.axis ? axis_sync_done(b) : spindle_sync_done(b))) {
    return;
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  coupling_block_.reset();
}

ChannelController::CouplingStart ChannelController::start_spindle_sync(
    const CouplingBlock& b) noexcept {
  bool known = !b.spindle.on;  // G113 cancels whatever this channel's groups have
  for (const SpindleGroupSetup& g : setup_.spindle_groups) {
    known = known || g.group == b.spindle.group;
  }
  if (!known) {
    char text[128];
    std::snprintf(text, sizeof text,
                  "G114.1 K%d: no synchronisation group %d has this channel's spindle as master",
                  b.spindle.group, b.spindle.group);
    raise(kAlarmSyncGroup, text, b.block.line, 0, 0);
    return CouplingStart::refused;
  }
  return CouplingStart::send;
}

bool ChannelController::spindle_sync_done(const CouplingBlock& b) const noexcept {
  for (const SpindleGroupSetup& g : setup_.spindle_groups) {
    if (b.spindle.on && g.group != b.spindle.group) {
      continue;
    }
    const AxisFeedbackView none{};
    const AxisFeedbackView& slave =
        g.slave_view < received_.size() ? received_[g.slave_view] : none;
    const bool done =
        b.spindle.on ? slave.coupled_to != 0 && slave.coupling_locked : slave.coupled_to == 0;
    if (!done) {
      return false;  // G114.1 ends once the slave is at speed and in phase
    }
  }
  return true;
}

ChannelController::CouplingStart ChannelController::start_axis_sync(CouplingBlock& b) noexcept {
  const char* g = b.axis_sync.on ? "G51.4" : "G50.4";
  char text[192];
  auto refuse = [&] {
    raise(kAlarmAxisSync, text, b.block.line, 0, 0);
    return CouplingStart::refused;
  };
  std::size_t s = setup_.slots.size();
  for (std::size_t i = 0; i < setup_.slots.size() && i < setup_.axis_count; ++i) {
    s = setup_.slots[i].id == b.slave && !setup_.slots[i].exchange_slot ? i : s;
  }
  if (s == setup_.slots.size() ||
      (slot_use_[s] != SlotUse::commanded && slot_use_[s] != SlotUse::follows)) {
    std::snprintf(text, sizeof text,
                  "%s Q%u: axis %u is not this channel's (the channel that commands it programs "
                  "it)",
                  g, b.slave, b.slave);
    return refuse();
  }
  const AxisSlot& slot = setup_.slots[s];
  if (!slot.may_follow) {
    std::snprintf(text, sizeof text,
                  "%s Q%u: %c cannot follow another axis (parameter 5600.1: axis_sync)", g, b.slave,
                  slot.address);
    return refuse();
  }
  b.axis_sync.slot = s;
  const std::uint32_t coupled_to = s < received_.size() ? received_[s].coupled_to : 0;
  if (!b.axis_sync.on) {
    return slot_use_[s] == SlotUse::follows || coupled_to != 0 ? CouplingStart::send
                                                               : CouplingStart::nothing_to_do;
  }
  const std::uint32_t master = b.axis_sync.master != 0 ? b.axis_sync.master : slot.default_master;
  if (master == 0) {
    std::snprintf(text, sizeof text,
                  "G51.4 Q%u: no P, and %c has no default master (parameter 5610: axis_sync "
                  "master)",
                  b.slave, slot.address);
    return refuse();
  }
  const MachineAxis* m =
      master <= setup_.machine_axes.size() ? &setup_.machine_axes[master - 1] : nullptr;
  const MachineAxisKind kind = slot.id >= 1 && slot.id <= setup_.machine_axes.size()
                                   ? setup_.machine_axes[slot.id - 1].kind
                                   : MachineAxisKind::linear;
  if (m == nullptr || m->kind != kind || m->may_follow) {
    std::snprintf(text, sizeof text, "G51.4 P%u: %s", master,
                  m == nullptr      ? "the machine has no such axis"
                  : m->kind != kind ? "the master is not of the same kind as the slave"
                                    : "the axis may follow another itself (5600.1), it "
                                      "cannot lead");
    return refuse();
  }
  if (slot_use_[s] == SlotUse::follows || coupled_to != 0) {
    if (coupled_to == master) {
      slot_use_[s] = SlotUse::follows;
      return CouplingStart::nothing_to_do;
    }
    std::snprintf(text, sizeof text, "G51.4 Q%u: %c already follows axis %u: G50.4 Q%u first",
                  b.slave, slot.address, coupled_to, b.slave);
    return refuse();
  }
  b.axis_sync.master = master;
  return CouplingStart::send;
}

bool ChannelController::axis_sync_done(const CouplingBlock& b) noexcept {
  const std::size_t s = b.axis_sync.slot;
  if (s >= received_.size()) {
    return false;
  }
  const AxisFeedbackView& f = received_[s];
  if (b.axis_sync.on) {
    if (f.coupled_to != b.axis_sync.master) {
      return false;
    }
    slot_use_[s] = SlotUse::follows;  // from now on the program does not move it
    return true;
  }
  if (f.coupled_to != 0) {
    return false;
  }
  // The axis stands where its master took it: the program goes on from there.
  commanded_[s] = f.cmd;
  slot_use_[s] = SlotUse::commanded;
  sync_positions();
  return true;
}

}  // namespace mcnc::channel

namespace mcnc::channel {

void ChannelController::run_control() noexcept {
  ControlBlock& b = *control_block_;
  start_held(b.block);
  const auto c = setup_.spindle_c_slot;
  if (!c || *c >= received_.size()) {
    raise(interp::alarm::kSpindleControl, "the spindle has no C axis for position control",
          b.block.line, 0, 0);
    return;
  }
  if (b.position && !under_position_control()) {
    const AxisFeedbackView& f = received_[*c];  // the spindle's own feedback
    if (f.coupled_to != 0) {
      raise(kAlarmSlaveSpindle,
            "the spindle follows another spindle (G114.1): its master's channel cancels that "
            "with G113 before position control",
            b.block.line, 0, 0);
      return;
    }
    // Taken over at rest: a spindle still coasting down from M05 would be stopped by the
    // position loop at once. Five cycles in a row below C's in-position width per cycle.
    constexpr int kStillCycles = 5;
    const double width = *c < setup_.in_position.size() ? setup_.in_position[*c] : 0.01;
    b.still_cycles = b.seen && std::fabs(f.act - b.last_act) <= width ? b.still_cycles + 1 : 0;
    b.seen = true;
    b.last_act = f.act;
    if (b.still_cycles < kStillCycles) {
      constexpr double kRestTimeout = 10.0;  // s: a spindle coasting down from any speed is in
      if (static_cast<double>(++b.waited) * setup_.cycle_s > kRestTimeout) {
        raise(kAlarmSpindleNotAtRest,
              "position control: the spindle did not come to rest within 10 s", b.block.line, 0, 0);
      }
      return;
    }
    c_base_ = 360.0 * std::floor(f.act / 360.0);
    commanded_[*c] = f.act - c_base_;
    slot_use_[*c] = SlotUse::commanded;
    sync_positions();
  } else if (!b.position) {
    leave_position_control();
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  control_block_.reset();
}

void ChannelController::leave_position_control() noexcept {
  if (setup_.spindle_c_slot && *setup_.spindle_c_slot < slot_use_.size()) {
    slot_use_[*setup_.spindle_c_slot] = SlotUse::speed_control;
  }
}

void ChannelController::watch_skip(std::span<const AxisFeedbackView> feedback) noexcept {
  if (!skip_block_ || skip_block_->phase != SkipBlock::Phase::moving) {
    return;
  }
  SkipBlock& b = *skip_block_;
  for (std::size_t i = 0; i < setup_.axis_count && i < feedback.size(); ++i) {
    if (probe_on_input(i, b.command.input) && feedback[i].probe == ProbeSeen::latched) {
      // The signal came: the latching axis where its drive latched it, the others where
      // they stood in the same feedback.
      for (std::size_t j = 0; j < setup_.axis_count && j < feedback.size(); ++j) {
        b.skip_at[j] = feedback[j].act;
      }
      b.skip_at[i] = feedback[i].probe_pos;
      b.skipped = true;
      b.phase = SkipBlock::Phase::stopping;
      planner_.reset();  // stop at once (the reset deceleration) and drop the rest of the move
      return;
    }
  }
}

void ChannelController::run_skip(std::span<const AxisFeedbackView> feedback) noexcept {
  SkipBlock& b = *skip_block_;
  if (b.phase == SkipBlock::Phase::arming) {
    bool armed = true;
    bool any = false;
    for (std::size_t i = 0; i < setup_.axis_count && i < feedback.size(); ++i) {
      if (probe_on_input(i, b.command.input)) {
        any = true;
        armed = armed && feedback[i].probe == ProbeSeen::armed;
      }
    }
    if (!any) {
      char text[96];
      std::snprintf(text, sizeof text,
                    "G31: no axis this channel commands has its touch probe on input %d",
                    b.command.input);
      raise(interp::alarm::kSkipInput, text, b.command.line, 0, 0);
      return;
    }
    if (!armed) {
      if (++b.waited > setup_.probe_arm_cycles) {
        char text[96];
        std::snprintf(text, sizeof text, "G31: the touch probe on input %d did not arm",
                      b.command.input);
        raise(kAlarmProbeNotArmed, text, b.command.line, 0, 0);
      }
      return;
    }
    if (queue_command(b.command)) {
      b.phase = SkipBlock::Phase::moving;
    } else {
      skip_block_.reset();  // the planner refused it: its alarm (source_alarm_) comes next
    }
    return;
  }
  // The move ended (its end reached without the signal, or stopped at it) and its block too.
  if (!b.skipped) {
    b.skip_at = commanded_;
  }
  source_.skip_result(b.skipped, b.skip_at, commanded_);
  skip_block_.reset();
}

void ChannelController::run_wait() noexcept {
  WaitBlock& b = *wait_block_;
  start_held(b.block);
  const interp::Command& c = b.command;
  bool holds = false;
  char text[160];
  if (c.op == interp::Op::wait_input) {
    const auto port = static_cast<std::size_t>(c.input);
    const int bit = port < setup_.input_ports.size() ? setup_.input_ports[port] : -1;
    if (bit < 0 || bit > 63 || plc_lost_) {
      std::snprintf(text, sizeof text, "G04 I%s%d: %s", c.input_on ? "" : "-", c.input,
                    plc_lost_ ? "the PLC node is gone" : "the PLC has no input with this port");
      raise(interp::alarm::kInputPort, text, b.block.line, 0, 0);
      return;
    }
    holds = (((plc_inputs_ >> bit) & 1U) != 0) == c.input_on;
  } else {
    const std::size_t view = setup_.axis_count + static_cast<std::size_t>(c.spindle) - 1;
    if (c.spindle < 1 || static_cast<std::size_t>(c.spindle) > setup_.spindle_count ||
        view >= received_.size() || !received_[view].present) {
      std::snprintf(text, sizeof text, "G04 PS%d=: no feedback of spindle %d in this channel",
                    c.spindle, c.spindle);
      raise(interp::alarm::kNoSuchSpindle, text, b.block.line, 0, 0);
      return;
    }
    // degrees per second to revolutions per minute; the direction does not count.
    constexpr double kRpmPerDegreePerSecond = 60.0 / 360.0;
    const double rpm = std::fabs(received_[view].vel) * kRpmPerDegreePerSecond;
    holds = std::fabs(rpm - c.rpm) <= setup_.speed_arrival_rpm;
  }
  switch (b.wait.step(holds)) {
    case coordination::WaitOutcome::waiting:
      return;
    case coordination::WaitOutcome::timed_out:
      // With a dwell time the time ends the block (spec [AMBIGUOUS], decision 68); without
      // one, an input or a speed that never comes is an alarm, as M01 I/J's (L6045-6049).
      if (c.dwell_s < 0.0) {
        if (c.op == interp::Op::wait_input) {
          std::snprintf(text, sizeof text, "G04 I%s%d: input %d not %s within %.3f s (J)",
                        c.input_on ? "" : "-", c.input, c.input, c.input_on ? "on" : "off",
                        c.timeout_s);
          raise(kAlarmInputTimeout, text, b.block.line, 0, 0);
        } else {
          std::snprintf(text, sizeof text,
                        "G04 PS%d=%.0f: spindle %d not within %.0f rpm of it after %.3f s "
                        "(speed_arrival, parameters 1057/1059)",
                        c.spindle, c.rpm, c.spindle, setup_.speed_arrival_rpm,
                        setup_.speed_arrival_timeout_s);
          raise(kAlarmSpeedTimeout, text, b.block.line, 0, 0);
        }
        return;
      }
      break;
    case coordination::WaitOutcome::met:
    case coordination::WaitOutcome::dwell_over:
      break;
  }
  push_event(block_event(b.block, ChannelEventKind::block_ended));
  wait_block_.reset();
}

}  // namespace mcnc::channel
