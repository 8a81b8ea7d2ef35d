#include "channel/motion/path_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mcnc::motion {

JerkLimits line_limits(const interp::AxisVector& direction, std::span<const AxisDynamics> axes,
                       double feed) noexcept {
  const std::size_t n = std::min(axes.size(), direction.size());
  double length = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    length += direction[i] * direction[i];
  }
  length = std::sqrt(length);
  constexpr double kNone = std::numeric_limits<double>::infinity();
  JerkLimits l{kNone, kNone, kNone};
  if (length <= 0.0) {
    return l;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double share = std::fabs(direction[i]) / length;
    if (share <= 1e-15) {
      continue;
    }
    l.velocity = std::min(l.velocity, axes[i].velocity / share);
    l.acceleration = std::min(l.acceleration, axes[i].acceleration / share);
    l.jerk = std::min(l.jerk, axes[i].jerk / share);
  }
  if (feed > 0.0) {
    l.velocity = std::min(l.velocity, feed);
  }
  return l;
}

}  // namespace mcnc::motion
