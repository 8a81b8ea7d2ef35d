#pragma once
// The axis node's core (ARCHITECTURE.md §5, §6): what the node has heard from the channels that
// may command it, who owns the axis (G140-G142), which setpoint wins (the owner's, or a
// coupling's: G114.1 for a slave spindle, G51.4 for a slave axis), and the drive's cycle. The
// adapters in axisnode/wire/ feed it from their DDS callbacks under the node's wake-up lock and
// hand it the drive's readings; it returns what the drive is sent, what the feedback says and
// what happened in the cycle, as data for the trace.
//
// The lockstep rule: cycle N runs once every candidate owner's setpoint stamped N-1 is in, with
// the events it announces (and, when coupled, its master's samples of N-1), so a G140/G141/G142
// or a coupling takes effect at the same cycle in every run. Events act from the cycle after the
// one they were sent in.
//
// Pure and deterministic: allocates at construction only, nothing throws; no DDS, socket,
// thread or file.
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/coupling/axis_coupling.hpp"
#include "axisnode/coupling/cam_coupling.hpp"
#include "axisnode/coupling/gear_box_coupling.hpp"
#include "axisnode/coupling/master_history.hpp"
#include "axisnode/coupling/spindle_coupling.hpp"
#include "axisnode/ownership/axis_ownership.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/pending_events.hpp"
#include "common/cycle/tracked_input.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mcnc::axisnode {

// What the node is to the machine: set once, from the machine file (axisnode/setup/).
struct AxisNodeRoles {
  std::uint32_t axis = 0;  // this axis's id
  std::uint32_t home = 0;  // its configured owner channel
  // The channels that may own it: home first, then those that may acquire it (G141).
  std::vector<std::uint32_t> candidates;
  bool exchangeable = false;  // its home channel may release it alone (G140)
  // G51.4: a slave axis, and the axes it may follow (any of its kind that is no slave itself).
  bool may_follow = false;
  std::vector<std::uint32_t> leaders;
  std::uint32_t power_on_master = 0;  // coupled from power-on to this axis (param 5600.3)
  // G114.1: a slave spindle's group, its master spindle's axis id and the channel that couples
  // it (all 0: none).
  std::uint32_t sync_group = 0;
  std::uint32_t sync_master = 0;
  std::uint32_t sync_channel = 0;
  // The coupling is a channel's polygon axis (G51.2 / G50.2, its `polygon`) instead: sync_master
  // is the master spindle and sync_channel the channel; G50.2 or the channel's reset brings the
  // axis to rest before it lets go.
  bool polygon = false;
  // Or the slave of a channel's electronic cam (G51.8 / G50.8, its `cam`): sync_master is the
  // master spindle and sync_channel the channel; the lift is laid over the channel's setpoint.
  bool cam = false;
  // Or the work axis of a channel's electronic gear box (G81.4 / G80.4, its `egb`): sync_master
  // is the tool spindle and sync_channel the channel; the gear box's offset is laid over the
  // channel's setpoint. egb_axial: the axial feed axis of helical gears (0: none), followed by
  // its commanded position as a G51.4 leader is (leaders holds it). egb_synchronous (param
  // 5320.1): the tool spindle's commanded angle is followed, not its actual one;
  // egb_reset_at_once (5320.4): a reset stops the work axis at once, not once the tool stands.
  bool egb = false;
  std::uint32_t egb_axial = 0;
  bool egb_synchronous = false;
  bool egb_reset_at_once = false;
  double in_position = 0.0;  // units: the axis stands when command and actual are this close
  double cycle_s = 0.001;
  AxisNodeSetup controller;
  coupling::SpindleCouplingSetup spindle_coupling;
  coupling::CamCouplingSetup cam_coupling;
  coupling::GearBoxSetup gear_box;
};

// One candidate owner's setpoint.
struct SetpointSample {
  std::uint64_t cycle = 0;
  double pos = 0.0;
  double vel = 0.0;
  double acc = 0.0;
  bool valid = false;                      // the channel commands the axis (false: hold)
  bool velocity = false;                   // a spindle in velocity mode
  ProbeRequest probe = ProbeRequest::off;  // G31: the touch probe to arm; G160: the torque skip
  // G160: the torque limit (percent of the rated torque, 0: none) and the skip deviation
  // (units), sent for as long as the limit stands.
  double torque_limit = 0.0;
  double skip_deviation = 0.0;
  // G10 L14 P10: torque mode at `torque` percent of the rated torque, the motor within
  // `torque_speed` rpm.
  bool torque_mode = false;
  double torque = 0.0;
  double torque_speed = 0.0;
};

