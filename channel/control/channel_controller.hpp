#pragma once
// The channel's cyclic core: the channel state machine (reset / idle / running / hold / waiting
// / alarm) that pulls canonical commands from its CommandSource as far as its look-ahead planner
// takes them, steps the planner once per cycle, holds every exact stop until the axes are in
// position, and yields one setpoint per axis per cycle plus the events of that cycle. A block
// that stops read-ahead (read_ahead_stop.hpp: G04.1, G144/G145, G140-G142, aux codes, couplings,
// M18/M17, G31, G04 I/PS) is held until the blocks before it ended, then run by the
// coordination state machine it composes for it: SyncMark (around SyncBarrier), SubCall,
// AxisExchange (which also keeps what the channel does with each axis slot), AuxHandshake,
// CouplingRequest, SpindleMode, SkipProbe and ConditionBlock; the controller maps their step
// outcomes to events, state changes and outputs. Pure and deterministic: inputs and cycle
// number in, outputs out.
#include "channel/control/block_queue.hpp"
#include "channel/control/read_ahead_stop.hpp"
#include "channel/control/shared_write_log.hpp"
#include "channel/coordination/aux_handshake.hpp"
#include "channel/coordination/axis_exchange.hpp"
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/channel_state.hpp"
#include "channel/coordination/condition_wait.hpp"
#include "channel/coordination/coupling_request.hpp"
#include "channel/coordination/skip_probe.hpp"
#include "channel/coordination/spindle_mode.hpp"
#include "channel/coordination/sub_call.hpp"
#include "channel/coordination/sync_barrier.hpp"
#include "channel/coordination/sync_mark.hpp"
#include "channel/interp/command_source.hpp"
#include "channel/motion/motion_planner.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace mcnc::channel {

using interp::AxisVector;
using interp::kMaxChannelAxes;

// The coordination state machines' vocabulary, as the channel's adapters and tests name it.
using coordination::AuxKind;
using coordination::AuxOutcome;
using coordination::AuxRequestOut;
using coordination::AxisFeedbackView;
using coordination::AxisRequestKind;
using coordination::AxisRequestOut;
using coordination::AxisSlot;
using coordination::AxisSyncOut;
using coordination::CallOutcome;
using coordination::CallRelease;
using coordination::CallRequest;
using coordination::ChannelState;
using coordination::MachineAxis;
using coordination::MachineAxisKind;
using coordination::PartnerStatus;
using coordination::PlcAnswer;
using coordination::ProbeSeen;
using coordination::SpindleGroupSetup;
using coordination::SpindleSyncOut;
using coordination::to_string;

struct CommandedAxis {
  double pos = 0.0;
  double vel = 0.0;
  double acc = 0.0;
  bool valid = false;              // false: the axis node holds its position
  ProbeArm probe = ProbeArm::off;  // G31: arm the drive's touch probe
};

enum class ChannelEventKind : std::uint8_t {
  state_changed,
  block_started,  // command.line / command.block
  block_ended,    // the path passed the block's end (an exact stop: and every axis is in position)
  alarm,          // alarm_number / alarm text via last_alarm()
  program_end,    // end_code
  mdi_end,        // MDI blocks ended (end_code: 0 at their text's end, else 30, 2 or 99)
  sync_arrive,    // G04.1 P: the channel arrived at the mark (CycleOutput::arrival)
  sync_release,   // every participant arrived: the channel goes on
  subcall,        // G144: this channel sent CycleOutput::call
  subcall_release,  // this channel released the caller of the call it runs (call_id)
};

struct ChannelEvent {
  ChannelEventKind kind = ChannelEventKind::state_changed;
  ChannelState state = ChannelState::reset;
  int line = 0;
  const std::string* file = nullptr;  // the block's file (nullptr: the main program's)
  std::string_view text;              // block_started: the block's line as written (the file's)
  std::size_t block = 0;
  int end_code = 0;
  int alarm_number = 0;
  AxisVector pos{};           // block_ended: the commanded end point of the block
  std::uint64_t call_id = 0;  // subcall_release
  CallOutcome call_outcome = CallOutcome::released;
};

