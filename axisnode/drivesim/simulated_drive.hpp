#pragma once
// One simulated CiA 402 servo drive in cyclic synchronous position, velocity or torque mode. Time
// advances only through on_sync(), one cycle per call, so a run is a pure function of the frames
// received.
#include "axisnode/drivesim/drive_objects.hpp"
#include "canopen/cia402/cia402_state.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/frames.hpp"
#include "canopen/heartbeat.hpp"

#include <array>
#include <cstdint>

namespace mcnc::drivesim {

// Faults a simulated drive can be told to have (fault injection for tests and demos).
enum class DriveFault : std::uint8_t {
  none,
  overcurrent,      // EMCY 0x2310, CiA 402 fault (fault reaction: quick-stop ramp)
  following_error,  // EMCY 0x8611, CiA 402 fault
  heartbeat_stop,   // the heartbeat producer falls silent; everything else goes on
};

// A value the drive's object dictionary holds after power-on and reset node, like an EDS
// file's DefaultValue (numeric objects up to 32 bits).
struct ObjectDefault {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::int64_t value = 0;
};

struct DriveParams {
  std::uint8_t node_id = 1;
  double counts_per_unit = 10000.0;
  double time_constant_s = 0.004;    // position loop: gain 1 / tau (following error ~ v * tau)
  double max_velocity = 500.0;       // units/s
  double quick_stop_decel = 5000.0;  // units/s^2
  double initial_position = 0.0;     // units
  // The mechanics, at the motor shaft: J w' = T - B w, |T| <= torque_limit.
  double units_per_rev = 10.0;           // load units per motor revolution (lead, 360 / ratio)
  double inertia = 0.0005;               // J, kg m^2 (motor and load, reflected)
  double friction = 0.001;               // B, N m s/rad (viscous)
  double torque_limit = 10.0;            // N m
  double rated_torque = 3.0;             // N m, the motor's (0x6076): 0x6077 is per mille of it
  double velocity_bandwidth_hz = 200.0;  // the velocity loop (PI) is tuned for this
  // Touch probe 1 (0x60B8-0x60BB): its input is on while the axis stands at or beyond
  // `probe_at` (units) on the side `probe_side` (+1 above, -1 below), as a stylus touching a
  // part there; 0: the drive has no probe input.
  int probe_side = 0;
  double probe_at = 0.0;
  // Teeth (G31.8): with `probe_pitch` above 0 the input is on only within `probe_count`
  // windows of `probe_width`, the k-th from probe_at + k * probe_pitch on the side probe_side
  // (a gear's teeth passing the sensor); probe_width < probe_pitch.
  double probe_pitch = 0.0;
  double probe_width = 0.0;
  int probe_count = 1;
  // A contact (a part, a centre the tailstock presses against): the load cannot pass
  // `contact_at` (units) going to the side `contact_side` (+1 above, -1 below; 0: none). There
  // the motor stands while the position loop's torque rises to its limit (G160).
  int contact_side = 0;
  double contact_at = 0.0;
  // Object defaults from the machine file (drive.objects), applied after the built-in ones.
  std::array<ObjectDefault, 16> objects{};
  std::size_t object_count = 0;
};

// One drive in cyclic synchronous position mode.
//
// NMT: bootup until power_on(), then pre-operational; start / stop / enter pre-operational as
// in CiA 301; reset node and reset communication return to pre-operational (the caller sends
// the boot-up). Reset node also restarts the CiA 402 state machine (switch on disabled) and
// clears the latched RPDO; the position is kept, as a motor does not move on a reset.
//
// Motion per on_sync(), integrated in 8 or more steps per cycle (a drive's inner loops run
// faster than the bus; more steps where the loop's bandwidth or the friction needs them to stay
// stable): a cascade like a real servo drive's.
//  - the velocity command: CSP P-position loop, (target - pos) / tau, clamped to
//    +-max_velocity; CSV the target velocity, clamped; quick stop and fault reaction a ramp
//    from the velocity at its start to 0 at quick_stop_decel.
//  - a PI velocity loop (gain J * 2 pi f, integral with anti-windup) gives the torque, limited
//    to torque_limit and to the max torque 0x6072 (per mille of rated_torque; its default is
//    torque_limit, by SDO or in an RPDO); the mechanics J w' = T - B w move the motor, and the load
//    by units_per_rev per revolution.
//  - a contact stops the load where it is (a rigid stop, no rebound).
//  - the fault reaction ends in fault at standstill; in every other state the brake holds:
//    v = 0 and pos stays.
// The target is taken from RPDOs received after the SYNC that enabled operation; until then
// (and in every other state) it follows the actual position, so enabling never jumps.
//
// Modes of operation (0x6060, by SDO or in an RPDO): 8 CSP (and 0, as before any was set); 9
// CSV: the target velocity 0x60FF (counts/s) is the velocity loop's command; 10 CST: the
// target torque 0x6071 (per mille of rated_torque, within 0x6072 and torque_limit) drives the
// mechanics, the motor's speed bounded by 0x6080 (rpm; 0: max_velocity) the way the torque
// turns it, so that a free motor runs at the limit and one against a contact presses with the
// set torque; 6 homing:
// methods 35 and 37 only (no switches on a simulated axis): on the rising edge of controlword
// bit 4 in operation enabled the current position becomes the home offset (0x607C), without
// moving, and statusword bit 12 (homing attained) is set until the mode changes.
class SimulatedDrive {
 public:
  SimulatedDrive(const DriveParams& params, double cycle_s) noexcept;
  [[nodiscard]] std::uint8_t node_id() const noexcept;
  [[nodiscard]] canopen::NmtState nmt_state() const noexcept;
  [[nodiscard]] cia402::State state() const noexcept;
  [[nodiscard]] double position() const noexcept;  // units
  [[nodiscard]] double velocity() const noexcept;  // units/s
  [[nodiscard]] double target() const noexcept;    // units, the target the loop follows
  [[nodiscard]] double torque() const noexcept { return torque_; }  // N m, the last one applied
  void power_on() noexcept;  // bootup -> pre-operational, CiA 402 -> switch on disabled
  void on_nmt(canopen::NmtCommand command) noexcept;    // ignored before power_on()
  void on_rpdo(const canopen::RxPdoCsp& pdo) noexcept;  // latched until the next SYNC
  // An RPDO read by the drive's mapping (DriveObjects::decode_rpdo): what it carries is latched
  // until the next SYNC, where a mode of operation (0x6060) in it takes effect.
  void on_rpdo(const RpdoValues& values) noexcept;
  [[nodiscard]] bool rpdo_since_sync() const noexcept { return rpdo_since_sync_; }
  // One cycle: apply the latched controlword/target, move; the TPDO to answer with.
  canopen::TxPdoCsp on_sync() noexcept;
  // The drive's object dictionary (what its SDO server reads and writes).
  [[nodiscard]] DriveObjects& objects() noexcept { return objects_; }
  [[nodiscard]] const DriveObjects& objects() const noexcept { return objects_; }
  // The heartbeat to send after this SYNC, when one is due (every producer time 0x1017, in
  // SYNC-counted time so that lockstep runs see it at the same cycles every time).
  bool heartbeat(can::CanFrame& out) noexcept;
  // The heartbeat of a drive that an NMT command took out of operational: no SYNC counts its
  // time any more, so its producer runs on `now_us` (the simulator's wall clock), as a real
  // drive's does in stopped and pre-operational (CiA 301). A healthy lockstep run never takes
  // a drive out of operational before its end, so its heartbeats stay SYNC-counted.
  bool heartbeat_out_of_operation(std::uint64_t now_us, can::CanFrame& out) noexcept;
  // The fault happens at the SYNC with this number (counted from 1 after power on).
  void schedule_fault(DriveFault fault, std::uint64_t at_sync) noexcept {
    fault_ = fault;
    fault_at_ = at_sync;
  }
  // The EMCY the drive has to send (once), error code 0 when none.
  // Writes the defaults into the object dictionary (power-on, reset node): 0x6085 from
  // quick_stop_decel, then `objects`. The SDO abort code of the first that fails, 0 when all
  // were taken; `failed` names it.
  std::uint32_t apply_defaults(ObjectDefault* failed = nullptr) noexcept;
  [[nodiscard]] canopen::Emcy take_emcy() noexcept {
    const canopen::Emcy e = emcy_;
    emcy_ = {};
    return e;
  }

