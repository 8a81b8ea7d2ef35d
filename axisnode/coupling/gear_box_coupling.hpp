#pragma once
// G81.4 / G80.4, the electronic gear box (EGB), as the work axis's node runs it (spec dafeng
// §2.6.11, L3231-3374): an offset laid over the position the work axis's channel commands, so
// that the work axis turns L/T times its tool spindle (L hob threads, T work teeth), plus, for a
// helical gear, the differential angle of the axial feed axis's travel since G81.4,
// travel x sin(P) / (pi T Q) x 360 degrees (P the helix angle, Q the module). With R the work
// axis is brought into phase with the tool spindle by the shortest way, within one period of
// 360 |L| / T degrees; without R it keeps the phase it had at G81.4.
//
// The offset grows without end, so it is not tracked like the cam's bounded lift: it catches up
// like a coupled spindle (catch_up_acceleration: speed first, then phase) within the work axis's
// acceleration (param 5313), then follows exactly ("locked"). Once locked, a commanded work speed
// that stays off the ratio's by more than the allowed deviation (5336) for longer than the
// allowed time (5337) raises the deviation alarm and the coupling stops. G80.4 (release) brings
// the work axis to rest within the stop time (5333) from the speed it has, and leaves it where it
// reached: the offset stays (stopped_offset) until the channel has taken it into its own
// position (absorb). Pure: one step per cycle, no allocation, no exceptions.
#include <cstdint>

namespace mcnc::coupling {

struct GearBoxCommand {
  int teeth = 1;        // T, 1 or more
  int threads = 1;      // L, not 0 (sign: the work axis's direction)
  double helix = 0.0;   // P, degrees (0: a spur gear)
  double module = 0.0;  // Q, mm (sign: the helical term's direction; 0: a spur gear)
  bool phase = false;   // R given: phase matching
  double r = 0.0;       // R, degrees: the work axis's angle while the tool spindle is at 0
};

struct GearBoxSetup {
  double cycle_s = 0.001;
  double max_acceleration = 3600.0;  // deg/s^2 the offset may catch up at (param 5313)
  double stop_time_s = 0.5;          // s: G80.4 stops the work axis within this (param 5333)
  double lock_phase = 0.05;          // deg: on the ratio within this ...
  double lock_speed = 1.0;           // deg/s: ... and at its speed within this: locked
  double max_deviation = 0.0;        // deg/s off the ratio's work speed (5336; 0: not watched)
  double deviation_time_s = 0.0;     // s: for longer than this, the alarm (5337)
  bool reverse = false;              // param 5320.2: the work axis turns the other way
  bool helix_reverse = false;        // param 5320.3: the helical term the other way
};

// Why `command` cannot be a gear box (nullptr: it can): T below 1, L 0, a helix angle outside
// -90..90 degrees or without a module, a module outside 0.1-25 mm, R outside 0-360.
const char* gear_box_command_error(const GearBoxCommand& command) noexcept;

// The work axis's degrees per degree of the tool spindle: L/T, negated by param 5320.2.
double gear_box_ratio(const GearBoxCommand& command, bool reverse) noexcept;

// The helical gear's differential angle (degrees) for `axial_travel` (mm) of the axial feed
// axis: travel x sin(P) / (pi T Q) x 360, negated by param 5320.3; 0 for a spur gear.
double helical_angle(const GearBoxCommand& command, double axial_travel,
                     bool helix_reverse) noexcept;

struct GearBoxOffset {
  double pos = 0.0;  // deg, added to the channel's setpoint of the work axis
  double vel = 0.0;  // deg/s
  bool locked = false;
};

class GearBoxCoupling {
 public:
  explicit GearBoxCoupling(const GearBoxSetup& setup) noexcept : setup_(setup) {}

  // G81.4 from this cycle on: the tool spindle at `tool_deg`, the axial axis at `axial` (mm;
  // 0 without one), the work axis's channel commanding `work_setpoint` (deg). The offset goes on
  // from where it stands (0, or what an earlier G80.4 left and the channel has not absorbed).
  void couple(const GearBoxCommand& command, double tool_deg, double axial,
              double work_setpoint) noexcept;
  // G80.4 (or the deviation alarm, or a reset): the work axis slows down to rest within the
  // stop time; the coupling ends there.
  void release() noexcept;
  // The channel commands the work axis at the reached angle now: the offset is its own.
  void absorb() noexcept;

  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] bool releasing() const noexcept { return active_ && releasing_; }
  [[nodiscard]] bool locked() const noexcept { return active_ && !releasing_ && locked_; }
  [[nodiscard]] double offset() const noexcept { return pos_; }
  // The coupling stopped the work axis off the channel's setpoint: what the channel takes over.
  [[nodiscard]] bool stopped_off_setpoint() const noexcept { return !active_ && pos_ != 0.0; }
  // The work speed stayed off the ratio's too long (param 5336/5337); latched until couple().
  [[nodiscard]] bool deviation_alarm() const noexcept { return deviation_alarm_; }
  // The largest |commanded work speed - the ratio's| seen while locked since couple(), deg/s.
  [[nodiscard]] double worst_deviation() const noexcept { return worst_deviation_; }

  // One cycle: the tool spindle's angle and speed (deg, deg/s) and the axial axis's position
  // and speed (mm, mm/s) at this cycle.
  GearBoxOffset step(double tool_deg, double tool_vel, double axial, double axial_vel) noexcept;
  // One cycle without the tool spindle's feedback: the work axis slows down as for G80.4.
  GearBoxOffset step_without_master() noexcept;

 private:
  GearBoxOffset step_release() noexcept;
  void watch_deviation(double deviation) noexcept;

  GearBoxSetup setup_;
  GearBoxCommand command_{};
  double ratio_ = 1.0;
  double target_base_ = 0.0;  // the offset's target = ratio x tool + helical + target_base_
  double axial_start_ = 0.0;
  bool active_ = false;
  bool releasing_ = false;
  bool locked_ = false;
  bool locked_once_ = false;           // since couple(): a fall out of lock is a deviation
  double release_deceleration_ = 0.0;  // deg/s^2
  double deviation_s_ = 0.0;
  bool deviation_alarm_ = false;
  double worst_deviation_ = 0.0;
  double pos_ = 0.0;
  double vel_ = 0.0;
};

}  // namespace mcnc::coupling
