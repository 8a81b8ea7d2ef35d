#include "channel/interp/path/line_angle.hpp"

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace mcnc::interp::path {
namespace {

std::string three_decimals(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

Point2 direction_of(double degrees) {
  const double rad = normalized_degrees(degrees) * kPi / 180.0;
  return {std::cos(rad), std::sin(rad)};
}

// Angle between two lines of these directions, in [0, 90] degrees.
double degrees_between_lines(double first, double second) {
  const double d =
      std::fmod(std::fabs(normalized_degrees(first) - normalized_degrees(second)), 180.0);
  return std::fmin(d, 180.0 - d);
}

// A hair below the tolerance, so that exactly 1 degree apart (Q181000 against 180) is accepted.
bool nearly_parallel(double first, double second) {
  return degrees_between_lines(first, second) < kAngleToleranceDegrees - 1e-9;
}

PathError angle_alarm(std::string text) {
  return PathError{alarm::kAngleProgramming, std::move(text), -1};
}

}  // namespace

double normalized_degrees(double degrees) {
  const double d = std::fmod(degrees, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

PathResult line_end_from_angle(Point2 start, double degrees, KnownAxis known, double value,
                               Point2& end) {
  const bool b_known = known == KnownAxis::b;
  // The axis of the known coordinate: X (b) known is a line along a, Z (a) known one along b.
  const double axis_degrees = b_known ? 0.0 : 90.0;
  if (nearly_parallel(degrees, axis_degrees)) {
    return angle_alarm(std::string("a line at ") + three_decimals(degrees) +
                       " degrees runs within 1 degree of the " + (b_known ? "first" : "second") +
                       " axis: it has no end point at " + (b_known ? "second" : "first") +
                       "-axis coordinate " + three_decimals(value));
  }
  const Point2 dir = direction_of(degrees);
  const Point2 known_line = b_known ? Point2{0.0, value} : Point2{value, 0.0};
  const Point2 known_dir = b_known ? Point2{1.0, 0.0} : Point2{0.0, 1.0};
  // At least 1 degree apart: the lines meet.
  end = start + intersect_lines(start, dir, known_line, known_dir).t[0] * dir;
  // The known coordinate exactly as programmed, not as recomputed.
  (b_known ? end.b : end.a) = value;
  return std::nullopt;
}

PathResult angle_lines_corner(Point2 start, double first_degrees, Point2 second_end,
                              double second_degrees, Point2& corner) {
  if (nearly_parallel(first_degrees, second_degrees)) {
    return angle_alarm("lines at " + three_decimals(first_degrees) + " and " +
                       three_decimals(second_degrees) +
                       " degrees are less than 1 degree apart: no intersection");
  }
  const Point2 dir = direction_of(first_degrees);
  corner = start + intersect_lines(start, dir, second_end, direction_of(second_degrees)).t[0] * dir;
  return std::nullopt;
}

}  // namespace mcnc::interp::path
