#pragma once
// The axis node's cyclic core: follows its owner channel's setpoints, brings its CiA 402 drive
// to operation enabled, and goes to quick stop when the owner's setpoints stop (deadline), the
// owner is gone, or the machine is E-stopped (ARCHITECTURE.md §6). Pure and deterministic.
#include "canopen/cia402/cia402_state.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/heartbeat.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::axisnode {

struct AxisNodeSetup {
  double counts_per_unit = 10000.0;
  double cycle_s = 0.001;
  int deadline_cycles = 5;
  // Heartbeat consumer time in cycles (CiA 301: monitoring starts with the first heartbeat);
  // 0: not monitored.
  int heartbeat_cycles = 0;
  // Cycles paced without real-time scheduling (AxisNodeInput::paced_best_effort): the drive's
  // answers and heartbeat are watched over at least this many cycles (decision 127).
  int best_effort_watch_cycles = 0;
  // A setpoint outside [soft_min, soft_max] is not followed: alarm and quick stop.
  bool has_soft_limits = false;
  double soft_min = 0.0;
  double soft_max = 0.0;
  // More than this between the command and the actual position: alarm and quick stop
  // (0: not checked).
  double following_error_limit = 0.0;
  // units/s^2: the owner plans its moves within it. A missing setpoint continues the motion as
  // a stop at this deceleration would (0: at the last velocity).
  double acceleration = 0.0;
  // After an operator reset, a drive still in fault this many cycles later is alarmed again.
  int fault_reset_cycles = 100;
  // A spindle: its drive starts in CSV and switches between CSV and CSP in operation as the
  // owner's setpoints ask (modes of operation in its RPDO, the display in its TPDO).
  bool spindle = false;
  // Reference return at start-up: the drive starts in homing mode (method and offset written at
  // start-up); once enabled the node starts the homing (controlword bit 4), and when the drive
  // says homing attained (statusword bit 12) switches it to CSP and takes over there. Until then
  // the axis is not enabled for its owner. Needs the PDOs with the modes (homing_axis_pdos).
  bool homing = false;
  int homing_timeout_cycles = 60000;  // from the drive's enable in homing mode
  // G160: the drive's max torque 0x6072 is in its RPDO2 and its torque 0x6077 in its TPDO2
  // (canopen::add_torque_limit).
  bool torque_skip = false;
  // G10 L14 P10-P12: the drive switches between CSP and cyclic synchronous torque (CST, mode
  // 10) as the owner's setpoints ask, the modes of operation in its RPDO1 and their display in
  // its TPDO1, the target torque 0x6071 and the max motor speed 0x6080 in its RPDO2 after the
  // max torque (canopen::add_torque_mode after add_torque_limit; needs torque_skip).
  bool torque_mode = false;
  // Param 5522: the drive's 1000 per mille of torque in % of the rated torque (100: CiA 402's;
  // torque_units.hpp).
  double torque_scale = 100.0;
};

inline constexpr std::int8_t kModeHoming = 6;
// "csp", "csv", "homing" (trace and messages); "other" for any other mode.
const char* mode_name(std::int8_t mode) noexcept;

inline constexpr std::int8_t kModeCsp = 8;
inline constexpr std::int8_t kModeCsv = 9;
inline constexpr std::int8_t kModeCst = 10;

// G31 skip: the owner asks the drive's touch probe to latch the position where its input goes
// on (rising) or off (falling); G160: to latch where the torque is at its limit and the
// following error beyond the skip deviation (torque). G31.8: to latch every such edge
// (every_rising, every_falling: the drive's continuous mode). What the node reports of it.
enum class ProbeRequest : std::uint8_t {
  off = 0,
  rising = 1,
  falling = 2,
  torque = 3,
  every_rising = 4,
  every_falling = 5
};
enum class ProbeState : std::uint8_t { off = 0, armed = 1, latched = 2 };

