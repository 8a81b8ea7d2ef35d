#pragma once
// The channel's cyclic core: the channel state machine (reset / idle / running / hold / waiting
// / alarm) that pulls canonical commands from its CommandSource as far as its look-ahead planner
// takes them, steps the planner once per cycle, holds every exact stop until the axes are in
// position, and yields one setpoint per axis per cycle plus the events of that cycle
// (cycle_output.hpp). A block that stops read-ahead (read_ahead_stop.hpp: G04.1, G144/G145,
// G140-G142, aux codes, couplings, M18/M17, G31, G04 I/PS) is handed to the channel's
// coordination (channel_coordination.hpp), which runs it on its state machine once the blocks
// before it ended. Pure and deterministic: inputs and cycle number in, outputs out.
#include "channel/control/block_queue.hpp"
#include "channel/control/channel_coordination.hpp"
#include "channel/control/channel_setup.hpp"
#include "channel/control/cycle_output.hpp"
#include "channel/interp/command_source.hpp"
#include "channel/motion/motion_planner.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace mcnc::channel {

// Alarm numbers the channel itself raises (program alarms come from the interpreter).
inline constexpr int kAlarmPlannerRejected = 1200;
inline constexpr int kAlarmAxisAlarm = 1201;
inline constexpr int kAlarmAxisLost = 1202;
inline constexpr int kAlarmEmergencyStop = 1203;
inline constexpr int kAlarmCoordinationLost = 1214;  // shared writes or partner events lost
using coordination::kAlarmAuxRefused;
using coordination::kAlarmAuxTimeout;
using coordination::kAlarmAxisAway;
using coordination::kAlarmAxisFollows;
using coordination::kAlarmAxisSync;
using coordination::kAlarmCallBusy;
using coordination::kAlarmCallCycle;
using coordination::kAlarmCallFailed;
using coordination::kAlarmCallRefused;
using coordination::kAlarmCallTimeout;
using coordination::kAlarmInputTimeout;
using coordination::kAlarmNotOwner;
using coordination::kAlarmProbeNotArmed;
using coordination::kAlarmRequestRefused;
using coordination::kAlarmSlaveSpindle;
using coordination::kAlarmSpeedTimeout;
using coordination::kAlarmSpindleNotAtRest;
using coordination::kAlarmSyncDeadlock;
using coordination::kAlarmSyncGroup;
using coordination::kAlarmSyncMismatch;
using coordination::kAlarmSyncPartnerLost;
using coordination::kAlarmSyncTableFull;

class ChannelController : private ChannelHost {
 public:
  ChannelController(ChannelSetup setup, interp::CommandSource& source,
                    motion::MotionPlanner& planner);

