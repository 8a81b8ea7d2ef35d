#pragma once
// Speed changes that start with an acceleration: what the look-ahead needs when it replans a
// move already under way (feed hold, override, a window that grew) and what a thread's ramp-in
// is. Pure math, no allocation, no exceptions.
#include "channel/motion/jerk_limited_profile.hpp"

#include <array>
#include <cstddef>

namespace mcnc::motion {

// Up to three phases of constant jerk from a start state. Past its duration the motion goes on
// at the end velocity with no acceleration.
class JerkPhases {
 public:
  struct Phase {
    double duration = 0.0;
    double jerk = 0.0;
  };

  JerkPhases() = default;
  explicit JerkPhases(const ProfileSample& start) noexcept : start_(start), end_(start) {}
  void add(double duration, double jerk) noexcept;

  [[nodiscard]] ProfileSample at(double t) const noexcept;
  [[nodiscard]] ProfileSample end() const noexcept { return end_; }
  [[nodiscard]] double duration() const noexcept { return total_; }

 private:
  std::array<Phase, 3> phases_{};
  std::size_t count_ = 0;
  ProfileSample start_{};
  ProfileSample end_{};
  double total_ = 0.0;
};

// The quickest change from velocity v0 at acceleration a0 (|a0| <= acceleration) to v1 with
// no acceleration, within the acceleration and jerk limits (limits.velocity is not used): jerk
// toward the needed side, hold the acceleration limit if the change needs it, jerk back to
// zero. v1 = v0 + a0 |a0| / (2 jerk) is a single phase that only brings the acceleration to
// zero. Starts at s = 0.
JerkPhases speed_transition(double v0, double a0, double v1, const JerkLimits& limits) noexcept;

// The velocity reached by bringing acceleration a0 to zero at the jerk limit.
double released_velocity(double v0, double a0, double jerk) noexcept;

// The highest speed v (at most limits.velocity, at least v_other) from which a speed change to
// or from v_other fits in `distance`: speed_change_distance(v, v_other) <= distance. Closed
// form (a quadratic with a constant-acceleration phase, a cubic without).
double max_speed_within(double distance, double v_other, const JerkLimits& limits) noexcept;

}  // namespace mcnc::motion
