#pragma once
// The channel's coordination with the other channels, its axis nodes and the PLC: the state
// machines of channel/coordination composed around the block that stops read-ahead
// (read_ahead_stop.hpp). The controller hands that block over when it pulls it and runs it here
// once every block before it ended: SyncMark (around SyncBarrier), SubCall, AxisExchange (which
// also keeps what the channel does with each axis slot), AuxHandshake, CouplingRequest,
// SpindleMode, SkipProbe and ConditionBlock. Their step outcomes become the cycle's events and
// outputs here, and state changes, alarms and planner moves through the ChannelHost (the
// controller). Pure and deterministic, like the controller; nothing allocates or throws.
#include "channel/control/block_queue.hpp"
#include "channel/control/channel_setup.hpp"
#include "channel/control/cycle_output.hpp"
#include "channel/control/read_ahead_stop.hpp"
#include "channel/coordination/aux_handshake.hpp"
#include "channel/coordination/axis_exchange.hpp"
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/channel_state.hpp"
#include "channel/coordination/coupling_request.hpp"
#include "channel/coordination/load_monitor.hpp"
#include "channel/coordination/load_timers.hpp"
#include "channel/coordination/skip_probe.hpp"
#include "channel/coordination/spindle_mode.hpp"
#include "channel/coordination/sub_call.hpp"
#include "channel/coordination/sync_mark.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <variant>

namespace mcnc::channel {

// What the coordination asks of the channel that composes it.
class ChannelHost {
 public:
  virtual void set_state(coordination::ChannelState state) noexcept = 0;
  virtual void raise(int number, const char* text, int line, int axis) noexcept = 0;
  // The planner takes `c` (false: refused; the source's alarm comes in its turn).
  virtual bool queue_command(const interp::Command& c) noexcept = 0;
  // The interpreter and the planner go on from the commanded position (an axis taken over).
  virtual void restart_at_commanded() noexcept = 0;
  // G31: the signal came; the move stops at once (the planner's reset deceleration).
  virtual void stop_move() noexcept = 0;
  // G31's move is over: whether it skipped and where the axes stand then.
  virtual void skip_result(bool skipped, const interp::AxisVector& where) noexcept = 0;
  // G31.8's move is over: the positions its probe latched, in order (none: no signal came).
  virtual void multi_skip_result(std::span<const double> latched) noexcept = 0;
  // G10 L14 P20-P51 ran: the axes (bit i: channel axis i) that met its condition.
  virtual void load_timer_result(std::uint32_t axes) noexcept = 0;
  // A G10 L14 P7/P8 in-feed is over after `overloads` overloads; `dropped_block` (0: none) ends
  // its block where the axes stand (CommandSource::overload_result).
  virtual void overload_result(std::uint32_t overloads, std::uint64_t dropped_block) noexcept = 0;

 protected:
  ChannelHost() = default;
  ~ChannelHost() = default;
  ChannelHost(const ChannelHost&) = default;
  ChannelHost& operator=(const ChannelHost&) = default;
};

class ChannelCoordination {
 public:
  // Keeps references to all of these: they outlive it (members of the same controller).
  ChannelCoordination(const ChannelSetup& setup, ChannelHost& host, CycleOutput& out,
                      interp::AxisVector& commanded, const BlockQueue& queued);

  // --- Inputs, given before the cycle (ChannelController's public API says what each means).
  void on_arrival(const coordination::SyncArrival& arrival) noexcept;
  void set_partner(std::uint32_t channel, const coordination::PartnerStatus& status) noexcept;
  void partner_lost(std::uint32_t channel) noexcept;
  void coordination_lost() noexcept { coordination_lost_ = true; }
  void on_call(const coordination::CallRequest& call) noexcept;
  void on_call_release(const coordination::CallRelease& release) noexcept;
  void on_aux_answer(const coordination::PlcAnswer& answer) noexcept;
  void plc_lost() noexcept;
  void set_plc_inputs(std::uint64_t inputs) noexcept { plc_inputs_ = inputs; }
  // Events from another channel or shared writes lost since the last call: why (an alarm), or
  // nullptr.
  const char* take_loss() noexcept;