  // Cycle start: the program runs as soon as every axis is enabled (from idle or reset); in
  // feed hold it goes on. A start while the program runs or waits is ignored, as on a control
  // panel.
  void request_start() noexcept {
    if (out_.state == ChannelState::hold) {
      resume_requested_ = true;
    } else if (out_.state != ChannelState::running && out_.state != ChannelState::waiting) {
      start_requested_ = true;
      mdi_requested_ = false;
    }
  }
  // MDI: the blocks prepared in the source (CommandSource::start_mdi) run as a cycle start runs
  // the program, from idle (from reset once the axes are enabled). Their end brings the channel
  // back to idle without a program end; the next cycle start runs the channel's program.
  // Ignored while the channel runs, holds or waits.
  void request_mdi() noexcept {
    if (may_change_program()) {
      start_requested_ = true;
      mdi_requested_ = true;
    }
  }
  // Whether the channel's program may change now: it stands in reset or idle and no reset
  // ramps down. A start asked for waits for a program being checked (set_program_pending).
  [[nodiscard]] bool may_change_program() const noexcept {
    return (out_.state == ChannelState::reset || out_.state == ChannelState::idle) && !resetting_;
  }
  // A program or MDI blocks are being checked for this channel: a cycle start waits for them.
  void set_program_pending(bool pending) noexcept { program_pending_ = pending; }
  // Counts the runs started from idle or reset and the resets (E-stop included): MDI blocks
  // asked for under another count are stale (a reset or another run came first).
  [[nodiscard]] std::uint64_t run_epoch() const noexcept { return run_epoch_; }
  // Feed hold: a running channel's path decelerates to a stop and stays (state hold) until a
  // cycle start; the spindle keeps turning. Ignored when the channel does not run (a channel
  // waiting at a mark or for an answer moves nothing).
  void request_feed_hold() noexcept { hold_requested_ = true; }
  // The operator panel's overrides, in percent, clamped: feed 0-200, rapid 0-100 (as the planner
  // applies them), spindle 50-120 (before the G50 S limit of G96). A value that is not a number
  // is ignored.
  // Single block: a running program stops (state hold) at the end of each motion block it
  // reaches from now on, blended corners included, until a cycle start runs the next; blocks
  // that move nothing (waits, M codes) pass. Turned off at a stop, the program stays stopped
  // until the cycle start.
  void set_single_block(bool on) noexcept;
  [[nodiscard]] bool single_block() const noexcept { return single_block_; }
  void set_feed_override(double percent) noexcept;
  void set_rapid_override(double percent) noexcept;
  void set_spindle_override(double percent) noexcept;
  // Reset (the RESET key): a moving channel ramps down with the planner's reset deceleration;
  // then the alarms are cleared, the program rewinds and the channel is in reset. It comes back
  // to idle once every axis is enabled again without an alarm (the axis nodes reset their drives
  // on the same command); a cycle start then runs the program from its start.
  void request_reset() noexcept {
    reset_requested_ = true;
    start_requested_ = false;  // a start asked for after this reset still counts
    mdi_requested_ = false;
  }
  // Emergency stop: motion ends at once, the channel goes to reset and stays there.
  void emergency_stop() noexcept { estop_requested_ = true; }
  // A program alarm found before the run (e.g. when the program was loaded): raised at the next
  // cycle, so it stands in that cycle's events.
  void report_alarm(const interp::ProgramAlarm& alarm) { pending_alarm_ = alarm; }
  // An owned axis's node is gone (`axis` counts the spindles after the axes): alarm and hold,
  // also after an E-stop (a host cut off: its loss and the E-stop come together).
  void axis_lost(std::size_t axis) noexcept;

  // Coordination inputs, given before cycle(): another channel's G04.1 arrival (applied in
  // the order sent), the channels in automatic operation as their status stamped N-1 says
  // (running, feed hold, waiting) and those stopped by an alarm, and a channel whose process is
  // gone.
  void on_arrival(const coordination::SyncArrival& arrival) noexcept {
    coordination_.on_arrival(arrival);
  }
  void set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept {
    coordination_.set_partner(channel, status);
  }
  void partner_lost(std::uint32_t channel) noexcept { coordination_.partner_lost(channel); }
  // Events from another channel did not fit this channel's receive queue: what the channels
  // share can no longer be trusted (an alarm).
  void coordination_lost() noexcept { coordination_.coordination_lost(); }
  // G144 calls addressed to this channel (run when it is idle, else refused), and the end of a
  // call this channel made.
  void on_call(const CallRequest& call) noexcept { coordination_.on_call(call); }
  void on_call_release(const CallRelease& release) noexcept {
    coordination_.on_call_release(release);
  }
  // The PLC's answer to an aux request of this channel (applied from the cycle after it was
  // sent, as every event).
  void on_aux_answer(const PlcAnswer& answer) noexcept { coordination_.on_aux_answer(answer); }
  // The PLC node is gone: a request waiting for it, and every later one, is refused.
  void plc_lost() noexcept { coordination_.plc_lost(); }
  // The PLC's inputs as its status stamped N-1 reports them (bit k: signal k on): G04 I.
  void set_plc_inputs(std::uint64_t inputs) noexcept { coordination_.set_plc_inputs(inputs); }