 private:
  void move_one_cycle() noexcept;
  // Touch probe 1 over the cycle's move from `from` to the present position: the edges of its
  // input latch where it switched as the function 0x60B8 asks (the first event of each edge,
  // or every edge in continuous mode, counted in 0x60B9 bits 6-7).
  void run_touch_probe(double from) noexcept;
  [[nodiscard]] bool probe_input(double position) const noexcept;
  // The velocity and mechanics for one cycle; velocity command from the mode (see above).
  enum class Loop : std::uint8_t { position, velocity, torque, ramp_down };
  void run_loops(Loop loop, double dt) noexcept;
  [[nodiscard]] bool target_reached() const noexcept;
  [[nodiscard]] std::int32_t to_counts(double units) const noexcept;        // saturating
  [[nodiscard]] std::int32_t position_counts(double units) const noexcept;  // wrapping

  DriveParams params_;
  double cycle_s_;
  canopen::NmtState nmt_ = canopen::NmtState::bootup;
  bool powered_ = false;
  cia402::DeviceStateMachine device_;
  RpdoValues latched_{};
  bool rpdo_since_sync_ = false;
  double position_;
  double velocity_ = 0.0;
  double target_;
  double previous_target_ = 0.0;  // CSP: the last SYNC's target (fine interpolation)
  double torque_ = 0.0;
  double integral_ = 0.0;  // the velocity loop's integral part, N m
  double ramp_ = 0.0;      // quick stop: the ramp's velocity command, units/s
  DriveObjects objects_;
  std::uint64_t syncs_ = 0;
  DriveFault fault_ = DriveFault::none;
  std::uint64_t fault_at_ = 0;
  bool heartbeat_stopped_ = false;
  canopen::HeartbeatProducer heartbeat_{0, 0};
  std::uint16_t heartbeat_ms_ = 0;  // the producer time heartbeat_ runs with
  // Out of operational by an NMT command after it had been operational: heartbeats on the wall
  // clock (heartbeat_out_of_operation).
  bool out_of_operation_ = false;
  canopen::HeartbeatProducer wall_heartbeat_{0, 0};
  std::uint16_t wall_heartbeat_ms_ = 0;  // the producer time wall_heartbeat_ runs with
  double velocity_target_ = 0.0;         // CSV: units/s
  bool homing_attained_ = false;
  bool homing_bit_ = false;  // controlword bit 4 at the last SYNC (homing starts on its edge)
  std::uint16_t probe_status_ = 0;  // 0x60B9
  canopen::Emcy emcy_{};
};

}  // namespace mcnc::drivesim