struct AxisNodeInput {
  bool have_setpoint = false;  // a setpoint from the owner stamped N-1 arrived
  double setpoint_pos = 0.0;
  double setpoint_vel = 0.0;
  bool setpoint_valid = false;     // the owner commands (false: hold)
  bool setpoint_velocity = false;  // a spindle: the owner commands velocity (CSV), not position
  std::int8_t mode_display = 0;    // a spindle: 0x6061 from its TPDO
  bool have_tpdo = false;          // the drive answered this cycle's SYNC
  std::uint16_t statusword = 0;
  std::int32_t position_counts = 0;
  bool owner_lost = false;  // the owner's writer left (DDS liveliness)
  bool emergency_stop = false;
  // The cycles are paced to real time by a process that is not scheduled for it (a lockstep
  // node after an E-stop, once its owner is gone, or stopping: each after its axis was
  // quick-stopped): on a loaded host the drive's simulator may answer late, so a drive is
  // judged silent only after best_effort_watch_cycles.
  bool paced_best_effort = false;
  std::uint64_t heartbeats = 0;            // the drive's heartbeats received so far
  bool bus_off = false;                    // the CAN controller went bus off
  std::uint64_t foreign_syncs = 0;         // SYNC frames another node sent
  ProbeRequest probe = ProbeRequest::off;  // the owner's, while it commands the axis
  std::uint16_t touch_probe_status = 0;    // 0x60B9
  std::int32_t probe_positive = 0;         // 0x60BA, counts
  std::int32_t probe_negative = 0;         // 0x60BB, counts
  // G160, the owner's while it commands the axis: the torque limit in percent of the rated
  // torque (0: none) and the following error beyond which the torque skip latches (units).
  double torque_limit = 0.0;
  double skip_deviation = 0.0;
  std::int16_t torque_actual = 0;  // 0x6077, per mille of the rated torque (torque_skip)
  // G10 L14 P10/P11, the owner's while it commands the axis (setup torque_mode): the drive in
  // torque mode at `torque` percent of the rated torque (signed), its motor within
  // `torque_speed` rpm; false: position mode.
  bool torque_mode = false;
  double torque = 0.0;
  double torque_speed = 0.0;
};

enum class AxisAlarm : std::uint8_t {
  none = 0,
  setpoint_deadline = 1,  // no setpoint for deadline_cycles
  owner_lost = 2,
  drive_fault = 3,
  drive_lost = 4,       // no TPDO for deadline_cycles (best_effort_watch_cycles if longer)
  drive_startup = 5,    // the drive could not be brought up (no boot-up, a refused SDO)
  heartbeat_lost = 6,   // no heartbeat from the drive for the consumer time
  bus_off = 7,          // the CAN controller went bus off
  soft_limit = 8,       // a setpoint beyond the axis's soft limits
  following_error = 9,  // command and actual position too far apart
  homing_failed = 10,   // homing error (statusword bit 13) or no end within its time
  foreign_sync = 11,    // a SYNC this node did not send: another SYNC producer on the bus
};
inline constexpr int kAlarmBase = 2000;  // alarm number = kAlarmBase + AxisAlarm
const char* to_text(AxisAlarm alarm) noexcept;

struct AxisNodeOutput {
  std::uint16_t controlword = 0;
  std::int32_t target_counts = 0;
  double cmd = 0.0;      // commanded position (units)
  double act = 0.0;      // actual position (units)
  double vel = 0.0;      // actual velocity (units/s)
  double vel_cmd = 0.0;  // a spindle in CSV: commanded velocity (units/s)
  std::int32_t target_velocity_counts = 0;
  std::int8_t mode = kModeCsp;          // modes of operation to send (a spindle's RPDO)
  std::int8_t mode_display = kModeCsp;  // the mode the drive runs in
  bool mode_changed = false;            // the drive switched modes this cycle
  bool homed = false;                   // the homing reached its end (homing axes)
  cia402::State drive_state = cia402::State::not_ready_to_switch_on;
  bool enabled = false;                   // operation enabled and following setpoints
  bool quick_stop = false;                // quick stop commanded (latched until restart)
  AxisAlarm new_alarm = AxisAlarm::none;  // raised this cycle
  AxisAlarm alarm = AxisAlarm::none;      // the active (first) alarm
  bool drive_state_changed = false;
  int missing_setpoints = 0;      // cycles since the last setpoint (skipped cycles count)
  std::uint16_t touch_probe = 0;  // 0x60B8 to send: touch probe 1 as the owner asks
  // The probe as the drive reports it for the function sent: armed (enabled, nothing stored)
  // or latched at probe_pos (units).
  ProbeState probe = ProbeState::off;
  double probe_pos = 0.0;
  // In continuous mode the edges latched since the probe was enabled (probe_pos: the last),
  // counted on from the drive's count modulo 4; 0 in the other modes.
  std::uint32_t probe_count = 0;
  // 0x6072 to send (torque_skip): the owner's limit, per mille of the rated torque, or none.
  std::uint16_t max_torque = canopen::kNoTorqueLimit;
  // 0x6071 and 0x6080 to send (torque_mode): per mille of the rated torque, rpm; 0 in CSP.
  std::int16_t target_torque = 0;
  std::uint32_t max_motor_speed = 0;
};

