#pragma once
// Constant surface speed (G96): the spindle speed that gives the programmed surface speed at
// the tool's distance from the spindle axis, clamped by G50 S and the machine's maximum.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::motion {

// surface_m_min: m/min; radius_mm: distance from the spindle axis; clamp_rpm / machine_rpm:
// 0 = none. At the axis itself the clamp is the answer (0 without one).
inline double constant_surface_rpm(double surface_m_min, double radius_mm, double clamp_rpm,
                                   double machine_rpm) noexcept {
  double limit = 0.0;
  for (const double c : {clamp_rpm, machine_rpm}) {
    if (c > 0.0) {
      limit = limit > 0.0 ? std::min(limit, c) : c;
    }
  }
  const double r = std::fabs(radius_mm);
  if (r <= 1e-9) {
    return limit;
  }
  const double rpm = std::fabs(surface_m_min) * 1000.0 / (2.0 * std::numbers::pi * r);
  return limit > 0.0 ? std::min(rpm, limit) : rpm;
}

}  // namespace mcnc::motion