// A coordination event from a channel, as far as an axis node reads it.
struct AxisNodeEvent {
  enum class Kind : std::uint8_t {
    axis_request,
    axis_sync,
    spindle_sync,
    polygon_sync,
    cam_sync,
    egb_sync,
    other
  };
  Kind kind = Kind::other;
  std::uint32_t channel = 0;
  std::uint64_t seq = 0;    // the sender's event sequence number
  std::uint64_t cycle = 0;  // the cycle it was sent in
  std::uint32_t axis = 0;   // axis_request (0: every axis of the request), axis_sync
  ownership::OwnershipRequestKind request = ownership::OwnershipRequestKind::acquire;
  bool force = false;
  bool sync_on = false;           // axis_sync, spindle_sync
  std::uint32_t sync_master = 0;  // axis_sync
  std::uint32_t sync_group = 0;   // spindle_sync (0 with sync_on false: every group)
  // spindle_sync: P, Q and the slave's phase; polygon_sync: P, Q and the master's start angle.
  coupling::SpindleCouplingCommand spindle{};
  coupling::CamProfile cam{};      // cam_sync with sync_on
  coupling::GearBoxCommand egb{};  // egb_sync with sync_on
  // egb_sync without sync_on: G80.4, a reset, or the channel took the reached angle (absorb).
  enum class EgbOff : std::uint8_t { stop, reset, absorb } egb_off = EgbOff::stop;
};

// The drive's side of a cycle, from the bus.
struct DriveReadings {
  bool have_tpdo = false;  // the drive answered since the last cycle
  std::uint16_t statusword = 0;
  std::int32_t position_counts = 0;
  std::int8_t mode_display = 0;
  std::uint64_t heartbeats = 0;
  bool bus_off = false;
  std::uint64_t foreign_syncs = 0;       // SYNC frames another node sent (the producer sees them)
  std::uint16_t touch_probe_status = 0;  // 0x60B9
  std::int32_t probe_positive = 0;       // 0x60BA
  std::int32_t probe_negative = 0;       // 0x60BB
  std::int16_t torque_actual = 0;        // 0x6077, per mille of the rated torque
};

// What happened in a cycle that the trace tells, in the order it happened.
struct AxisNodeHappening {
  enum class Kind : std::uint8_t {
    spindle_coupled,    // master, spindle
    spindle_decoupled,  // master
    axis_coupled,       // master
    axis_decoupled,     // master
    polygon_coupled,    // master, spindle (r: the master's start angle)
    polygon_decoupled,  // master (the polygon axis stands)
    cam_coupled,        // master (the lift is laid over the setpoint from the next cycle)
    cam_decoupled,      // master (the lift is off)
    cam_refused,        // master (a profile that cannot be a cam: nothing moves)
    egb_coupled,        // master (the gear box is laid over the setpoint from this cycle)
    egb_refused,        // master (a command that cannot be a gear box: nothing moves)
    egb_stopped,        // master, why (G80.4, a reset, the deviation or the tool lost), at
    egb_absorbed,       // master (the channel commands the reached angle: the offset is off)
    owner,              // channel (0: released), previous (0: none), forced
    follows,            // channel whose valid setpoints the node now applies (0: none)
  };
  Kind kind = Kind::owner;
  std::uint32_t channel = 0;
  std::uint32_t previous = 0;
  bool forced = false;
  std::uint32_t master = 0;
  coupling::SpindleCouplingCommand spindle{};
  // egb_stopped: why the work axis stopped, and the offset it stands at (degrees).
  enum class EgbStop : std::uint8_t { program, reset, deviation, tool_lost } egb_stop{};
  double at = 0.0;
};

// What the feedback says besides the drive's own values.
struct AxisNodeStanding {
  std::uint32_t owner = 0;  // 0: released
  std::uint32_t released_by = 0;
  std::uint32_t coupled_to = 0;  // the master axis while coupled
  bool coupling_locked = false;
  // The channels whose latest G140-G142 request the node refused, or could not keep (bit c-1
  // for channel c): each asker alarms instead of waiting (AxisOwnership).
  std::uint64_t refused_channels = 0;
  std::uint64_t full_channels = 0;
};

class AxisNode {
 public:
  using WriterId = cycle::TrackedInput<SetpointSample>::WriterId;
  static constexpr std::size_t kMaxHappenings = 48;

  explicit AxisNode(const AxisNodeRoles& roles);  // allocates here, never afterwards

