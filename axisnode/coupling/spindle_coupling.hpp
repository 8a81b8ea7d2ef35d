#pragma once
// G114.1 spindle synchronisation as the slave spindle's axis node runs it (spec dafeng §2.6.13,
// §3.7): the slave follows the master's position times Q/P plus the phase R, with the master's
// direction times the sign of Q. From wherever the slave stands (at rest, or turning) it
// accelerates within its limit until speed and phase match ("dynamic sync"), then follows the
// master exactly ("locked"). The coupling is the slave node's state: a reset does not end it,
// only G113 does. G51.2 polygon turning (§2.6.6) is the same coupling with the phase given at
// the master (polygon_command), and ends by release(): the slave decelerates to rest.
// Pure: one step per cycle, no allocation, no exceptions.
#include <cstdint>

namespace mcnc::coupling {

struct SpindleCouplingSetup {
  double cycle_s = 0.001;
  double max_acceleration = 3600.0;  // deg/s^2 the slave may use to catch up
  double lock_phase = 0.05;          // deg: in phase within this ...
  double lock_speed = 1.0;           // deg/s: ... and at speed within this: locked
};

struct SpindleCouplingCommand {
  int p = 1;       // master ratio
  int q = 1;       // slave ratio (sign: direction)
  double r = 0.0;  // phase offset of the slave, degrees
};

struct SlaveTarget {
  double pos = 0.0;  // deg
  double vel = 0.0;  // deg/s
  bool locked = false;
};

class SpindleCoupling {
 public:
  explicit SpindleCoupling(const SpindleCouplingSetup& setup) noexcept : setup_(setup) {}

  // Starts following from where the slave stands now.
  void couple(const SpindleCouplingCommand& command, double slave_pos, double slave_vel) noexcept;
  void decouple() noexcept { active_ = false; }
  // Stops following: the slave decelerates within its limit and the coupling ends once it
  // stands (G50.2, spec dafeng L2925-2927).
  void release() noexcept { releasing_ = active_; }
  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] bool releasing() const noexcept { return active_ && releasing_; }
  [[nodiscard]] bool locked() const noexcept { return active_ && locked_; }

  // One cycle: the master's position and velocity at this cycle (deg, deg/s) in, the slave's
  // commanded position and velocity out.
  SlaveTarget step(double master_pos, double master_vel) noexcept;

 private:
  SlaveTarget step_release() noexcept;

  SpindleCouplingSetup setup_;
  SpindleCouplingCommand command_{};
  bool active_ = false;
  bool locked_ = false;
  bool releasing_ = false;
  double pos_ = 0.0;
  double vel_ = 0.0;
};

// G51.2 P Q R: the slave turns Q/P times the master, and stands at its zero while the master
// stands at R, its start angle (spec dafeng L2851-2856); as a coupling command, the phase the
// slave has when the master is at zero.
SpindleCouplingCommand polygon_command(int p, int q, double master_start) noexcept;

// `angle` folded into (-180, 180].
double wrap_degrees(double angle) noexcept;

}  // namespace mcnc::coupling
