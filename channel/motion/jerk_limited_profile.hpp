#pragma once
// A 1-D move over a distance from one velocity to another, both without acceleration, with
// bounded velocity, acceleration and jerk: the 7-phase S-curve (jerk up, constant acceleration,
// jerk down, cruise, and the mirrored deceleration). The look-ahead chains these along the path;
// a block's junction velocities come from its backward and forward passes. Pure math, no
// allocation, no exceptions.
#include <array>
#include <cstdint>

namespace mcnc::motion {

// The state of a 1-D motion along its path.
struct ProfileSample {
  double s = 0.0;  // distance travelled
  double v = 0.0;  // velocity
  double a = 0.0;  // acceleration
};

enum class ProfileResult : std::uint8_t {
  ok,
  bad_limits,   // a limit <= 0, a negative distance or velocity, an end above v_max
  unreachable,  // the end velocity cannot be reached within the distance
};

struct JerkLimits {
  double velocity = 0.0;      // > 0
  double acceleration = 0.0;  // > 0
  double jerk = 0.0;          // > 0
};

// Time and distance to change speed from v0 to v1 (zero acceleration at both ends) at the
// limits: |v1 - v0| >= a^2/j takes a constant-acceleration phase, a shorter change does not.
double speed_change_time(double v0, double v1, const JerkLimits& limits) noexcept;
double speed_change_distance(double v0, double v1, const JerkLimits& limits) noexcept;

class JerkLimitedProfile {
 public:
  JerkLimitedProfile() = default;

  // The fastest profile: up to the highest velocity the distance allows (at most the limit),
  // cruise, down to v_end. A start above the limit (an override lowered under way) first slows
  // down to the limit. `out` is unchanged unless the result is ok.
  static ProfileResult plan(double distance, double v_start, double v_end, const JerkLimits& limits,
                            JerkLimitedProfile& out) noexcept;

  // The state at time t after the start: the start before 0, exactly the end (distance, v_end,
  // no acceleration) from duration() on, so chained blocks never drift.
  [[nodiscard]] ProfileSample at(double t) const noexcept;

  [[nodiscard]] double duration() const noexcept { return total_; }
  [[nodiscard]] double peak_velocity() const noexcept { return v_peak_; }
  [[nodiscard]] double cruise_time() const noexcept { return phases_[3].duration; }

 private:
  struct Phase {
    double duration = 0.0;
    double jerk = 0.0;
    ProfileSample start;  // the state where the phase begins
  };
  std::array<Phase, 7> phases_{};
  double distance_ = 0.0;
  double v_end_ = 0.0;
  double v_peak_ = 0.0;
  double total_ = 0.0;
};

}  // namespace mcnc::motion