  // --- The cycle: begin_cycle() before the controller's step, end_cycle() after it.
  // Clears the coordination outputs, takes the slots' feedback (an axis lost to another channel
  // under a queued move is an alarm) and builds the views the program sees.
  void begin_cycle(std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  [[nodiscard]] std::span<const coordination::AxisFeedbackView> views() const noexcept {
    return {views_.data(), view_count_};
  }
  // Only commanded axes follow their setpoints; the probes, the spindle's position control and
  // the axis requests of the cycle go out.
  void end_cycle() noexcept;

  // --- The block that stops read-ahead.
  // Holds `stop` and starts its machine; false when it is std::monostate (nothing held).
  bool hold(ReadAheadStop stop) noexcept;
  [[nodiscard]] bool holds() const noexcept {
    return !std::holds_alternative<std::monostate>(held_);
  }
  // A cutting block `c` while a G51.2 or G81.4 that did not wait has not locked yet: held until
  // it has (LockWaitStop); false when `c` may go to the planner.
  bool hold_cut_until_locked(const interp::Command& c, std::uint64_t cycle) noexcept;
  // The held block stops the motion before it for single block: any but a G31 whose move runs.
  [[nodiscard]] bool holds_before_motion() const noexcept;
  // One cycle of the held block, once every block before it ended.
  void run_held(std::uint64_t cycle,
                std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  // The held G04.1 or G144 waits for a channel whose process is gone: one cycle of it, which
  // raises that alarm (1213, 1222). For the cycle an E-stop arrives in, before it ends the wait:
  // across hosts the loss and the E-stop come together, and the alarm says which partner went.
  void run_held_if_partner_lost(std::uint64_t cycle,
                                std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  // A pulled move of an axis the channel does not command from `from`: the alarm it is.
  [[nodiscard]] std::optional<interp::ProgramAlarm> foreign_move(const interp::AxisVector& from,
                                                                 const interp::Command& c) const;
  // G31 while it moves: a latch stops the move.
  void watch_skip(std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  // G31's move, or a G10 L14 P7/P8 in-feed that overloaded, decelerates to a stop.
  [[nodiscard]] bool skip_stopping() const noexcept {
    const auto* o = std::get_if<OverloadStop>(&held_);
    return skip_in(coordination::SkipPhase::stopping) ||
           (o != nullptr && o->phase == OverloadPhase::stopping);
  }
  // The axes a G10 L14 P7/P8 in-feed watches while an overload stops it (0: none).
  [[nodiscard]] std::uint32_t overload_stopped_axes() const noexcept {
    const auto* o = std::get_if<OverloadStop>(&held_);
    return o != nullptr && o->phase == OverloadPhase::stopping ? o->command.overload_axes : 0;
  }
  // G10 L14 P7/P8 while the in-feed moves: an overload of an axis it watches stops the move
  // (channel_overload.cpp).
  void watch_overload(std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  // A queued block starts: a move of an axis under a G160 (or G31 P98/P99) torque limit other
  // than one that sets one cancels it (L5382), and so does G160 P-1.
  void block_started(const QueuedBlock& b) noexcept;
  // G160: axis i's torque limit (percent of the rated torque, 0: none) and skip deviation.
  [[nodiscard]] double torque_limit(std::size_t i) const noexcept { return torque_[i].limit; }
  // G10 L14 P9: axis i's torque limit (percent of the rated torque, 0: none); a G160's or G31
  // P98/P99's stands above it while it lasts.
  [[nodiscard]] double programmed_torque_limit(std::size_t i) const noexcept {
    return programmed_torque_[i];
  }
  // A reset cancels the limits of G10 L14 P9 (decision 120).
  void cancel_programmed_torque_limits() noexcept { programmed_torque_ = {}; }
  // G10 L14 P10: axis i is held in torque mode; its command follows the motor, so it is never
  // out of position, and no block may move it until P10 α0 or P12.
  [[nodiscard]] bool in_torque_mode(std::size_t i) const noexcept {
    return i < torque_mode_.size() && torque_mode_[i].on;
  }
  // A reset with param 5520.1 = 1: every axis in torque mode goes back to position mode where
  // it stands (the channel re-reads its position once its axes are enabled again).
  void leave_torque_mode() noexcept { torque_mode_ = {}; }
  // G10 L14 P0/P1 and the load timers of P2-P5, once per cycle of a run before the motion:
  // true when an axis the block under way moves overloaded, or does not report the load a
  // timer counts (its alarm raised: nothing may move from here on).
  bool watch_load(std::span<const AxisFeedbackView> feedback) noexcept;
  // The block under way ended: no move is under way until the next starts.
  void block_ended() noexcept { under_way_ = {}; }

  // --- Runs and their end.
  void settle_slots() noexcept { exchange_.settle(received_, commanded_); }
  void withdraw_waits() noexcept { exchange_.withdraw(); }
  // No block under way any more (a new run, a reset): every machine lets go of it.
  void abandon_run() noexcept;
  // The served call's hold on its caller ends (once) with `outcome`; no call is served then.
  void stop_serving(coordination::CallOutcome outcome) noexcept;
  // The channel stopped with an alarm: a caller waiting for its G145 stops too, and it takes no
  // axis.
  void on_alarm() noexcept;
  void release_caller(coordination::CallOutcome outcome) noexcept;
  void push_release(const coordination::CallRelease& release) noexcept;
  void leave_position_control() noexcept;  // no program runs: speed control, at rest
  // A reset or an emergency stop: the polygon axis, if it follows, is released (G50.2 P0), the
  // cam's lift taken off its slave (G50.8) and the gear box stopped (param 5320.4).
  void release_polygon() noexcept;
  // Once per cycle of a run: the gear box stopped without G80.4 (its alarm raised: true).
  bool watch_gear_box(std::uint64_t cycle) noexcept;
  // A run starts: the work axis a stopped gear box left off the commanded position (a reset's,
  // an alarm's stop) is commanded where it stands, and its node told.
  void take_gear_box_angle() noexcept;
  coordination::SubCall& calls() noexcept { return calls_; }
  [[nodiscard]] const coordination::SubCall& calls() const noexcept { return calls_; }

  // --- What the channel waits for and commands (ChannelController's accessors).
  [[nodiscard]] bool commands_axis(std::size_t slot) const noexcept {
    return exchange_.use(slot) == coordination::SlotUse::commanded;
  }
  [[nodiscard]] double spindle_c_base() const noexcept { return spindle_mode_.c_base(); }
  [[nodiscard]] const coordination::SyncBarrier& sync() const noexcept { return mark_.barrier(); }
  [[nodiscard]] std::uint32_t waiting_for_call() const noexcept;
  [[nodiscard]] const coordination::AuxRequestOut* waiting_for_fin() const noexcept;
  [[nodiscard]] int waiting_g() const noexcept;
  [[nodiscard]] std::size_t waiting_slot() const noexcept { return exchange_.waiting_slot(); }

 private:
  [[nodiscard]] bool in_run() const noexcept;
  [[nodiscard]] bool exchanges() const noexcept { return exchange_.exchanges(); }
  [[nodiscard]] bool under_position_control() const noexcept;
  [[nodiscard]] bool skip_in(coordination::SkipPhase phase) const noexcept {
    return std::holds_alternative<SkipStop>(held_) && skip_.phase() == phase;
  }
  [[nodiscard]] bool writes_pending() const noexcept {
    return setup_.shared_writes != nullptr && setup_.shared_writes->size() > 0;
  }
  // Axis `axis`'s actual position is within its in-position width of the command.
  [[nodiscard]] bool stands_at_command(std::span<const AxisFeedbackView> feedback,
                                       std::size_t axis) const noexcept;
  // Bit i: axis i's touch probe is on skip input `input` and the channel commands the axis.
  [[nodiscard]] std::uint32_t probe_axes(int input) const noexcept;
  // Bit i: a G160 or G31 P98/P99 limits axis i's torque (its axis, the axes with a load
  // ratio), the channel commands the axis and its drive takes a torque limit.
  [[nodiscard]] std::uint32_t torque_axes(const SkipStop& s) const noexcept;
  // The probes that a G31 or G160 arms and watches: touch probes on the input and torque skips.
  // G31.8: only the probe of the axis it moves, whose position it stores.
  [[nodiscard]] std::uint32_t skip_axes(const SkipStop& s) const noexcept {
    if (s.command.multi_skip) {
      return s.command.skip_axis < 32 ? probe_axes(s.command.input) & (1U << s.command.skip_axis)
                                      : 0U;
    }
    return (s.arm == ProbeArm::torque ? 0U : probe_axes(s.command.input)) | torque_axes(s);
  }
  // G31 P: skip signal `signal` (1-8) on in the PLC's status; the PLC gone (or without it).
  [[nodiscard]] bool skip_signal_on(int signal) const noexcept;
  [[nodiscard]] bool skip_signal_gone(int signal) const noexcept;
  // Alarm (1231, or 1261 for an axis that follows) at the first queued block that moves slot
  // `s`, which the channel no longer commands: "<address> <why>".
  void raise_if_queued_moves(std::size_t s, const char* why) noexcept;
  void raise(const coordination::CoordinationAlarm& alarm, int line) noexcept {
    host_.raise(alarm.number, alarm.text.data(), line, alarm.axis);
  }
  void push_event(const ChannelEvent& event) noexcept { out_.add_event(event); }
  [[nodiscard]] ChannelEvent block_event(const HeldBlock& b, ChannelEventKind kind) const noexcept;
  void start_held(HeldBlock& b) noexcept;      // its start event, once
  void end_held(const HeldBlock& b) noexcept;  // its end event; read-ahead goes on

  void run(std::monostate& /*none*/, std::uint64_t /*cycle*/,
           std::span<const coordination::AxisFeedbackView> /*feedback*/) noexcept {}
  void run(SyncStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(CallStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(ReleaseStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(ExchangeStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(AuxStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(CouplingStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(ModeStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(SkipStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(WaitStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(TorqueDataStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(LoadTimerStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(TorqueModeStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(LockWaitStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  void run(OverloadStop& b, std::uint64_t cycle,
           std::span<const coordination::AxisFeedbackView> feedback) noexcept;
  // G10 L14 P7/P8: the in-feed (again) from where the axes stand, its loads watched.
  void feed_in(OverloadStop& b) noexcept;

  const ChannelSetup& setup_;
  ChannelHost& host_;
  CycleOutput& out_;
  interp::AxisVector& commanded_;
  const BlockQueue& queued_;

  // The block that stops read-ahead, pulled and not passed yet (std::monostate: none). Each
  // kind runs once every block before it ended; the machines hold what outlives it.
  ReadAheadStop held_;

  // G04.1 (the barrier) and G144 / G145 (calls made and served).
  coordination::SyncMark mark_;
  coordination::SubCall calls_;
  coordination::ChannelSet active_;
  coordination::ChannelSet halted_partners_;
  coordination::ChannelSet lost_partners_;
  bool coordination_lost_ = false;
  std::uint64_t writes_lost_seen_ = 0;

  // G140/G141/G142 and what the channel does with each slot; the feedback as it came and as the
  // program sees it.
  coordination::AxisExchange exchange_;
  static constexpr std::size_t kMaxViews = interp::kMaxChannelAxes + 8;  // axes, then spindles
  std::array<coordination::AxisFeedbackView, kMaxViews> views_{};
  std::size_t view_count_ = 0;
  std::span<const coordination::AxisFeedbackView> received_;
  bool was_position_ = false;  // under position control when the cycle began

  // M/S/T codes, couplings, the spindle's mode, G31 and G04 I / G04 PS.
  coordination::AuxHandshake aux_;
  coordination::CouplingRequest coupling_;
  coordination::SpindleMode spindle_mode_;
  std::uint64_t plc_inputs_ = 0;
  coordination::SkipProbe skip_;
  // G160's (and G31 P98/P99's) torque limits, per channel axis: they stay after the skip (a
  // tailstock keeps pressing) until a move of the axis cancels them (decisions 101, 116).
  struct TorqueLimit {
    double limit = 0.0;  // percent of the rated torque, 0: none
    double deviation = 0.0;
  };
  std::array<TorqueLimit, interp::kMaxChannelAxes> torque_{};
  // G10 L14 P9's torque limits, per channel axis (percent, 0: none): modal, until P9 α0 or a
  // reset.
  interp::AxisVector programmed_torque_{};
  // G10 L14 P10-P12, per channel axis: in torque mode at `torque` % of the rated torque, the
  // motor within `speed` rpm; P11's speeds (rpm, 0: param 5521's) for the P10s after it.
  struct TorqueMode {
    bool on = false;
    double torque = 0.0;
    double speed = 0.0;
  };
  std::array<TorqueMode, interp::kMaxChannelAxes> torque_mode_{};
  interp::AxisVector torque_mode_speed_{};
  // G10 L14 P0/P1: the loads watched, over the moves of the block under way.
  coordination::LoadMonitor load_;
  coordination::MoveUnderWay under_way_{};
  // G10 L14 P2-P5: the load timers, over the same moves; P20-P51 read them.
  coordination::LoadTimers timers_;
  // G10 L14 P7/P8: the loads of the in-feed under way, as P1 watches its G01 moves.
  coordination::LoadMonitor overload_;
  // The torque limit a G160 or G31 P98/P99 puts on channel axis i (limit 0: none): G160 its P
  // and Q on its one axis, P98/P99 the axis's load ratio and no deviation (decision 116).
  [[nodiscard]] static TorqueLimit skip_torque_limit(const interp::Command& c,
                                                     std::size_t i) noexcept;
};

}  // namespace mcnc::channel