  // --- What arrives, under the lock that also guards ready() and take_inputs().
  // A setpoint from `channel` for `axis`, announcing its sender's last event.
  void on_setpoint(std::uint32_t channel, std::uint32_t axis, const SetpointSample& sample,
                   std::uint64_t announced_event_seq, const WriterId& writer) noexcept;
  // A setpoint writer left: a candidate whose writer it was is lost.
  void on_setpoint_writer_gone(const WriterId& writer) noexcept;
  void on_event(const AxisNodeEvent& event) noexcept;
  // G114.1: the coupling channel's status, and the master spindle's feedback.
  void on_sync_channel_status(std::uint32_t channel, std::uint64_t cycle,
                              std::uint64_t announced_event_seq, const WriterId& writer) noexcept;
  void on_sync_channel_gone(const WriterId& writer) noexcept;
  // `cmd`: its commanded angle (a G81.4 in synchronous mode follows it, param 5320.1).
  void on_master_feedback(std::uint32_t axis, std::uint64_t cycle, double act, double vel,
                          double cmd, const WriterId& writer) noexcept;
  void on_master_gone(const WriterId& writer) noexcept;
  // G51.4: an axis's feedback that this slave may follow.
  void on_leader_feedback(std::uint32_t axis, std::uint64_t cycle, double cmd, bool operating,
                          const WriterId& writer) noexcept;
  void on_leader_gone(const WriterId& writer) noexcept;

  // Lockstep: every input of `cycle` is in.
  [[nodiscard]] bool ready(std::uint64_t cycle) const noexcept;
  // What keeps lockstep cycle `cycle` waiting, for a log line when the wait is slow: whose input
  // (a candidate channel's setpoints and events, the G114.1 coupling channel's status, the master
  // spindle's or a G51.4 leader's feedback) and how far it came.
  struct InputWait {
    enum class From : std::uint8_t { channel, coupling_channel, master, leader };
    From from = From::channel;
    std::uint32_t id = 0;            // the channel's id, or the master's or leader's axis id
    cycle::LockstepGate::Wait gate;  // a leader: no gate input (only the cycle waited for)
  };
  [[nodiscard]] std::optional<InputWait> input_wait(std::uint64_t cycle) const noexcept;
  // The owner's setpoint writer has left (its axis goes to its safe state).
  [[nodiscard]] bool owner_lost() const noexcept { return owner_lost_; }

  // --- The cycle.
  // Under the lock: the events sent before `cycle`, then who owns the axis and which setpoint
  // it follows. Clears and begins the cycle's happenings.
  void take_inputs(std::uint64_t cycle, bool lockstep) noexcept;
  // The channel an operator reset of the axis concerns: the one that commands it (a lent axis:
  // its borrower); released, its home channel.
  [[nodiscard]] std::uint32_t commanding_channel() const noexcept;
  void reset() noexcept { controller_.reset(); }
  // Outside the lock, after take_inputs(): the drive's cycle. `paced_best_effort`: see
  // AxisNodeInput.
  const AxisNodeOutput& step(std::uint64_t cycle, const DriveReadings& drive, bool emergency_stop,
                             bool paced_best_effort = false) noexcept;

  [[nodiscard]] const AxisNodeOutput& output() const noexcept { return controller_.output(); }
  [[nodiscard]] bool ready_to_disable() const noexcept { return controller_.ready_to_disable(); }
  [[nodiscard]] AxisNodeStanding standing() const noexcept;
  [[nodiscard]] const AxisNodeHappening* happenings() const noexcept { return happened_.data(); }
  [[nodiscard]] std::size_t happening_count() const noexcept { return happened_count_; }
  // Ownership requests that did not fit (more waiting than the node keeps).
  [[nodiscard]] std::uint64_t requests_dropped() const noexcept { return requests_dropped_; }
  [[nodiscard]] const AxisNodeRoles& roles() const noexcept { return roles_; }
  // G51.8: the cam's lift in this cycle's command (0: no cam); G81.4: the gear box's offset,
  // which stays once G80.4 has stopped the work axis until the channel takes it (absorb).
  [[nodiscard]] double superimposed() const noexcept {
    return cam_coupling_.offset() + gear_box_.offset();
  }
  // The node reads the channels' coordination events (G140-G142, G51.4 or G114.1 concern it).
  [[nodiscard]] bool hears_events() const noexcept { return watches_events_ || coupled_spindle(); }
  // Events of `channel` may concern the node (a candidate owner or the coupling channel). Reads
  // the roles only: callable from any thread, without the lock.
  [[nodiscard]] bool hears_from(std::uint32_t channel) const noexcept {
    return candidate_of(channel) >= 0 || (coupled_spindle() && channel == roles_.sync_channel);
  }

