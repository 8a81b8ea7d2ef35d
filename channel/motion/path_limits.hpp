#pragma once
// What a block's geometry allows the path: the per-axis limits of the machine projected on a
// straight move, and the velocity through a corner that a blend within the path tolerance
// allows. The look-ahead takes its per-block limits from here. Pure math.
#include "channel/interp/canonical_command.hpp"
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

// The highest velocity through the corner from unit direction `in` to unit direction `out` (the
// first `axis_count` axes) such that a blend arc that leaves the corner by at most `tolerance`
// keeps its centripetal acceleration within `acceleration`. With theta the angle between -in
// and out, the blend radius is tolerance * sin(theta/2) / (1 - sin(theta/2)) and the velocity
// sqrt(acceleration * radius). Straight on: infinity; a reversal: 0.
double corner_velocity(const interp::AxisVector& in, const interp::AxisVector& out,
                       std::size_t axis_count, double tolerance, double acceleration) noexcept;

}  // namespace mcnc::motion