struct ChannelAlarm {
  int number = 0;
  std::array<char, 192> text{};  // fixed: alarms are raised from the cyclic path
  int line = 0;
  int column = 0;
  int axis = 0;  // channel axis index + 1 when an axis is concerned
};

struct CycleOutput {
  std::array<CommandedAxis, kMaxChannelAxes> setpoints{};
  ChannelState state = ChannelState::reset;
  std::size_t block = 0;
  int line = 0;
  interp::ModalState modal;  // of the block under way (of the last one, between runs)
  bool program_end = false;
  int end_code = -1;
  std::uint64_t run_start_cycle = 0;  // cycle the program started (valid once it has run)
  std::uint64_t end_cycle = 0;        // cycle of its program end (valid when program_end)
  // The channel's spindle (S1) as its program commands it: speed and direction (+1 M03,
  // -1 M04, 0 stopped). Stopped whenever no program runs (reset, idle, alarm, end).
  double spindle_rpm = 0.0;
  int spindle_direction = 0;
  // The spindle is under position control (M18): its setpoint is setpoints[spindle_c_slot],
  // in the spindle's degrees.
  bool spindle_position = false;
  // A G04.1 arrival to send to every other channel this cycle (sync_arrive event).
  bool arrival_due = false;
  coordination::SyncArrival arrival{};
  // A G144 call to send this cycle (subcall event), and the releases of calls to send.
  bool call_due = false;
  CallRequest call{};
  static constexpr std::size_t kMaxReleases = 8;
  std::array<CallRelease, kMaxReleases> releases{};
  std::size_t release_count = 0;
  // G140/G141/G142 requests to send to the axis nodes this cycle.
  static constexpr std::size_t kMaxAxisRequests = coordination::AxisExchange::kMaxRequests;
  std::array<AxisRequestOut, kMaxAxisRequests> axis_requests{};
  std::size_t axis_request_count = 0;
  // An M or T code for the PLC node, sent this cycle.
  bool aux_due = false;
  AuxRequestOut aux{};
  // G114.1 / G113 to the slave spindles' axis nodes, sent this cycle.
  bool spindle_sync_due = false;
  SpindleSyncOut spindle_sync{};
  // G51.4 / G50.4 to a slave axis's node, sent this cycle.
  bool axis_sync_due = false;
  AxisSyncOut axis_sync{};
  static constexpr std::size_t kMaxEvents = 64;  // many short blocks may pass in one cycle
  std::array<ChannelEvent, kMaxEvents> events{};
  std::size_t event_count = 0;
};

struct ChannelSetup {
  std::size_t axis_count = 0;
  std::vector<double> in_position;  // per axis, units
  double cycle_s = 0.001;
  std::size_t pulls_per_cycle = 64;  // commands pulled into the look-ahead per cycle at most
  // Spindles whose feedback follows the axes' in cycle()'s `feedback`: their alarms stop the
  // channel too, and a channel comes to idle only with them enabled.
  std::size_t spindle_count = 0;
  std::uint32_t channel_id = 1;  // the channel's number (CHn), as G04.1 Q names it
  // The writes to shared variables not yet sent (null: none kept): the channel arrives at a
  // G04.1 and calls with G144 only once they are out.
  const SharedWriteLog* shared_writes = nullptr;
  // Per axis: what the channel may do with it (G140/G141/G142). Empty: every axis is the
  // channel's own for good (no exchange; feedback owner not looked at).
  std::vector<AxisSlot> slots{};
  // A PLC node runs M and T codes: each is a block that ends with its answer; a spindle
  // start (M03/M04) waits for the PLC's consent.
  bool plc = false;
  // G114.1 groups this channel commands (its spindle is their master).
  std::vector<SpindleGroupSetup> spindle_groups{};
  // G144: how many cycles a call waits for its target to become free (0: as long as it takes).
  std::uint64_t call_wait_cycles = 0;
  // The channel's first spindle is the slave of a G114.1 group: a start waits until the blocks
  // before it ended and is an alarm while the spindle follows its master.
  bool spindle_may_follow = false;
  // Every axis of the machine, by system number - 1: what G51.4 P may name.
  std::vector<MachineAxis> machine_axes{};
  // The slot of the first spindle's C axis (C1 mode), if it has one: its feedback is the
  // spindle's, and it is commanded only while M18 (GSK M14) holds the spindle under position
  // control.
  std::optional<std::size_t> spindle_c_slot{};
  // Per axis: the skip input its drive's touch probe is wired to (G31; 0: none). Empty: none.
  std::vector<int> probe_inputs{};
  // G31: a touch probe that does not report itself armed within this many cycles is an alarm.
  std::uint64_t probe_arm_cycles = 200;
  // G04 I: per input port (the index), the bit of the PLC's inputs it reads (-1: none).
  std::vector<int> input_ports{};
  // G04 PS: reached within this many rpm (param 1057); an alarm after this long (param 1059).
  double speed_arrival_rpm = 10.0;
  double speed_arrival_timeout_s = 10.0;
};

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

