#pragma once
// A path in one plane: what the canned cycles (channel/interp/cycles/) produce and what corner
// insertion and tool-nose compensation (this folder) read and write.
//
// Coordinates are physical millimetres of the plane's two axes: `a` is the first axis and `b`
// the second (G18: a = Z, b = X as a radius; G17: a = X, b = Y; G19: a = Y, b = Z). Seen with a
// to the right and b up, G02 turns clockwise and G03 counter-clockwise in every plane.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::interp::path {

struct Point2 {
  double a = 0.0;
  double b = 0.0;
};

inline Point2 operator+(Point2 p, Point2 q) { return {p.a + q.a, p.b + q.b}; }
inline Point2 operator-(Point2 p, Point2 q) { return {p.a - q.a, p.b - q.b}; }
inline Point2 operator*(double k, Point2 p) { return {k * p.a, k * p.b}; }
inline double dot(Point2 p, Point2 q) { return p.a * q.a + p.b * q.b; }
// z of the 3-D cross product: > 0 when q turns counter-clockwise from p.
inline double cross(Point2 p, Point2 q) { return p.a * q.b - p.b * q.a; }

enum class MoveKind : std::uint8_t {
  rapid,   // positioning (G00)
  feed,    // straight cut (G01)
  arc,     // circular cut (G02/G03)
  thread,  // straight or taper thread (G32/G34): feed synchronised with the spindle
  dwell,   // no motion: `seconds` at `to` (which repeats the current point)
};

// One move of a path, from the end of the previous one (or the path's start point) to `to`.
struct PlaneMove {
  MoveKind kind = MoveKind::feed;
  Point2 to;
  Point2 center;     // arc
  bool ccw = false;  // arc: G03 when true, G02 when false
  double feed = 0.0;  // feed, arc: mm/min or mm/rev in the channel's feed mode; 0 = unchanged
  // thread: lead along the long axis (mm/rev), its change per revolution (G34, mm/rev/rev),
  // spindle angle at which the thread starts (degrees).
  double lead = 0.0;
  double lead_change = 0.0;
  double start_angle = 0.0;
  double seconds = 0.0;  // dwell
  // The program element the move comes from: the index of the contour element in a cycle's
  // contour, or -1 for a move the cycle or the corner insertion made.
  int source = -1;
};

using PlanePath = std::vector<PlaneMove>;

// Why a path cannot be made: an interpreter alarm number (channel/interp/program_alarms.hpp),
// the reason, and the contour element to blame (-1: the cycle block itself).
struct PathError {
  int alarm = 0;
  std::string text;
  int source = -1;
};

using PathResult = std::optional<PathError>;  // nullopt: the path was made

}  // namespace mcnc::interp::path