class AxisNodeController {
 public:
  explicit AxisNodeController(const AxisNodeSetup& setup) noexcept;
  // One cycle. Cycle numbers increase; a gap (realtime ticks skipped) counts as that many
  // cycles without input.
  const AxisNodeOutput& cycle(std::uint64_t cycle, const AxisNodeInput& in) noexcept;
  [[nodiscard]] const AxisNodeOutput& output() const noexcept { return out_; }
  // Operator reset, applied once the drive is at rest (a quick stop or fault reaction finishes
  // its ramp first): clears the alarms and the quick-stop latch. A drive in fault gets one
  // fault reset (controlword bit 7 rising), then the enable sequence; the node takes over the
  // drive's position again when it is back in operation. A cause that is still there raises
  // its alarm again: a drive still in fault after fault_reset_cycles or faulting again, a
  // heartbeat still silent after the consumer time, bus off and E-stop at once.
  void reset() noexcept { reset_requested_ = true; }
  // The drive may now be disabled without letting its axis fall or coast: it is out of
  // operation and no longer braking (a quick stop that has halted, or never enabled). A drive
  // in operation, in a quick stop still ramping down or in a fault reaction may not.
  [[nodiscard]] bool ready_to_disable() const noexcept;

 private:
  void raise(AxisAlarm alarm) noexcept;
  [[nodiscard]] bool drive_at_rest() const noexcept;
  // Touch probe 1: the function to send and what the drive reports of the last one sent.
  void probe_cycle(const AxisNodeInput& in) noexcept;
  // G160: the max torque to send, and the torque skip while the owner asks for it.
  void torque_cycle(const AxisNodeInput& in) noexcept;
  // The following error allowed now: the limit, and while a torque limit stands its skip
  // deviation besides (the axis presses against what holds it, decision 100).
  [[nodiscard]] double following_error_allowed() const noexcept;

  AxisNodeSetup setup_;
  AxisNodeOutput out_{};
  std::uint16_t raised_ = 0;  // bit per AxisAlarm: each is raised once, then stays active
  bool have_position_ = false;
  bool was_enabled_ = false;  // the drive has been in operation (drive and owner watched)
  bool following_ = false;    // in operation and following since the last take-over
  bool reset_requested_ = false;
  bool resetting_ = false;  // a reset under way: the drive's fault is being reset
  std::uint64_t reset_cycle_ = 0;
  std::uint64_t last_tpdo_cycle_ = 0;
  std::uint64_t last_setpoint_cycle_ = 0;
  std::uint64_t last_cycle_ = 0;
  bool owner_seen_ = false;  // the setpoint deadline runs once the owner has sent a setpoint
  double last_setpoint_vel_ = 0.0;
  std::uint64_t heartbeats_ = 0;
  std::int8_t requested_mode_ = kModeCsp;
  bool homed_ = false;
  std::uint64_t homing_since_ = 0;  // cycle the homing began (0: not yet)
  std::uint16_t statusword_ = 0;    // the last one received
  std::int64_t counts_ = 0;         // position actual, unwrapped
  std::int32_t last_counts_ = 0;
  std::uint16_t probe_edge_bits_ = 0;     // 0x60B9 bits 6-7 as last counted
  bool homing_started_ = false;           // in operation in homing mode: bit 4 goes up next
  std::uint64_t start_sent_cycle_ = 0;    // the cycle bit 4 first went out (0: not yet)
  canopen::HeartbeatConsumer heartbeat_;  // in cycles
  // G160: the owner's torque limit (percent, 0: none) and skip deviation, from its last
  // setpoint; the command the drive followed at its last SYNC; a torque skip latched.
  double torque_limit_ = 0.0;
  double skip_deviation_ = 0.0;
  double sent_cmd_ = 0.0;
  bool torque_latched_ = false;
};

}  // namespace mcnc::axisnode
