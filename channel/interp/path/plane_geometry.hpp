#pragma once
// Plane geometry of lines and arcs that the cycles, corner insertion and tool-nose compensation
// share (plane_path.hpp for the coordinates). Pure functions; angles in radians.
#include "channel/interp/path/plane_path.hpp"

#include <array>
#include <optional>

namespace mcnc::interp::path {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kLengthEpsilon = 1e-9;  // mm: points closer than this are one point

double length(Point2 p);
Point2 unit(Point2 p);           // p / |p|; (0, 0) stays (0, 0)
Point2 left_normal(Point2 dir);  // dir turned 90 degrees counter-clockwise
bool same_point(Point2 p, Point2 q, double tolerance = kLengthEpsilon);

// Radius of an arc move that starts at `from`.
double arc_radius(Point2 from, const PlaneMove& arc);
// Signed sweep of an arc move from `from`: > 0 counter-clockwise, in (0, 2 pi] for G03 and
// [-2 pi, 0) for G02. Start = end is a full circle.
double arc_sweep(Point2 from, const PlaneMove& arc);
// Length travelled by a move from `from` (0 for a dwell).
double move_length(Point2 from, const PlaneMove& m);
// Unit direction of travel where the move starts / ends.
Point2 start_direction(Point2 from, const PlaneMove& m);
Point2 end_direction(Point2 from, const PlaneMove& m);
// The point at `distance` along the move (clamped to [0, length]).
Point2 point_along(Point2 from, const PlaneMove& m, double distance);
// Whether `p` (on the arc's circle) lies within the arc's sweep from `from`, ends included.
bool within_arc(Point2 from, const PlaneMove& arc, Point2 p, double tolerance = 1e-9);

// Intersections. Line: point + t * direction (t any real). Results are parameters on the first
// line (lines) or points (circles); the count says how many entries are valid.
struct LineHits {
  int count = 0;
  std::array<double, 2> t{};
};
struct PointHits {
  int count = 0;
  std::array<Point2, 2> p{};
};
// Parallel lines (|cross| below 1e-12 of their lengths) have no hit.
LineHits intersect_lines(Point2 p0, Point2 d0, Point2 p1, Point2 d1);
// A straight line through `point` along `direction`, or a circle about `point` of `radius`: the
// offset elements that corners and compensation intersect.
struct LineOrCircle {
  bool circle = false;
  Point2 point;
  Point2 direction;
  double radius = 0.0;
};
PointHits intersect(const LineOrCircle& e1, const LineOrCircle& e2);
LineHits intersect_line_circle(Point2 p, Point2 d, Point2 center, double radius);
PointHits intersect_circles(Point2 c0, double r0, Point2 c1, double r1);

// The arc from `start` through `middle` to `end` (G05, gsk A.6.4): its centre and sense. None
// when the three points are collinear (two of them the same point included): no circle, or a
// circle of no use, passes through them.
struct ThreePointArc {
  Point2 center;
  bool ccw = false;
};
std::optional<ThreePointArc> arc_through(Point2 start, Point2 middle, Point2 end);

}  // namespace mcnc::interp::path
