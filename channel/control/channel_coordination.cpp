#include "channel/control/channel_coordination.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <utility>

namespace mcnc::channel {

using coordination::AxisFeedbackView;
using coordination::ChannelState;
using coordination::SlotUse;

namespace {

// The C axis's in-position width, per cycle: below it the spindle stands (M18).
double c_rest_width(const ChannelSetup& setup) noexcept {
  const auto c = setup.spindle_c_slot;
  return c && *c < setup.in_position.size() ? setup.in_position[*c] : 0.01;
}

}  // namespace

static_assert(coordination::kCallArgs == interp::kSubcallArgs);
static_assert(coordination::AxisExchange::kMaxSlots >= interp::kMaxChannelAxes);
static_assert(std::is_same_v<coordination::SkipProbe::Position, interp::AxisVector>);

ChannelCoordination::ChannelCoordination(const ChannelSetup& setup, ChannelHost& host,
                                         CycleOutput& out, interp::AxisVector& commanded,
                                         const BlockQueue& queued)
    : setup_(setup),
      host_(host),
      out_(out),
      commanded_(commanded),
      queued_(queued),
      mark_(setup.channel_id),
      calls_(setup.channel_id, setup.call_wait_cycles),
      exchange_(coordination::ExchangeSetup{setup.channel_id, setup.axis_count, setup.slots,
                                            setup.spindle_c_slot}),
      aux_(setup.channel_id),
      coupling_(coordination::CouplingSetup{setup.axis_count, setup.slots, setup.spindle_groups,
                                            setup.machine_axes, setup.polygon, setup.cam,
                                            setup.egb}),
      spindle_mode_(c_rest_width(setup), setup.cycle_s),
      skip_(setup.axis_count, setup.probe_arm_cycles),
      load_(setup.slots),
      timers_(setup.slots),
      overload_(setup.slots) {}

void ChannelCoordination::on_arrival(const coordination::SyncArrival& arrival) noexcept {
  mark_.on_arrival(arrival);  // a full table makes the next evaluation an alarm
}

void ChannelCoordination::set_partner(std::uint32_t channel,
                                      const coordination::PartnerStatus& status) noexcept {
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

void ChannelCoordination::partner_lost(std::uint32_t channel) noexcept {
  if (channel >= 1 && channel <= coordination::kMaxChannels) {
    lost_partners_.set(channel);
  }
}

void ChannelCoordination::on_call(const coordination::CallRequest& call) noexcept {
  if (const auto refused = calls_.on_call(call)) {
    push_release(*refused);
  }
}

void ChannelCoordination::on_call_release(const coordination::CallRelease& release) noexcept {
  calls_.on_release(release);
}

void ChannelCoordination::on_aux_answer(const coordination::PlcAnswer& answer) noexcept {
  aux_.on_answer(answer);  // an answer to a request a reset abandoned is ignored
}

void ChannelCoordination::plc_lost() noexcept {
  aux_.plc_lost();
}

const char* ChannelCoordination::take_loss() noexcept {
  const std::uint64_t writes_lost = setup_.shared_writes ? setup_.shared_writes->lost() : 0;
  const char* why = coordination_lost_
                        ? "events from another channel were lost (receive queue full)"
                    : writes_lost > writes_lost_seen_
                        ? "shared variable writes were lost (more than the log holds)"
                        : nullptr;
  coordination_lost_ = false;
  writes_lost_seen_ = writes_lost;
  return why;
}

void ChannelCoordination::begin_cycle(std::span<const AxisFeedbackView> feedback) noexcept {
  out_.arrival_due = false;
  out_.call_due = false;
  out_.release_count = 0;
  exchange_.begin_cycle();
  out_.aux_due = false;
  out_.spindle_sync_due = false;
  out_.axis_sync_due = false;
  out_.polygon_sync_due = false;
  out_.cam_sync = nullptr;
  out_.egb_sync_due = false;
  was_position_ = under_position_control();
  received_ = feedback;
  for (std::size_t s = 0; s < feedback.size(); ++s) {
    if (const auto loss = exchange_.update(s, feedback[s])) {
      raise_if_queued_moves(loss->slot, loss->why.data());
    }
  }
  view_count_ = std::min(feedback.size(), kMaxViews);
  for (std::size_t i = 0; i < view_count_; ++i) {
    views_[i] = feedback[i];
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

void ChannelCoordination::end_cycle() noexcept {
  // Only an axis the channel commands follows its setpoints; the others hold where they are.
  for (std::size_t i = 0; i < setup_.axis_count && exchanges(); ++i) {
    if (exchange_.use(i) != SlotUse::commanded) {
      out_.setpoints[i].valid = false;
    }
  }
  // G31: the probes on the block's input stay armed while it arms and moves; G160: its axis's
  // torque skip.
  const auto* skip = std::get_if<SkipStop>(&held_);
  if (skip != nullptr && skip->command.skip_signal == 0 &&
      skip_.phase() != coordination::SkipPhase::stopping && in_run()) {
    const std::uint32_t probes = skip_axes(*skip);
    const std::uint32_t torques = torque_axes(*skip);
    for (std::size_t i = 0; i < setup_.axis_count; ++i) {
      if (((probes >> i) & 1U) != 0) {
        out_.setpoints[i].probe = ((torques >> i) & 1U) != 0 ? ProbeArm::torque : skip->arm;
      }
    }
  }
  for (std::size_t i = 0; i < setup_.axis_count && i < torque_.size(); ++i) {
    // A G160's (or G31 P98/P99's) limit stands above G10 L14 P9's while it lasts.
    const bool skip_limit = torque_[i].limit > 0.0;
    out_.setpoints[i].torque_limit = skip_limit ? torque_[i].limit : programmed_torque_[i];
    out_.setpoints[i].skip_deviation = skip_limit ? torque_[i].deviation : 0.0;
  }
  for (std::size_t i = 0; i < setup_.axis_count && i < torque_mode_.size(); ++i) {
    if (!torque_mode_[i].on) {
      continue;
    }
    // In torque mode the node's command follows the motor: the setpoint says where that is, so
    // that its position goes on from there when the channel takes the axis back.
    CommandedAxis& sp = out_.setpoints[i];
    sp.pos = i < received_.size() ? received_[i].channel_cmd() : sp.pos;
    sp.vel = 0.0;
    sp.acc = 0.0;
    sp.torque_mode = true;
    sp.torque = torque_mode_[i].torque;
    sp.torque_speed = torque_mode_[i].speed;
  }
  out_.spindle_position = false;
  const double c_base = spindle_mode_.c_base();
  if (const auto c = setup_.spindle_c_slot; c && under_position_control()) {
    out_.spindle_position = true;
    out_.setpoints[*c].pos += c_base;
  } else if (c && was_position_) {
    // Position control ended in this cycle (M17, the end, a reset): C's last position still
    // goes out, so the spindle stands where the program put it, not a sample short.
    out_.spindle_position = true;
    out_.setpoints[*c] = CommandedAxis{commanded_[*c] + c_base, 0.0, 0.0, true};
  }
  const auto requests = exchange_.requests();
  std::copy(requests.begin(), requests.end(), out_.axis_requests.begin());
  out_.axis_request_count = requests.size();
}

bool ChannelCoordination::hold(ReadAheadStop stop) noexcept {
  held_ = std::move(stop);
  if (const auto* s = std::get_if<SyncStop>(&held_)) {
    mark_.begin(s->has_p, s->p, s->participants, s->all_channels);
  } else if (const auto* s = std::get_if<CallStop>(&held_)) {
    calls_.begin(s->call);
  } else if (const auto* s = std::get_if<ExchangeStop>(&held_)) {
    exchange_.begin(s->kind, s->slot, s->force);
  } else if (const auto* s = std::get_if<AuxStop>(&held_)) {
    aux_.begin(s->kind, s->code, s->spindle_start);
  } else if (const auto* s = std::get_if<CouplingStop>(&held_)) {
    if (s->egb) {
      coupling_.begin_egb(s->egb_sync);
    } else if (s->cam) {
      coupling_.begin_cam(s->cam_sync);
    } else if (s->polygon) {
      coupling_.begin_polygon(s->polygon_sync);
    } else if (s->axis) {
      coupling_.begin_axis(s->on, s->master, s->slave);
    } else {
      coupling_.begin_spindle(s->spindle);
    }
  } else if (const auto* s = std::get_if<ModeStop>(&held_)) {
    spindle_mode_.begin(s->position);
  } else if (const auto* s = std::get_if<SkipStop>(&held_)) {
    if (s->command.skip_signal != 0) {
      skip_.begin_signal(s->command.skip_signal);
    } else if (s->command.multi_skip) {
      skip_.begin_multi(s->command.input, s->command.skip_axis, s->command.max_signals);
    } else {
      skip_.begin(s->command.input);
    }
  }
  return holds();
}

bool ChannelCoordination::hold_cut_until_locked(const interp::Command& c,
                                                std::uint64_t cycle) noexcept {
  using interp::Op;
  const bool cuts = c.op == Op::linear || c.op == Op::arc || c.op == Op::thread;
  if (!cuts ||
      !coupling_.lock_pending(coordination::CouplingInputs{cycle, received_, exchange_.uses()})) {
    return false;
  }
  return hold(LockWaitStop{c});
}

bool ChannelCoordination::holds_before_motion() const noexcept {
  const auto* overload = std::get_if<OverloadStop>(&held_);
  return holds() &&
         (!std::holds_alternative<SkipStop>(held_) || skip_in(coordination::SkipPhase::arming)) &&
         (overload == nullptr || overload->phase == OverloadPhase::start);
}

void ChannelCoordination::run_held(std::uint64_t cycle,
                                   std::span<const AxisFeedbackView> feedback) noexcept {
  std::visit([&](auto& b) { run(b, cycle, feedback); }, held_);
}

void ChannelCoordination::run_held_if_partner_lost(
    std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept {
  const std::uint32_t callee = waiting_for_call();
  const bool waits_for_lost =
      (std::holds_alternative<SyncStop>(held_) &&
       (mark_.barrier().missing() & lost_partners_).any()) ||
      (callee != 0 && callee <= coordination::kMaxChannels && lost_partners_.test(callee));
  if (waits_for_lost && in_run()) {
    run_held(cycle, feedback);
  }
}

std::optional<interp::ProgramAlarm> ChannelCoordination::foreign_move(
    const interp::AxisVector& from, const interp::Command& c) const {
  for (std::size_t i = 0; c.moves() && i < setup_.axis_count && i < torque_mode_.size(); ++i) {
    if (torque_mode_[i].on && c.to[i] != from[i]) {
      coordination::CoordinationAlarm a;
      a.set(coordination::kAlarmTorqueMode,
            "axis %zu is held in torque mode (G10 L14 P10): G10 L14 P12 (or P10 with 0) before "
            "the program moves it",
            i + 1);
      return interp::ProgramAlarm{a.number, a.text.data(), "", c.line, 0};
    }
  }
  const auto away = c.moves() ? exchange_.foreign_slot(from, c.to) : std::nullopt;
  if (!away) {
    return std::nullopt;
  }
  const coordination::CoordinationAlarm a = exchange_.foreign_move_alarm(*away, received_);
  return interp::ProgramAlarm{a.number, a.text.data(), "", c.line, 0};
}

void ChannelCoordination::abandon_run() noexcept {
  load_.cancel();  // the checks live in the program's run (decision 121)
  overload_.cancel();
  timers_.clear();          // so do the load timers
  torque_mode_speed_ = {};  // so does P11's speed; an axis in torque mode keeps its own
  under_way_ = {};
  withdraw_waits();
  held_ = std::monostate{};
  exchange_.abandon();
  aux_.abandon();
  mark_.abandon();
  calls_.abandon();
}

void ChannelCoordination::stop_serving(coordination::CallOutcome outcome) noexcept {
  release_caller(outcome);
  calls_.stop_serving();
}

void ChannelCoordination::on_alarm() noexcept {
  release_caller(coordination::CallOutcome::failed);
  withdraw_waits();
}

void ChannelCoordination::push_release(const coordination::CallRelease& release) noexcept {
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

void ChannelCoordination::release_caller(coordination::CallOutcome outcome) noexcept {
  if (const auto release = calls_.release_caller(outcome)) {
    push_release(*release);
  }
}

void ChannelCoordination::release_polygon() noexcept {
  if (const auto off = coupling_.polygon_on_reset(received_)) {
    out_.polygon_sync = *off;
    out_.polygon_sync_due = true;
  }
  if (coupling_.cam_on_reset(received_)) {
    out_.cam_sync = &coupling_.cam();
  }
  if (coupling_.egb_on_reset(received_)) {
    out_.egb_sync = coupling_.egb();
    out_.egb_sync_due = true;
  }
}

bool ChannelCoordination::watch_gear_box(std::uint64_t cycle) noexcept {
  if (!coupling_.egb_lost(coordination::CouplingInputs{cycle, received_, exchange_.uses()})) {
    return false;
  }
  raise(coupling_.alarm(), out_.line);
  return true;
}

void ChannelCoordination::take_gear_box_angle() noexcept {
  if (const auto change = coupling_.egb_hand_over(received_)) {
    commanded_[change->slot] = change->at;
    out_.egb_sync = coupling_.egb();
    out_.egb_sync_due = true;
  }
}

void ChannelCoordination::leave_position_control() noexcept {
  spindle_mode_.leave();
  if (setup_.spindle_c_slot && *setup_.spindle_c_slot < interp::kMaxChannelAxes) {
    exchange_.set_use(*setup_.spindle_c_slot, SlotUse::speed_control);
  }
}

std::uint32_t ChannelCoordination::waiting_for_call() const noexcept {
  return std::holds_alternative<CallStop>(held_) ? calls_.waiting_for() : 0;
}

const coordination::AuxRequestOut* ChannelCoordination::waiting_for_fin() const noexcept {
  return std::holds_alternative<AuxStop>(held_) && aux_.sent() && in_run() ? &aux_.request()
                                                                           : nullptr;
}

int ChannelCoordination::waiting_g() const noexcept {
  return std::holds_alternative<ExchangeStop>(held_) && in_run() ? exchange_.waiting_g() : 0;
}

bool ChannelCoordination::in_run() const noexcept {
  return out_.state == ChannelState::running || out_.state == ChannelState::waiting ||
         out_.state == ChannelState::hold;
}

bool ChannelCoordination::under_position_control() const noexcept {
  return setup_.spindle_c_slot && exchange_.use(*setup_.spindle_c_slot) == SlotUse::commanded;
}

bool ChannelCoordination::stands_at_command(std::span<const AxisFeedbackView> feedback,
                                            std::size_t axis) const noexcept {
  const double width = axis < setup_.in_position.size() ? setup_.in_position[axis] : 0.0;
  return axis >= feedback.size() || axis >= commanded_.size() ||
         std::fabs(feedback[axis].act - commanded_[axis]) <= width;
}

std::uint32_t ChannelCoordination::probe_axes(int input) const noexcept {
  std::uint32_t probes = 0;
  for (std::size_t i = 0; i < setup_.axis_count && i < setup_.probe_inputs.size(); ++i) {
    const bool commanded = !exchanges() || exchange_.use(i) == SlotUse::commanded;
    probes |= setup_.probe_inputs[i] == input && commanded ? 1U << i : 0U;
  }
  return probes;
}

ChannelCoordination::TorqueLimit ChannelCoordination::skip_torque_limit(const interp::Command& c,
                                                                        std::size_t i) noexcept {
  if (c.torque_skip) {
    return i == c.skip_axis && c.torque_limit > 0.0 ? TorqueLimit{c.torque_limit, c.deviation}
                                                    : TorqueLimit{};
  }
  // Held back at the ratio is the load reaching it: the skip needs no following error beyond.
  return c.load_skip && i < c.load_ratio.size() ? TorqueLimit{c.load_ratio[i], 0.0} : TorqueLimit{};
}

std::uint32_t ChannelCoordination::torque_axes(const SkipStop& s) const noexcept {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < setup_.axis_count && i < setup_.torque_axes.size(); ++i) {
    const bool wired = setup_.torque_axes[i] && (!exchanges() || commands_axis(i));
    bits |= wired && skip_torque_limit(s.command, i).limit > 0.0 ? 1U << i : 0U;
  }
  return bits;
}

void ChannelCoordination::block_started(const QueuedBlock& b) noexcept {
  under_way_ = coordination::MoveUnderWay{b.moves, b.feed};
  for (std::size_t i = 0; i < setup_.axis_count && i < torque_.size(); ++i) {
    if (((b.moves >> i) & 1U) != 0 && !b.sets_torque_limit) {
      torque_[i] = TorqueLimit{};
    }
  }
}

bool ChannelCoordination::skip_signal_on(int signal) const noexcept {
  const int bit = setup_.skip_signals[static_cast<std::size_t>(signal - 1)];
  return bit >= 0 && bit < 64 && ((plc_inputs_ >> bit) & 1U) != 0;
}

bool ChannelCoordination::skip_signal_gone(int signal) const noexcept {
  return aux_.plc_gone() || setup_.skip_signals[static_cast<std::size_t>(signal - 1)] < 0;
}

void ChannelCoordination::watch_skip(std::span<const AxisFeedbackView> feedback) noexcept {
  const auto* skip = std::get_if<SkipStop>(&held_);
  if (skip == nullptr) {
    return;
  }
  const int signal = skip->command.skip_signal;
  const bool stop =
      signal != 0 ? skip_.watch_signal(feedback, skip_signal_on(signal), skip_signal_gone(signal))
      : skip->command.multi_skip ? skip_.watch_multi(feedback)
                                 : skip_.watch(feedback, skip_axes(*skip));
  if (stop) {
    host_.stop_move();  // and drop the rest of the move
  }
}

void ChannelCoordination::raise_if_queued_moves(std::size_t s, const char* why) noexcept {
  const int moving_line = queued_.first_moving(s, commanded_[s]);
  if (moving_line != 0 &&
      (out_.state == ChannelState::running || out_.state == ChannelState::hold)) {
    char text[128];
    std::snprintf(text, sizeof text, "%c %s", setup_.slots[s].address, why);
    host_.raise(exchange_.use(s) == SlotUse::follows ? coordination::kAlarmAxisFollows
                                                     : coordination::kAlarmAxisAway,
                text, moving_line, static_cast<int>(s + 1));
  }
}

ChannelEvent ChannelCoordination::block_event(const HeldBlock& b,
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

void ChannelCoordination::start_held(HeldBlock& b) noexcept {
  if (b.started) {
    return;
  }
  b.started = true;
  out_.block = b.n;
  out_.line = b.line;
  out_.modal = b.modal;
  push_event(block_event(b, ChannelEventKind::block_started));
}

void ChannelCoordination::end_held(const HeldBlock& b) noexcept {
  push_event(block_event(b, ChannelEventKind::block_ended));
  held_ = std::monostate{};  // `b` is gone from here on
}

void ChannelCoordination::run(SyncStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  const coordination::SyncMarkStep step =
      mark_.step({active_, halted_partners_, lost_partners_, writes_pending()});
  if (mark_.arrived_now()) {
    out_.arrival = mark_.barrier().current();
    out_.arrival_due = true;
    push_event(block_event(b.block, ChannelEventKind::sync_arrive));
    host_.set_state(ChannelState::waiting);
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
      host_.set_state(ChannelState::running);
      break;
    case coordination::SyncMarkStep::done:
      break;
  }
  end_held(b.block);
}

void ChannelCoordination::run(CallStop& b, std::uint64_t cycle,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (calls_.step(cycle, lost_partners_, writes_pending())) {
    case coordination::CallStep::pending:
      return;
    case coordination::CallStep::waiting:
      host_.set_state(ChannelState::waiting);
      return;
    case coordination::CallStep::alarm:
      raise(calls_.alarm(), b.block.line);
      return;
    case coordination::CallStep::send:
      out_.call = calls_.call();
      out_.call_due = true;
      push_event(block_event(b.block, ChannelEventKind::subcall));
      if (calls_.call().wait) {
        host_.set_state(ChannelState::waiting);
        return;
      }
      break;
    case coordination::CallStep::done:
      break;
  }
  end_held(b.block);
  host_.set_state(ChannelState::running);
}

void ChannelCoordination::run(ReleaseStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  // G145: the caller goes on; this program goes on too (spec dafeng §3.4).
  start_held(b.block);
  release_caller(CallOutcome::released);  // no caller, or released before: nothing
  end_held(b.block);
}

void ChannelCoordination::run(ExchangeStop& b, std::uint64_t cycle,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (exchange_.step(cycle, received_, commanded_)) {
    case coordination::ExchangeStep::sent:
      host_.set_state(ChannelState::waiting);
      return;
    case coordination::ExchangeStep::waiting:
      return;
    case coordination::ExchangeStep::alarm:
      raise(exchange_.alarm(), b.block.line);
      return;
    case coordination::ExchangeStep::done:
      if (exchange_.took_over()) {
        host_.restart_at_commanded();
      }
      break;
  }
  end_held(b.block);
  host_.set_state(ChannelState::running);
}

void ChannelCoordination::run(AuxStop& b, std::uint64_t /*cycle*/,
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
    (void)host_.queue_command(command);  // a refusal is a source alarm, raised in its turn
    return;
  }
  end_held(b.block);
}

void ChannelCoordination::run(CouplingStop& b, std::uint64_t cycle,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  switch (coupling_.step(coordination::CouplingInputs{cycle, received_, exchange_.uses()})) {
    case coordination::CouplingStep::waiting:
      return;
    case coordination::CouplingStep::alarm:
      raise(coupling_.alarm(), b.block.line);
      return;
    case coordination::CouplingStep::send:
      if (coupling_.kind() == coordination::CouplingKind::egb) {
        out_.egb_sync = coupling_.egb();
        out_.egb_sync_due = true;
      } else if (coupling_.kind() == coordination::CouplingKind::cam) {
        out_.cam_sync = &coupling_.cam();
      } else if (coupling_.kind() == coordination::CouplingKind::polygon) {
        out_.polygon_sync = coupling_.polygon();
        out_.polygon_sync_due = true;
        if (coupling_.slot_change().to == coordination::SlotChange::To::follows) {
          // A servo polygon axis: no valid setpoint from the cycle its node takes G51.2 in.
          exchange_.set_use(coupling_.slot_change().slot, SlotUse::follows);
        }
      } else if (coupling_.axis()) {
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
    // The axis stands where its master (or G80.4's gear box) took it: the program goes on from
    // there; the gear box's node takes its offset off in the same cycle.
    commanded_[change.slot] = change.at;
    exchange_.set_use(change.slot, coordination::SlotUse::commanded);
    host_.restart_at_commanded();
    if (coupling_.kind() == coordination::CouplingKind::egb) {
      out_.egb_sync = coupling_.egb();
      out_.egb_sync_due = true;
    }
  }
  end_held(b.block);
}

void ChannelCoordination::run(ModeStop& b, std::uint64_t /*cycle*/,
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
    host_.restart_at_commanded();
  } else if (!spindle_mode_.position_control()) {
    leave_position_control();
  }
  end_held(b.block);
}

void ChannelCoordination::run(SkipStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> feedback) noexcept {
  if (!b.at_front) {
    // G160 or G31 P98/P99 at the front: its limits stand from here on.
    b.at_front = true;
    if (b.command.torque_skip) {
      skip_.begin_torque(b.command.skip_axis);
    } else if (b.command.load_skip) {
      skip_.begin_load(b.command.input, b.command.skip);
    }
    const std::uint32_t limited = torque_axes(b);
    for (std::size_t i = 0; i < setup_.axis_count && i < torque_.size(); ++i) {
      if (((limited >> i) & 1U) != 0) {
        torque_[i] = skip_torque_limit(b.command, i);
      }
    }
  }
  if (skip_.phase() == coordination::SkipPhase::arming) {
    const int signal = b.command.skip_signal;
    switch (signal != 0 ? skip_.arm_signal(skip_signal_on(signal), skip_signal_gone(signal))
                        : skip_.arm(feedback, skip_axes(b))) {
      case coordination::SkipArming::waiting:
        return;
      case coordination::SkipArming::alarm:
        raise(skip_.alarm(), b.command.line);
        return;
      case coordination::SkipArming::armed:
        break;
    }
    if (host_.queue_command(b.command)) {
      skip_.start_moving();
    } else {
      held_ = std::monostate{};  // the planner refused it: its alarm (source_alarm_) comes next
    }
    return;
  }
  if (skip_.lost()) {  // the PLC went away under a G31 P, a G31.8 lost edges: stopped, alarm
    raise(skip_.alarm(), b.command.line);
    return;
  }
  // G31.8 at its end point: the edges its axis passed are latched when the axis passes them,
  // which lags the command by the drive's following error; they count until it stands there.
  if (b.command.multi_skip && skip_.phase() == coordination::SkipPhase::moving &&
      !stands_at_command(feedback, b.command.skip_axis)) {
    return;
  }
  // The move ended (its end reached without the signal, or stopped at it) and its block too.
  if (b.command.multi_skip) {
    host_.multi_skip_result(skip_.latched());
  } else {
    host_.skip_result(skip_.skipped(), skip_.where(commanded_));
  }
  held_ = std::monostate{};
}

void ChannelCoordination::run(TorqueDataStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  start_held(b.block);
  if (b.limit) {
    // G10 L14 P9: from here on the named axes' drives take their new limits (0: none).
    for (std::size_t i = 0; i < setup_.axis_count && i < programmed_torque_.size(); ++i) {
      if (((b.axes >> i) & 1U) != 0) {
        programmed_torque_[i] = b.values[i];
      }
    }
  } else {
    // G10 L14 P0/P1 and P2-P5: J in whole cycles, at least one.
    coordination::LoadMonitor::Percent loads{};
    std::copy_n(b.values.begin(), std::min(b.values.size(), loads.size()), loads.begin());
    const auto cycles = static_cast<std::uint64_t>(std::ceil(b.filter_s / setup_.cycle_s - 1e-9));
    if (b.timer != 0) {
      timers_.start(b.timer, b.axes, loads, cycles);
    } else {
      load_.set(
          b.every_move ? coordination::LoadWatch::every_move : coordination::LoadWatch::feed_moves,
          b.axes, loads, cycles);
    }
  }
  end_held(b.block);
}

void ChannelCoordination::run(LoadTimerStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  // G10 L14 P20-P51: every block before it ended, so its timer holds their whole time.
  start_held(b.block);
  coordination::LoadTimers::Values seconds{};
  std::copy_n(b.seconds.begin(), std::min(b.seconds.size(), seconds.size()), seconds.begin());
  const std::uint32_t met =
      timers_.check(b.timer, b.longer, b.axes, seconds, setup_.cycle_s, b.variable);
  if (met != 0 && !b.variable) {
    raise(timers_.alarm(), b.block.line);
    return;
  }
  host_.load_timer_result(met);
  end_held(b.block);
}

bool ChannelCoordination::watch_load(std::span<const AxisFeedbackView> feedback) noexcept {
  const auto axes = feedback.first(std::min(feedback.size(), setup_.axis_count));
  if (!timers_.step(axes, under_way_)) {
    raise(timers_.alarm(), out_.line);
    return true;
  }
  if (load_.watch() == coordination::LoadWatch::off || !load_.step(axes, under_way_)) {
    return false;
  }
  raise(load_.alarm(), out_.line);
  return true;
}

void ChannelCoordination::run(WaitStop& b, std::uint64_t /*cycle*/,
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

void ChannelCoordination::run(TorqueModeStop& b, std::uint64_t /*cycle*/,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  // G10 L14 P10-P12 (L5143-5209): every block before it ended, so the axes stand.
  start_held(b.block);
  bool back = false;
  for (std::size_t i = 0; i < setup_.axis_count && i < torque_mode_.size(); ++i) {
    if (((b.axes >> i) & 1U) == 0) {
      continue;
    }
    const double param_speed =
        i < setup_.torque_mode_speeds.size() ? setup_.torque_mode_speeds[i] : 0.0;
    TorqueMode& m = torque_mode_[i];
    if (b.p == 11) {
      torque_mode_speed_[i] = b.values[i];
      m.speed = m.on ? b.values[i] : m.speed;  // an axis in torque mode takes it at once
      continue;
    }
    if (b.p == 10 && b.values[i] != 0.0) {
      m = TorqueMode{true, b.values[i],
                     torque_mode_speed_[i] > 0.0 ? torque_mode_speed_[i] : param_speed};
      continue;
    }
    // P10 α0 or P12: back to position mode where the motor took the axis; the program goes on
    // from there (as after G141).
    if (m.on && i < received_.size()) {
      commanded_[i] = received_[i].channel_cmd();
      back = true;
    }
    m = TorqueMode{};
    if (b.p == 12) {
      programmed_torque_[i] = b.values[i];  // P12 α: the torque limit from here on (0: none)
    }
  }
  if (back) {
    host_.restart_at_commanded();
  }
  end_held(b.block);
}

void ChannelCoordination::run(LockWaitStop& b, std::uint64_t cycle,
                              std::span<const AxisFeedbackView> /*feedback*/) noexcept {
  // Every block before it ended: the cut starts once the slave is locked.
  if (coupling_.lock_pending(coordination::CouplingInputs{cycle, received_, exchange_.uses()})) {
    return;
  }
  const interp::Command command = b.command;
  held_ = std::monostate{};
  (void)host_.queue_command(command);  // a refusal is a source alarm, raised in its turn
}

}  // namespace mcnc::channel
