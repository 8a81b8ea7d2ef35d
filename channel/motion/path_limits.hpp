#pragma once
// What a straight move allows the path: the per-axis limits of the machine projected on its
// direction. The look-ahead takes its line limits from here. Pure math.
#include "channel/interp/axis_vector.hpp"
#include "channel/motion/jerk_limited_profile.hpp"

#include <cstddef>
#include <span>

namespace mcnc::motion {

// One axis's dynamic limits (machine file): units/s, units/s^2, units/s^3; all > 0.
struct AxisDynamics {
  double velocity = 0.0;
  double acceleration = 0.0;
  double jerk = 0.0;
};

// The highest path velocity, acceleration and jerk along `direction` (any non-zero length) at
// which no axis exceeds its own: an axis whose share of the direction is u limits the path to
// its limit / |u|; an axis that does not move does not limit. `feed` > 0 caps the velocity.
// axes.size() axes of `direction` are used.
JerkLimits line_limits(const interp::AxisVector& direction, std::span<const AxisDynamics> axes,
                       double feed) noexcept;

}  // namespace mcnc::motion