 private:
  struct SpindleSyncRequest {
    bool on = false;
    coupling::SpindleCouplingCommand command;  // polygon: as programmed (r: the start angle)
  };
  struct CamRequest {
    bool on = false;
    coupling::CamProfile profile;
  };
  struct EgbRequest {
    bool on = false;
    coupling::GearBoxCommand command;
    AxisNodeEvent::EgbOff off = AxisNodeEvent::EgbOff::stop;
  };
  struct AxisSyncRequest {
    bool on = false;
    std::uint32_t master = 0;
  };
  struct MasterSample {
    double act = 0.0;
    double vel = 0.0;
    double cmd = 0.0;
  };
  struct LeaderWriter {
    WriterId writer{};
    std::uint32_t axis = 0;
  };

  [[nodiscard]] bool coupled_spindle() const noexcept { return roles_.sync_master != 0; }
  [[nodiscard]] int candidate_of(std::uint32_t channel) const noexcept;
  // The setpoint `channel` sent for `cycle` (realtime: its latest while no older than the last
  // cycle's).
  [[nodiscard]] const SetpointSample* setpoint_of(std::uint32_t channel, std::uint64_t cycle,
                                                  bool lockstep) const noexcept;
  // The master the slave follows at `cycle`: the coupling as the events sent before it leave it.
  [[nodiscard]] std::uint32_t axis_master_at(std::uint64_t cycle) const noexcept;
  // Who owns the axis, and the owner's setpoint into this cycle's input.
  ownership::OwnershipChange decide_owner(std::uint64_t cycle, bool lockstep) noexcept;
  void apply_spindle_sync(std::uint64_t cycle, bool lockstep) noexcept;
  void apply_axis_sync(std::uint64_t cycle, bool lockstep) noexcept;
  void apply_cam(std::uint64_t cycle, bool lockstep) noexcept;
  void apply_egb(std::uint64_t cycle, bool lockstep) noexcept;
  void stop_egb(AxisNodeHappening::EgbStop why) noexcept;
  // G81.4 with a helical term: the axial axis's sample of cycle - 1 is an input of the cycle.
  [[nodiscard]] bool waits_for_axial(std::uint64_t cycle) const noexcept;
  void happened(const AxisNodeHappening& h) noexcept;

  AxisNodeRoles roles_;
  bool watches_events_;
  cycle::LockstepGate gate_;
  std::vector<cycle::TrackedInput<SetpointSample>> from_;  // per candidate
  cycle::TrackedInput<std::uint64_t> sync_channel_;        // G114.1: only its arrival counts
  cycle::TrackedInput<MasterSample> master_feedback_;
  cycle::PendingEvents<ownership::OwnershipRequest, 256> requests_;
  cycle::PendingEvents<SpindleSyncRequest, 16> spindle_syncs_;
  cycle::PendingEvents<AxisSyncRequest, 16> axis_syncs_;
  cycle::PendingEvents<CamRequest, 4> cams_;
  cycle::PendingEvents<EgbRequest, 8> egbs_;
  coupling::MasterHistory master_history_;
  std::vector<LeaderWriter> leader_writers_;  // capacity: the leaders
  ownership::AxisOwnership ownership_;
  coupling::SpindleCoupling spindle_coupling_;
  coupling::AxisCoupling axis_coupling_;
  coupling::CamCoupling cam_coupling_;
  coupling::GearBoxCoupling gear_box_;
  // G81.4: where the channel last validly commanded the work axis (a reset's stop lays the
  // offset over it), why the gear box is stopping, and a reset that waits for the tool to stand.
  double egb_base_ = 0.0;
  AxisNodeHappening::EgbStop egb_stopping_ = AxisNodeHappening::EgbStop::program;
  bool egb_release_when_tool_stands_ = false;
  AxisNodeController controller_;

  std::uint32_t owner_now_;  // the owner as the last decision left it
  bool owner_lost_ = false;  // the current owner's writer left
  std::uint32_t following_;  // the channel whose valid setpoints the node applied last
  std::uint64_t requests_dropped_ = 0;
  AxisNodeInput in_{};  // this cycle's, from take_inputs() to step()
  std::array<AxisNodeHappening, kMaxHappenings> happened_{};
  std::size_t happened_count_ = 0;
};

}  // namespace mcnc::axisnode