class ChannelController {
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
  // An owned axis's node is gone (`axis` counts the spindles after the axes): alarm and hold.
  void axis_lost(std::size_t axis) noexcept;

  // Coordination inputs, given before cycle(): another channel's G04.1 arrival (applied in
  // the order sent), the channels in automatic operation as their status stamped N-1 says
  // (running, feed hold, waiting) and those stopped by an alarm, and a channel whose process is
  // gone.
  void on_arrival(const coordination::SyncArrival& arrival) noexcept;
  void set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept;
  void partner_lost(std::uint32_t channel) noexcept;
  // Events from another channel did not fit this channel's receive queue: what the channels
  // share can no longer be trusted (an alarm).
  void coordination_lost() noexcept { coordination_lost_ = true; }
  // G144 calls addressed to this channel (run when it is idle, else refused), and the end of a
  // call this channel made.
  void on_call(const CallRequest& call) noexcept;
  void on_call_release(const CallRelease& release) noexcept;
  // The PLC's answer to an aux request of this channel (applied from the cycle after it was
  // sent, as every event).
  void on_aux_answer(const PlcAnswer& answer) noexcept;
  // The PLC node is gone: a request waiting for it, and every later one, is refused.
  void plc_lost() noexcept;
  // The PLC's inputs as its status stamped N-1 reports them (bit k: signal k on): G04 I.
  void set_plc_inputs(std::uint64_t inputs) noexcept { plc_inputs_ = inputs; }

  // One cycle. `feedback` holds one entry per channel axis, then one per spindle.
  const CycleOutput& cycle(std::uint64_t cycle,
                           std::span<const AxisFeedbackView> feedback) noexcept;
  // G140/G141/G142: whether the channel commands axis `slot` now (owns it and took over its
  // position); a slot it does not command is a virtual axis or with another channel.
  [[nodiscard]] bool commands_axis(std::size_t slot) const noexcept {
    return slot < kMaxChannelAxes && exchange_.use(slot) == coordination::SlotUse::commanded;
  }

