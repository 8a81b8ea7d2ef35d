#include "channel/control/channel_controller.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <type_traits>

namespace mcnc::channel {

namespace {

// The C axis's in-position width, per cycle: below it the spindle stands (M18).
double c_rest_width(const ChannelSetup& setup) noexcept {
  const auto c = setup.spindle_c_slot;
  return c && *c < setup.in_position.size() ? setup.in_position[*c] : 0.01;
}

}  // namespace

static_assert(coordination::kCallArgs == interp::kSubcallArgs);
static_assert(coordination::AxisExchange::kMaxSlots >= kMaxChannelAxes);
static_assert(std::is_same_v<coordination::SkipProbe::Position, AxisVector>);

ChannelController::ChannelController(ChannelSetup setup, interp::CommandSource& source,
                                     motion::MotionPlanner& planner)
    : setup_(std::move(setup)),
      source_(source),
      planner_(planner),
      queued_(std::max<std::size_t>(planner.window_blocks(), 1) + 8),
      mark_(setup_.channel_id),
      calls_(setup_.channel_id, setup_.call_wait_cycles),
      exchange_(coordination::ExchangeSetup{setup_.channel_id, setup_.axis_count, setup_.slots,
                                            setup_.spindle_c_slot}),
      aux_(setup_.channel_id),
      coupling_(coordination::CouplingSetup{setup_.axis_count, setup_.slots, setup_.spindle_groups,
                                            setup_.machine_axes}),
      spindle_mode_(c_rest_width(setup_), setup_.cycle_s),
      skip_(setup_.axis_count, setup_.probe_arm_cycles) {}

void ChannelController::axis_lost(std::size_t axis) noexcept {
  if (lost_axis_ == 0) {
    lost_axis_ = axis + 1;
  }
}

void ChannelController::on_arrival(const coordination::SyncArrival& arrival) noexcept {
  mark_.on_arrival(arrival);  // a full table makes the next evaluation an alarm
}

void ChannelController::set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept {
  if (channel < 1 || channel > coordination::kMaxChannels) {
    return;
  }
  const bool automatic =
      status.known && (status.state == ChannelState::running ||
                       status.state == ChannelState::hold || status.state == ChannelState::waiting);
  active_.set(channel, automatic);
  halted_partners_.set(channel, status.known && status.state == ChannelState::alarm);
  calls_.set_partner(channel, status);
}

void ChannelController::on_call(const CallRequest& call) noexcept {
  if (const auto refused = calls_.on_call(call)) {
    push_release(*refused);
  }
}

void ChannelController::on_call_release(const CallRelease& release) noexcept {
  calls_.on_release(release);
}

void ChannelController::on_aux_answer(const PlcAnswer& answer) noexcept {
  aux_.on_answer(answer);  // an answer to a request a reset abandoned is ignored
}

void ChannelController::plc_lost() noexcept {
  aux_.plc_lost();
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
  if (out_.event_count < CycleOutput::kMaxEvents) {
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
    out_.setpoints[i] = CommandedAxis{commanded_[i], 0.0, 0.0, valid};
  }
}

void ChannelController::forget_program_run() noexcept {
  withdraw_waits();
  mdi_run_ = false;
  held_ = std::monostate{};
  exchange_.abandon();
  aux_.abandon();
  spindle_queued_ = 0;  // a program (re)starts with its spindle stopped
  halted_ = false;
  queued_.clear();
  end_pulled_ = false;
  end_started_ = false;
  source_alarm_.reset();
  mark_.abandon();
  calls_.abandon();
  out_.program_end = false;
  out_.end_code = -1;
}

void ChannelController::finish_reset() noexcept {
  resetting_ = false;
  source_.abandon();
  release_caller(CallOutcome::aborted);  // a caller waiting for this channel goes on with an alarm
  calls_.stop_serving();
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
  out_.arrival_due = false;
  out_.call_due = false;
  out_.release_count = 0;
  exchange_.begin_cycle();
  out_.aux_due = false;
  out_.spindle_sync_due = false;
  out_.axis_sync_due = false;
  const bool was_position = under_position_control();
  received_ = feedback;
  for (std::size_t s = 0; s < feedback.size(); ++s) {
    if (const auto loss = exchange_.update(s, feedback[s])) {
      raise_if_queued_moves(loss->slot, loss->why.data());
    }
  }
  build_views(feedback);
  run_cycle(cycle,
            std::span<const AxisFeedbackView>(views_.data(), std::min(feedback.size(), kMaxViews)));
  // Only an axis the channel commands follows its setpoints; the others hold where they are.
  for (std::size_t i = 0; i < setup_.axis_count && exchanges(); ++i) {
    if (exchange_.use(i) != coordination::SlotUse::commanded) {
      out_.setpoints[i].valid = false;
    }
  }
  // G31: the probes on the block's input stay armed while it arms and moves.
  const auto* skip = std::get_if<SkipStop>(&held_);
  if (skip != nullptr && skip_.phase() != coordination::SkipPhase::stopping && in_run()) {
    const std::uint32_t probes = probe_axes(skip->command.input);
    for (std::size_t i = 0; i < setup_.axis_count; ++i) {
      if (((probes >> i) & 1U) != 0) {
        out_.setpoints[i].probe = skip->arm;
      }
    }
  }
  out_.spindle_position = false;
  const double c_base = spindle_mode_.c_base();
  if (const auto c = setup_.spindle_c_slot; c && under_position_control()) {
    out_.spindle_position = true;
    out_.setpoints[*c].pos += c_base;
  } else if (c && was_position) {
    // Position control ended in this cycle (M17, the end, a reset): C's last position still
    // goes out, so the spindle stands where the program put it, not a sample short.
    out_.spindle_position = true;
    out_.setpoints[*c] = CommandedAxis{commanded_[*c] + c_base, 0.0, 0.0, true};
  }
  const auto requests = exchange_.requests();
  std::copy(requests.begin(), requests.end(), out_.axis_requests.begin());
  out_.axis_request_count = requests.size();
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
    calls_.stop_serving();
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
      out_.setpoints[i] = CommandedAxis{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
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

  if (const auto* refusal = calls_.take_refusal(); refusal != nullptr && in_run()) {
    raise(*refusal, out_.line);  // a call without wait (H0) its target refused
  }
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
         k < setup_.pulls_per_cycle && !end_pulled_ && !source_alarm_ && !holds_block() &&
         planner_.accepts() && !queued_.full() && source_.ready();
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
      if (const auto away =
              c->moves() ? exchange_.foreign_slot(planner_.queue_end(), c->to) : std::nullopt) {
        const coordination::CoordinationAlarm a = exchange_.foreign_move_alarm(*away, received_);
        source_alarm_ = interp::ProgramAlarm{a.number, a.text.data(), "", c->line, 0};
        return;
      }
      const StopRules rules{
          setup_.channel_id,
          setup_.slots,
          setup_.plc,
          setup_.spindle_may_follow,
          {setup_.speed_arrival_rpm, setup_.speed_arrival_timeout_s, setup_.cycle_s}};
      held_ = read_ahead_stop(*c, rules, spindle_queued_, source_alarm_);
      if (holds_block()) {
        begin_held();
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

void ChannelController::begin_held() noexcept {
  if (const auto* s = std::get_if<SyncStop>(&held_)) {
    mark_.begin(s->has_p, s->p, s->participants, s->all_channels);
  } else if (const auto* s = std::get_if<CallStop>(&held_)) {
    calls_.begin(s->call);
  } else if (const auto* s = std::get_if<ExchangeStop>(&held_)) {
    exchange_.begin(s->kind, s->slot, s->force);
  } else if (const auto* s = std::get_if<AuxStop>(&held_)) {
    aux_.begin(s->kind, s->code, s->spindle_start);
  } else if (const auto* s = std::get_if<CouplingStop>(&held_)) {
    if (s->axis) {
      coupling_.begin_axis(s->on, s->master, s->slave);
    } else {
      coupling_.begin_spindle(s->spindle);
    }
  } else if (const auto* s = std::get_if<ModeStop>(&held_)) {
    spindle_mode_.begin(s->position);
  } else if (const auto* s = std::get_if<SkipStop>(&held_)) {
    skip_.begin(s->command.input);
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
      queued_.started();
    } else {
      event.kind = ChannelEventKind::block_ended;
      event.pos = q.to;
      queued_.ended();
    }
    push_event(event);
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
    out_.setpoints[i] = CommandedAxis{m.sample.pos[i], m.sample.vel[i], m.sample.acc[i], true};
  }
  if (m.block != 0) {
    out_.block = m.block;
    out_.line = m.line;
  }
  if (skip_in(coordination::SkipPhase::stopping) && planner_.idle()) {
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
  const bool held_block = holds_block() && (!std::holds_alternative<SkipStop>(held_) ||
                                            skip_in(coordination::SkipPhase::arming));
  if (single_block_ && held_block && m.completed_block > single_block_stop_) {
    single_block_stop_ = m.completed_block;
    set_state(ChannelState::hold);
    return;
  }
  // Everything pulled so far has run.
  if (holds_block()) {
    std::visit([&](auto& b) { run(b, cycle, feedback); }, held_);
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
  if (calls_.served() != nullptr) {
    release_caller(CallOutcome::released);  // the end releases a caller without G145 too
    if (calls_.repeat_served()) {
      start_served_call(cycle);
    }
  }
}

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

void ChannelController::end_held(const HeldBlock& b) noexcept {
  push_event(block_event(b, ChannelEventKind::block_ended));
  held_ = std::monostate{};  // `b` is gone from here on
}

void ChannelController::run(SyncStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  const coordination::SyncMarkStep step =
      mark_.step({active_, halted_partners_, lost_partners_, writes_pending()});
  if (mark_.arrived_now()) {
    out_.arrival = mark_.barrier().current();
    out_.arrival_due = true;
    push_event(block_event(b.block, ChannelEventKind::sync_arrive));
    set_state(ChannelState::waiting);
  }
  switch (step) {
    case coordination::SyncMarkStep::pending:
    case coordination::SyncMarkStep::waiting:
      return;
    case coordination::SyncMarkStep::alarm:
      raise(mark_.alarm(), b.block.line);
      return;
    case coordination::SyncMarkStep::released:
      push_event(block_event(b.block, ChannelEventKind::sync_release));
      set_state(ChannelState::running);
      break;
    case coordination::SyncMarkStep::done:
      break;
  }
  end_held(b.block);
}

void ChannelController::push_release(const CallRelease& release) noexcept {
  if (out_.release_count < CycleOutput::kMaxReleases) {
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
  if (const auto release = calls_.release_caller(outcome)) {
    push_release(*release);
  }
}

void ChannelController::take_calls(std::uint64_t cycle) noexcept {
  for (const CallRequest& call : calls_.incoming()) {
    const bool free = calls_.served() == nullptr && out_.state == ChannelState::idle &&
                      position_known_ && !halted_ && !reset_requested_ && !estop_requested_ &&
                      !start_requested_;
    if (!free) {
      push_release(calls_.refusal(call));
      continue;
    }
    calls_.serve(call);
    start_served_call(cycle);
  }
  calls_.clear_incoming();
}

void ChannelController::start_served_call(std::uint64_t cycle) noexcept {
  const CallRequest& call = calls_.served()->call;
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

void ChannelController::run(CallStop& b, std::uint64_t cycle,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (calls_.step(cycle, lost_partners_, writes_pending())) {
    case coordination::CallStep::pending:
      return;
    case coordination::CallStep::waiting:
      set_state(ChannelState::waiting);
      return;
    case coordination::CallStep::alarm:
      raise(calls_.alarm(), b.block.line);
      return;
    case coordination::CallStep::send:
      out_.call = calls_.call();
      out_.call_due = true;
      push_event(block_event(b.block, ChannelEventKind::subcall));
      if (calls_.call().wait) {
        set_state(ChannelState::waiting);
        return;
      }
      break;
    case coordination::CallStep::done:
      break;
  }
  end_held(b.block);
  set_state(ChannelState::running);
}

void ChannelController::run(ReleaseStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  // G145: the caller goes on; this program goes on too (spec dafeng §3.4).
  start_held(b.block);
  release_caller(CallOutcome::released);  // no caller, or released before: nothing
  end_held(b.block);
}

void ChannelController::raise_if_queued_moves(std::size_t s, const char* why) noexcept {
  const int moving_line = queued_.first_moving(s, commanded_[s]);
  if (moving_line != 0 &&
      (out_.state == ChannelState::running || out_.state == ChannelState::hold)) {
    char text[128];
    std::snprintf(text, sizeof text, "%c %s", setup_.slots[s].address, why);
    raise(exchange_.use(s) == coordination::SlotUse::follows ? kAlarmAxisFollows : kAlarmAxisAway,
          text, moving_line, 0, static_cast<int>(s + 1));
  }
}

void ChannelController::build_views(std::span<const AxisFeedbackView> received) noexcept {
  using coordination::SlotUse;
  for (std::size_t i = 0; i < received.size() && i < kMaxViews; ++i) {
    views_[i] = received[i];
    if (i == setup_.spindle_c_slot && under_position_control()) {
      views_[i].cmd -= spindle_mode_.c_base();  // the spindle's degrees as C
      views_[i].act -= spindle_mode_.c_base();
    }
    if (exchanges() && i < setup_.axis_count && exchange_.use(i) != SlotUse::commanded) {
      // Not commanded by this channel now: for the program it stands where the channel last
      // put it, in position. Its alarms are its owner's; a following axis is still this
      // channel's, with its alarms.
      views_[i].cmd = commanded_[i];
      views_[i].act = commanded_[i];
      if (exchange_.use(i) != SlotUse::follows) {
        views_[i].enabled = true;
        views_[i].alarm = false;
      }
    }
  }
}

void ChannelController::sync_positions() noexcept {
  source_.adopt_position(commanded_);
  planner_.restart(commanded_);
  hold_outputs(true);  // this cycle's setpoints came from the planner before it knew
}

void ChannelController::run(ExchangeStop& b, std::uint64_t cycle,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (exchange_.step(cycle, received_, commanded_)) {
    case coordination::ExchangeStep::sent:
      set_state(ChannelState::waiting);
      return;
    case coordination::ExchangeStep::waiting:
      return;
    case coordination::ExchangeStep::alarm:
      raise(exchange_.alarm(), b.block.line);
      return;
    case coordination::ExchangeStep::done:
      if (exchange_.took_over()) {
        sync_positions();
      }
      break;
  }
  end_held(b.block);
  set_state(ChannelState::running);
}

void ChannelController::run(AuxStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  const bool spindle = aux_.spindle_start();
  if (!spindle) {
    start_held(b.block);  // a spindle start has its block events from the queue once allowed
  }
  const std::size_t first_spindle = setup_.axis_count;
  coordination::AuxInputs in;
  in.plc = setup_.plc;
  in.spindle_follows = first_spindle < received_.size() && received_[first_spindle].coupled_to != 0;
  switch (aux_.step(in)) {
    case coordination::AuxStep::waiting:
      return;  // FIN wait
    case coordination::AuxStep::send:
      out_.aux = aux_.request();
      out_.aux_due = true;
      return;
    case coordination::AuxStep::alarm:
      raise(aux_.alarm(), b.block.line);
      return;
    case coordination::AuxStep::done:
      break;
  }
  if (spindle) {
    const interp::Command command = b.command;
    held_ = std::monostate{};
    (void)queue_command(command);  // a refusal is a source alarm, raised in its turn
    return;
  }
  end_held(b.block);
}

void ChannelController::run(CouplingStop& b, std::uint64_t cycle,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (coupling_.step(coordination::CouplingInputs{cycle, received_, exchange_.uses()})) {
    case coordination::CouplingStep::waiting:
      return;
    case coordination::CouplingStep::alarm:
      raise(coupling_.alarm(), b.block.line);
      return;
    case coordination::CouplingStep::send:
      if (coupling_.axis()) {
        out_.axis_sync = coupling_.axis_sync();
        out_.axis_sync_due = true;
      } else {
        out_.spindle_sync = coupling_.spindle_sync();
        out_.spindle_sync_due = true;
      }
      return;
    case coordination::CouplingStep::done:
      break;
  }
  const coordination::SlotChange& change = coupling_.slot_change();
  if (change.to == coordination::SlotChange::To::follows) {
    exchange_.set_use(change.slot, coordination::SlotUse::follows);  // the program won't move it
  } else if (change.to == coordination::SlotChange::To::commanded) {
    // The axis stands where its master took it: the program goes on from there.
    commanded_[change.slot] = change.at;
    exchange_.set_use(change.slot, coordination::SlotUse::commanded);
    sync_positions();
  }
  end_held(b.block);
}

void ChannelController::run(ModeStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  const auto c = setup_.spindle_c_slot;
  coordination::SpindleModeInputs in;
  in.has_c_axis = c && *c < received_.size();
  in.act = in.has_c_axis ? received_[*c].act : 0.0;  // the spindle's own feedback
  in.follows = in.has_c_axis && received_[*c].coupled_to != 0;
  switch (spindle_mode_.step(in)) {
    case coordination::SpindleModeStep::waiting:
      return;
    case coordination::SpindleModeStep::alarm:
      raise(spindle_mode_.alarm(), b.block.line);
      return;
    case coordination::SpindleModeStep::done:
      break;
  }
  if (spindle_mode_.position_control() && !under_position_control()) {
    commanded_[*c] = spindle_mode_.c_start();  // C taken over from where the spindle stands
    exchange_.set_use(*c, coordination::SlotUse::commanded);
    sync_positions();
  } else if (!spindle_mode_.position_control()) {
    leave_position_control();
  }
  end_held(b.block);
}

void ChannelController::leave_position_control() noexcept {
  spindle_mode_.leave();
  if (setup_.spindle_c_slot && *setup_.spindle_c_slot < kMaxChannelAxes) {
    exchange_.set_use(*setup_.spindle_c_slot, coordination::SlotUse::speed_control);
  }
}

std::uint32_t ChannelController::probe_axes(int input) const noexcept {
  std::uint32_t probes = 0;
  for (std::size_t i = 0; i < setup_.axis_count && i < setup_.probe_inputs.size(); ++i) {
    const bool commanded = !exchanges() || exchange_.use(i) == coordination::SlotUse::commanded;
    probes |= setup_.probe_inputs[i] == input && commanded ? 1U << i : 0U;
  }
  return probes;
}

void ChannelController::watch_skip(std::span<const AxisFeedbackView> feedback) noexcept {
  const auto* skip = std::get_if<SkipStop>(&held_);
  if (skip != nullptr && skip_.watch(feedback, probe_axes(skip->command.input))) {
    planner_.reset();  // stop at once (the reset deceleration) and drop the rest of the move
  }
}

void ChannelController::run(SkipStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> feedback) noexcept {
  if (skip_.phase() == coordination::SkipPhase::arming) {
    switch (skip_.arm(feedback, probe_axes(b.command.input))) {
      case coordination::SkipArming::waiting:
        return;
      case coordination::SkipArming::alarm:
        raise(skip_.alarm(), b.command.line);
        return;
      case coordination::SkipArming::armed:
        break;
    }
    if (queue_command(b.command)) {
      skip_.start_moving();
    } else {
      held_ = std::monostate{};  // the planner refused it: its alarm (source_alarm_) comes next
    }
    return;
  }
  // The move ended (its end reached without the signal, or stopped at it) and its block too.
  source_.skip_result(skip_.skipped(), skip_.where(commanded_), commanded_);
  held_ = std::monostate{};
}

void ChannelController::run(WaitStop& b, std::uint64_t /*cycle*/,
                            std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  const coordination::ConditionSpec& c = b.condition.spec();
  coordination::ConditionInputs in;
  const auto port = static_cast<std::size_t>(c.port);
  in.input_bit = c.input && port < setup_.input_ports.size() ? setup_.input_ports[port] : -1;
  in.plc_inputs = plc_inputs_;
  in.plc_gone = aux_.plc_gone();
  const std::size_t view = setup_.axis_count + static_cast<std::size_t>(c.spindle) - 1;
  in.spindle_present = !c.input && c.spindle >= 1 &&
                       static_cast<std::size_t>(c.spindle) <= setup_.spindle_count &&
                       view < received_.size() && received_[view].present;
  in.spindle_vel = in.spindle_present ? received_[view].vel : 0.0;
  switch (b.condition.step(in)) {
    case coordination::ConditionStep::waiting:
      return;
    case coordination::ConditionStep::alarm:
      raise(b.condition.alarm(), b.block.line);
      return;
    case coordination::ConditionStep::done:
      break;
  }
  end_held(b.block);
}

}  // namespace mcnc::channel
