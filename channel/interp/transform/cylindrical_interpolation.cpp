#include "channel/interp/transform/cylindrical_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::interp::transform {

double CylindricalInterpolation::to_degrees(double length) const {
  return length * 180.0 / (std::numbers::pi * radius_);
}

double CylindricalInterpolation::to_length(double degrees) const {
  return degrees * std::numbers::pi * radius_ / 180.0;
}

std::vector<double> CylindricalInterpolation::chord_ends(const PlanePiece& piece, double tolerance,
                                                         std::size_t max_chords) {
  if (!piece.arc) {
    return {1.0};
  }
  const double r0 = std::hypot(piece.from[0] - piece.centre[0], piece.from[1] - piece.centre[1]);
  const double r1 = std::hypot(piece.to[0] - piece.centre[0], piece.to[1] - piece.centre[1]);
  const double r = std::max(r0, r1);
  if (r <= 0.0) {
    return {1.0};
  }
  // A chord over the angle t stands r (1 - cos(t / 2)) off the circle at its middle.
  const double widest =
      std::min(std::numbers::pi / 2.0, 2.0 * std::acos(std::max(-1.0, 1.0 - tolerance / r)));
  const double sweep = piece.length() / (0.5 * (r0 + r1));
  const double chords = std::max(1.0, std::ceil(sweep / widest - 1e-12));
  if (!(chords <= static_cast<double>(max_chords))) {
    return {};
  }
  const auto n = static_cast<std::size_t>(chords);
  std::vector<double> ends;
  ends.reserve(n);
  for (std::size_t k = 1; k <= n; ++k) {
    ends.push_back(k == n ? 1.0 : static_cast<double>(k) / static_cast<double>(n));
  }
  return ends;
}

}  // namespace mcnc::interp::transform