  [[nodiscard]] ChannelState state() const noexcept { return out_.state; }
  [[nodiscard]] const ChannelAlarm& last_alarm() const noexcept { return alarm_; }
  [[nodiscard]] std::size_t alarm_count() const noexcept { return alarm_count_; }
  [[nodiscard]] const AxisVector& commanded() const noexcept { return commanded_; }
  // The spindle's position at C = 0 (whole turns) of the last position control (0: none yet).
  [[nodiscard]] double spindle_c_base() const noexcept { return spindle_mode_.c_base(); }
  // The G04.1 marks as this channel sees them: the mark it waits at and whom it misses.
  [[nodiscard]] const coordination::SyncBarrier& sync() const noexcept { return mark_.barrier(); }
  // The G144 call this channel runs for another channel: its id (0: none) and caller.
  [[nodiscard]] std::uint64_t serving_call() const noexcept { return calls_.serving_call(); }
  [[nodiscard]] std::uint32_t serving_caller() const noexcept { return calls_.serving_caller(); }
  // The operator panel's overrides as applied, as fractions (1.0: 100 %).
  [[nodiscard]] double feed_override() const noexcept { return feed_override_; }
  [[nodiscard]] double rapid_override() const noexcept { return rapid_override_; }
  [[nodiscard]] double spindle_override() const noexcept { return spindle_override_; }
  // G144 H1: the channel this one's sent call waits for, 0 when none.
  [[nodiscard]] std::uint32_t waiting_for_call() const noexcept {
    return std::holds_alternative<CallStop>(held_) ? calls_.waiting_for() : 0;
  }
  // The M or T code whose answer (FIN) from the PLC the channel waits for, or nullptr.
  [[nodiscard]] const AuxRequestOut* waiting_for_fin() const noexcept {
    return std::holds_alternative<AuxStop>(held_) && aux_.sent() && in_run() ? &aux_.request()
                                                                             : nullptr;
  }
  // The axis exchange the channel waits for: its G code (140, 141, 142; 0: none) and the slot
  // (AxisRequestOut::kAllSlots for G142).
  struct ExchangeWait {
    int g = 0;
    std::size_t slot = 0;
  };
  [[nodiscard]] ExchangeWait waiting_for_exchange() const noexcept {
    if (!std::holds_alternative<ExchangeStop>(held_) || exchange_.waiting_g() == 0 || !in_run()) {
      return {};
    }
    return {exchange_.waiting_g(), exchange_.waiting_slot()};
  }
  // A run is under way (not stopped by an alarm or a reset): what it waits for is real.
  [[nodiscard]] bool in_run() const noexcept {
    return out_.state == ChannelState::running || out_.state == ChannelState::waiting ||
           out_.state == ChannelState::hold;
  }

