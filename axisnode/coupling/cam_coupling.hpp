#pragma once
// G51.8 / G50.8 electronic cam as the slave axis's node runs it (spec dafeng §2.6.7-2.6.10,
// L3013-3230): a lift, a function of the master spindle's angle, laid over the position the
// slave's channel commands. The lift is a table of N values that divide one master revolution
// into N equal steps from the start angle R (linear between points, the last one joining the
// first), an ellipse (H1) or an eccentric circle (H2). The offset the node adds reaches the lift
// from where it stands (0 when the cam starts) within the axis's velocity and acceleration, then
// follows it exactly ("locked": on the lift with neither limit in the way); release() brings it
// back to 0 the same way before the coupling ends. Lift values are radial: what the axis moves,
// also on a diameter axis. Pure: one step per cycle, no allocation, no exceptions.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::coupling {

// Macro variables #1-#999 hold a table at most (L3048).
inline constexpr std::size_t kMaxCamPoints = 999;

enum class CamShape : std::uint8_t {
  table,      // G51.8 P L R
  ellipse,    // G51.8 H1 A B R: semi-axes a (at the start angle) and b
  eccentric,  // G51.8 H2 D P R: a = the circle's radius D/2, b = the eccentricity P
};

struct CamProfile {
  CamShape shape = CamShape::table;
  std::size_t points = 0;  // table: how many of `lift` are used
  std::array<double, kMaxCamPoints> lift{};
  double a = 0.0;
  double b = 0.0;
  double start = 0.0;  // R: the master angle of the table's first point (degrees)
};

// Why `profile` cannot be a cam (nullptr: it can): a table of 0 or more than 999 points, an
// ellipse whose semi-axes are not positive, an eccentricity not below the circle's radius (the
// spindle's axis would lie outside the circle), a start angle outside 0-360.
const char* cam_profile_error(const CamProfile& profile) noexcept;

// The lift at master angle `master_deg` (any real number of degrees). Shapes are 0 at the start
// angle: the ellipse's radius minus a, the eccentric circle's distance from the spindle's axis
// minus its largest, a + b.
double cam_lift(const CamProfile& profile, double master_deg) noexcept;

// The profile of G51.8's words: shape 0 with the table `lift` (at most kMaxCamPoints taken), 1
// (H1) with A and B, 2 (H2) with the diameter D and the eccentricity P; R is `start`. Another
// shape is a table of no points, which cam_profile_error refuses.
CamProfile cam_profile_of(std::uint8_t shape, double first, double second, double start,
                          std::span<const double> lift) noexcept;

struct CamCouplingSetup {
  double cycle_s = 0.001;
  double max_velocity = 100.0;       // units/s the offset may move at
  double max_acceleration = 1000.0;  // units/s^2
};

struct CamOffset {
  double pos = 0.0;  // units, added to the channel's setpoint
  double vel = 0.0;  // units/s
  bool locked = false;
};

class CamCoupling {
 public:
  explicit CamCoupling(const CamCouplingSetup& setup) noexcept : setup_(setup) {}

  // Follows `profile` from the next step on, from the offset as it stands (0 unless a cam runs).
  void couple(const CamProfile& profile) noexcept;
  // G50.8: the offset goes back to 0 within the limits; the coupling ends once it is there.
  void release() noexcept { releasing_ = active_; }
  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] bool releasing() const noexcept { return active_ && releasing_; }
  [[nodiscard]] bool locked() const noexcept { return active_ && !releasing_ && locked_; }
  [[nodiscard]] double offset() const noexcept { return pos_; }

  // One cycle with the master's angle at this cycle (degrees).
  CamOffset step(double master_deg) noexcept;
  // One cycle without the master's feedback: the offset holds (a releasing one goes on to 0).
  CamOffset step_without_master() noexcept;

 private:
  CamOffset track(double target) noexcept;

  CamCouplingSetup setup_;
  CamProfile profile_{};
  bool active_ = false;
  bool releasing_ = false;
  bool locked_ = false;
  bool have_target_ = false;  // target_ is last cycle's
  double target_ = 0.0;
  double pos_ = 0.0;
  double vel_ = 0.0;
};

}  // namespace mcnc::coupling