  // One cycle. `feedback` holds one entry per channel axis, then one per spindle.
  const CycleOutput& cycle(std::uint64_t cycle,
                           std::span<const AxisFeedbackView> feedback) noexcept;
  // G140/G141/G142: whether the channel commands axis `slot` now (owns it and took over its
  // position); a slot it does not command is a virtual axis or with another channel.
  [[nodiscard]] bool commands_axis(std::size_t slot) const noexcept {
    return slot < kMaxChannelAxes && coordination_.commands_axis(slot);
  }

  [[nodiscard]] ChannelState state() const noexcept { return out_.state; }
  [[nodiscard]] const ChannelAlarm& last_alarm() const noexcept { return alarm_; }
  [[nodiscard]] std::size_t alarm_count() const noexcept { return alarm_count_; }
  [[nodiscard]] const AxisVector& commanded() const noexcept { return commanded_; }
  // The spindle's position at C = 0 (whole turns) of the last position control (0: none yet).
  [[nodiscard]] double spindle_c_base() const noexcept { return coordination_.spindle_c_base(); }
  // The G04.1 marks as this channel sees them: the mark it waits at and whom it misses.
  [[nodiscard]] const coordination::SyncBarrier& sync() const noexcept {
    return coordination_.sync();
  }
  // The G144 call this channel runs for another channel: its id (0: none) and caller.
  [[nodiscard]] std::uint64_t serving_call() const noexcept {
    return coordination_.calls().serving_call();
  }
  [[nodiscard]] std::uint32_t serving_caller() const noexcept {
    return coordination_.calls().serving_caller();
  }
  // The operator panel's overrides as applied, as fractions (1.0: 100 %).
  [[nodiscard]] double feed_override() const noexcept { return feed_override_; }
  [[nodiscard]] double rapid_override() const noexcept { return rapid_override_; }
  [[nodiscard]] double spindle_override() const noexcept { return spindle_override_; }
  // G144 H1: the channel this one's sent call waits for, 0 when none.
  [[nodiscard]] std::uint32_t waiting_for_call() const noexcept {
    return coordination_.waiting_for_call();
  }
  // The M or T code whose answer (FIN) from the PLC the channel waits for, or nullptr.
  [[nodiscard]] const AuxRequestOut* waiting_for_fin() const noexcept {
    return coordination_.waiting_for_fin();
  }
  // The axis exchange the channel waits for: its G code (140, 141, 142; 0: none) and the slot
  // (AxisRequestOut::kAllSlots for G142).
  struct ExchangeWait {
    int g = 0;
    std::size_t slot = 0;
  };
  [[nodiscard]] ExchangeWait waiting_for_exchange() const noexcept {
    const int g = coordination_.waiting_g();
    return g == 0 ? ExchangeWait{} : ExchangeWait{g, coordination_.waiting_slot()};
  }
  // A run is under way (not stopped by an alarm or a reset): what it waits for is real.
  [[nodiscard]] bool in_run() const noexcept {
    return out_.state == ChannelState::running || out_.state == ChannelState::waiting ||
           out_.state == ChannelState::hold;
  }

 private:
  // What the coordination asks of the channel (ChannelHost).
  void set_state(ChannelState state) noexcept override;
  void raise(int number, const char* text, int line, int axis) noexcept override {
    raise(number, text, line, 0, axis);
  }
  bool queue_command(const interp::Command& c) noexcept override;
  void restart_at_commanded() noexcept override;
  void stop_move() noexcept override { planner_.reset(); }
  void skip_result(bool skipped, const AxisVector& where) noexcept override {
    source_.skip_result(skipped, where, commanded_);
  }
  void multi_skip_result(std::span<const double> latched) noexcept override {
    source_.multi_skip_result(latched, commanded_);
  }
  void load_timer_result(std::uint32_t axes) noexcept override { source_.load_timer_result(axes); }
  void overload_result(std::uint32_t overloads, std::uint64_t dropped_block) noexcept override {
    source_.overload_result(overloads, dropped_block, commanded_);
  }