 private:
  const CycleOutput& run_cycle(std::uint64_t cycle,
                               std::span<const AxisFeedbackView> feedback) noexcept;
  void set_state(ChannelState state) noexcept;
  void push_event(const ChannelEvent& event) noexcept;
  void raise(int number, const char* text, int line, int column, int axis) noexcept;
  void raise(const coordination::CoordinationAlarm& alarm, int line) noexcept {
    raise(alarm.number, alarm.text.data(), line, 0, alarm.axis);
  }
  void raise_program_alarm(const interp::ProgramAlarm& alarm) noexcept;
  bool all_enabled(std::span<const AxisFeedbackView> feedback) const noexcept;
  // Every axis's actual position within its in-position width of `at`.
  bool in_position(std::span<const AxisFeedbackView> feedback, const AxisVector& at) const noexcept;
  void run_blocks(std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void fill() noexcept;
  void block_events(const motion::MotionOutput& m,
                    std::span<const AxisFeedbackView> feedback) noexcept;
  void hold_outputs(bool valid) noexcept;
  void finish_reset() noexcept;
  void forget_program_run() noexcept;  // the queue, the end and the alarms of a program run
  // Starts (or repeats) the program of the call this channel serves.
  void start_served_call(std::uint64_t cycle) noexcept;
  void take_calls(std::uint64_t cycle) noexcept;
  // Ends the served call's hold on its caller (once).
  void release_caller(CallOutcome outcome) noexcept;
  void push_release(const CallRelease& release) noexcept;

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
  bool resetting_ = false;     // ramping down for a reset
  bool after_reset_ = false;   // reset done, waiting for the axes to be enabled without alarms
  bool estopped_ = false;      // an emergency stop: a reset does not undo it
  std::size_t lost_axis_ = 0;  // axis index + 1
  bool halted_ = false;        // an alarm or emergency stop ended the run
  BlockQueue queued_;          // the blocks the planner took, until their end event
  interp::Command end_{};      // the program end, once pulled
  bool end_pulled_ = false;
  bool end_started_ = false;
  std::optional<interp::ProgramAlarm> source_alarm_;  // raised when the blocks before it ran
  std::optional<interp::ProgramAlarm> pending_alarm_;
  bool first_cycle_ = true;

  // The block's event of `kind`, with the channel's position.
  [[nodiscard]] ChannelEvent block_event(const HeldBlock& b, ChannelEventKind kind) const noexcept;
  // The block is the channel's current one: its start event, once.
  void start_held(HeldBlock& b) noexcept;
  // The held block ends: its end event, and read-ahead goes on.
  void end_held(const HeldBlock& b) noexcept;

  // The block that stops read-ahead, pulled and not passed yet (std::monostate: none). Each
  // kind runs once every block before it ended; the coordination machines hold what outlives it.
  ReadAheadStop held_;
  [[nodiscard]] bool holds_block() const noexcept {
    return !std::holds_alternative<std::monostate>(held_);
  }
  void begin_held() noexcept;  // the held block's machine starts on it
  // One cycle of the held block, once every block before it ended.
  void run(std::monostate& /*none*/, std::uint64_t /*cycle*/,
           std::span<const AxisFeedbackView> /*feedback*/) noexcept {}
  void run(SyncStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void run(CallStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void run(ReleaseStop& b, std::uint64_t cycle,
           std::span<const AxisFeedbackView> feedback) noexcept;
  void run(ExchangeStop& b, std::uint64_t cycle,
           std::span<const AxisFeedbackView> feedback) noexcept;
  void run(AuxStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void run(CouplingStop& b, std::uint64_t cycle,
           std::span<const AxisFeedbackView> feedback) noexcept;
  void run(ModeStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void run(SkipStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;
  void run(WaitStop& b, std::uint64_t cycle, std::span<const AxisFeedbackView> feedback) noexcept;

  // G04.1 (the barrier) and G144 / G145 (calls made and served).
  coordination::SyncMark mark_;
  coordination::SubCall calls_;
  coordination::ChannelSet active_;
  coordination::ChannelSet halted_partners_;
  coordination::ChannelSet lost_partners_;
  bool coordination_lost_ = false;
  std::uint64_t writes_lost_seen_ = 0;
  [[nodiscard]] bool writes_pending() const noexcept {
    return setup_.shared_writes != nullptr && setup_.shared_writes->size() > 0;
  }

  // G140/G141/G142 and what the channel does with each slot.
  coordination::AxisExchange exchange_;
  [[nodiscard]] bool exchanges() const noexcept { return exchange_.exchanges(); }
  // Alarm (1231, or 1261 for an axis that follows) at the first queued block that moves slot
  // `s`, which the channel no longer commands: "<address> <why>".
  void raise_if_queued_moves(std::size_t s, const char* why) noexcept;
  void build_views(std::span<const AxisFeedbackView> received) noexcept;
  void settle_slots() noexcept { exchange_.settle(received_, commanded_); }
  void sync_positions() noexcept;  // the interpreter and the planner stand at commanded_
  void withdraw_waits() noexcept { exchange_.withdraw(); }
  static constexpr std::size_t kMaxViews = kMaxChannelAxes + 8;  // axes, then spindles
  std::array<AxisFeedbackView, kMaxViews> views_{};
  std::span<const AxisFeedbackView> received_;  // this cycle's feedback as it came

  // M/S/T codes, couplings, the spindle's mode.
  coordination::AuxHandshake aux_;
  int spindle_queued_ = 0;  // the first spindle's direction as the pulled blocks leave it
  coordination::CouplingRequest coupling_;
  coordination::SpindleMode spindle_mode_;
  void leave_position_control() noexcept;  // no program runs: speed control, at rest
  [[nodiscard]] bool under_position_control() const noexcept {
    return setup_.spindle_c_slot &&
           exchange_.use(*setup_.spindle_c_slot) == coordination::SlotUse::commanded;
  }

  // G31 and G04 I / G04 PS.
  std::uint64_t plc_inputs_ = 0;
  coordination::SkipProbe skip_;
  // Bit i: axis i's touch probe is on skip input `input` and the channel commands the axis.
  [[nodiscard]] std::uint32_t probe_axes(int input) const noexcept;
  [[nodiscard]] bool skip_in(coordination::SkipPhase phase) const noexcept {
    return std::holds_alternative<SkipStop>(held_) && skip_.phase() == phase;
  }
  void watch_skip(std::span<const AxisFeedbackView> feedback) noexcept;  // moving: a latch
  // Hands a command to the planner and the block queue; false (and a source alarm) when the
  // planner refuses it.
  bool queue_command(const interp::Command& c) noexcept;
};

}  // namespace mcnc::channel
