#include "channel/interp/transform/polar_interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::interp::transform {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

double distance(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

// The signed sweep of an arc from its start to its end angle about the centre, with its turns.
double sweep(const PlanePiece& p) {
  const double a0 = std::atan2(p.from[1] - p.centre[1], p.from[0] - p.centre[0]);
  const double a1 = std::atan2(p.to[1] - p.centre[1], p.to[0] - p.centre[0]);
  double s = a1 - a0;
  const double full = 2.0 * std::numbers::pi;
  if (p.ccw) {
    while (s <= 1e-12) {
      s += full;
    }
  } else {
    while (s >= -1e-12) {
      s -= full;
    }
  }
  return s + (p.ccw ? 1.0 : -1.0) * full * p.turns;
}

}  // namespace

std::array<double, 2> PlanePiece::at(double fraction) const {
  if (fraction >= 1.0) {
    return to;
  }
  if (!arc) {
    return {from[0] + fraction * (to[0] - from[0]), from[1] + fraction * (to[1] - from[1])};
  }
  // The radius goes linearly from the start's to the end's (an end a little off the circle).
  const double r0 = distance(from, centre);
  const double r1 = distance(to, centre);
  const double a0 = std::atan2(from[1] - centre[1], from[0] - centre[0]);
  const double a = a0 + fraction * sweep(*this);
  const double r = r0 + fraction * (r1 - r0);
  return {centre[0] + r * std::cos(a), centre[1] + r * std::sin(a)};
}

double PlanePiece::length() const {
  if (!arc) {
    return distance(from, to);
  }
  const double r = 0.5 * (distance(from, centre) + distance(to, centre));
  return std::fabs(sweep(*this)) * r;
}

PolarPoint PolarInterpolation::to_machine(const std::array<double, 2>& p,
                                          double near_degrees) const {
  PolarPoint m;
  m.radius = std::hypot(p[0], p[1]);
  double a = zero_degrees_ + std::atan2(p[1], p[0]) * kDegrees;
  a += 360.0 * std::round((near_degrees - a) / 360.0);
  m.degrees = m.radius > 0.0 ? a : near_degrees;  // at the centre every angle is the point
  return m;
}

std::array<double, 2> PolarInterpolation::to_plane(const PolarPoint& m) const {
  const double a = (m.degrees - zero_degrees_) / kDegrees;
  return {m.radius * std::cos(a), m.radius * std::sin(a)};
}

bool PolarInterpolation::steps(const PlanePiece& piece, double from_degrees, double tolerance,
                               std::vector<PolarStep>& out, std::size_t max_steps) const {
  // Step by step from the start, each end's turn taken nearest the step's start: a step that
  // does not keep the tip on the piece is halved, the next one tries twice the last length.
  const double total = piece.length();
  const double check = 0.5 * tolerance;
  auto fits = [&](double f0, double f1, const PolarPoint& m0, const PolarPoint& m1) {
    for (const double q : {0.25, 0.5, 0.75}) {
      const PolarPoint between{m0.radius + q * (m1.radius - m0.radius),
                               m0.degrees + q * (m1.degrees - m0.degrees)};
      if (distance(to_plane(between), piece.at(f0 + q * (f1 - f0))) > check) {
        return false;
      }
    }
    return true;
  };
  double f0 = 0.0;
  PolarPoint m0{std::hypot(piece.from[0], piece.from[1]), from_degrees};
  double length = 1.0;
  std::size_t made = 0;
  while (f0 < 1.0) {
    double f1 = std::min(1.0, f0 + length);
    PolarPoint m1 = to_machine(piece.at(f1), m0.degrees);
    while (f1 - f0 > 1e-12 && !fits(f0, f1, m0, m1)) {
      f1 = f0 + 0.5 * (f1 - f0);
      m1 = to_machine(piece.at(f1), m0.degrees);
    }
    if (++made > max_steps) {
      return false;
    }
    out.push_back(PolarStep{m1, (f1 - f0) * total});
    length = 2.0 * (f1 - f0);
    f0 = f1;
    m0 = m1;
  }
  return true;
}

}  // namespace mcnc::interp::transform