  const CycleOutput& run_cycle(std::uint64_t cycle,
                               std::span<const AxisFeedbackView> feedback) noexcept;
  // `file`: the file the alarm is in; without it, that of the block under way.
  void raise(int number, const char* text, int line, int column, int axis,
             std::string_view file = {}) noexcept;
  void raise(const coordination::CoordinationAlarm& alarm, int line) noexcept {
    raise(alarm.number, alarm.text.data(), line, 0, alarm.axis);
  }
  void raise_program_alarm(const interp::ProgramAlarm& alarm) noexcept;
  bool all_enabled(std::span<const AxisFeedbackView> feedback) const noexcept;
  // Every axis's actual position within its in-position width of `at`.
  bool in_position(std::span<const AxisFeedbackView> feedback, const AxisVector& at) const noexcept;
  void run_blocks(std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  // The program's end block, once everything before it ran: its events, then idle.
  void end_program(std::uint64_t cycle, bool in_pos) noexcept;
  void fill(std::uint64_t cycle) noexcept;
  void block_events(const motion::MotionOutput& m,
                    std::span<const AxisFeedbackView> feedback) noexcept;
  void hold_outputs(bool valid) noexcept;
  void finish_reset() noexcept;
  // Alarm 1202 for the axis or spindle axis_lost() named, once, unless an alarm stands.
  void tell_lost_axis() noexcept;
  void forget_program_run() noexcept;  // the queue, the end and the alarms of a program run
  // Starts (or repeats) the program of the call this channel serves.
  void start_served_call(std::uint64_t cycle) noexcept;
  void take_calls(std::uint64_t cycle) noexcept;

  ChannelSetup setup_;
  interp::CommandSource& source_;
  motion::MotionPlanner& planner_;
  CycleOutput out_{};
  ChannelAlarm alarm_{};
  std::size_t alarm_count_ = 0;
  AxisVector commanded_{};
  bool position_known_ = false;
  bool start_requested_ = false;
  bool mdi_requested_ = false;    // the start asked for runs the MDI blocks
  bool mdi_run_ = false;          // the run under way is MDI blocks
  bool program_pending_ = false;  // a program being checked: a start waits
  std::uint64_t run_epoch_ = 0;
  bool resume_requested_ = false;
  bool hold_requested_ = false;
  bool single_block_ = false;
  std::uint64_t single_block_stop_ = 0;  // the block a single block stop was last made after
  double feed_override_ = 1.0;
  double rapid_override_ = 1.0;
  double spindle_override_ = 1.0;
  bool estop_requested_ = false;
  bool reset_requested_ = false;
  bool resetting_ = false;       // ramping down for a reset
  bool after_reset_ = false;     // reset done, waiting for the axes to be enabled without alarms
  bool estopped_ = false;        // an emergency stop: a reset does not undo it
  std::size_t lost_axis_ = 0;    // axis index + 1
  bool lost_axis_told_ = false;  // alarm 1202 raised for it (once: a lost node never returns)
  bool halted_ = false;          // an alarm or emergency stop ended the run
  BlockQueue queued_;            // the blocks the planner took, until their end event
  interp::Command end_{};        // the program end, once pulled
  bool end_pulled_ = false;
  bool end_started_ = false;
  std::optional<interp::ProgramAlarm> source_alarm_;  // raised when the blocks before it ran
  std::optional<interp::ProgramAlarm> pending_alarm_;
  bool first_cycle_ = true;
  int spindle_queued_ = 0;  // the first spindle's direction as the pulled blocks leave it
  // G04.1, G144/G145, G140-G142, aux codes, couplings, M18/M17, G31, G04 I/PS: the block that
  // stops read-ahead and the machines that run it (after queued_ and commanded_, which it
  // reads).
  ChannelCoordination coordination_;
};

}  // namespace mcnc::channel
