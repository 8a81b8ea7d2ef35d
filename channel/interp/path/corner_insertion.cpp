#include "channel/interp/path/corner_insertion.hpp"

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

namespace mcnc::interp::path {
namespace {

// Directions closer than this (sine of the angle) meet without a corner.
constexpr double kSameDirection = 1e-9;

std::string mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

std::string size_word(CornerKind kind, double size) {
  switch (kind) {
    case CornerKind::chamfer_setback:
      return "chamfer " + mm(size);
    case CornerKind::chamfer_length:
      return "chamfer length " + mm(size);
    case CornerKind::round:
      return "corner radius " + mm(size);
  }
  return mm(size);
}

PathError does_not_fit(const PlaneMove& first, std::string text) {
  return PathError{alarm::kCornerDoesNotFit, std::move(text), first.source};
}

// One of the two moves seen from the virtual corner: distances are measured along the move
// away from the corner (backwards on the first move, forwards on the second).
struct Side {
  Point2 from;  // where the move starts
  const PlaneMove& move;
  bool ends_at_corner;  // the first move: the corner is its end; the second: its start

  Point2 corner() const { return ends_at_corner ? move.to : from; }
  bool is_arc() const { return move.kind == MoveKind::arc; }
  double length() const { return move_length(from, move); }
  double radius() const { return arc_radius(from, move); }
  // Unit direction of travel on the line (lines only).
  Point2 line_direction() const { return unit(move.to - from); }

  Point2 point_at(double distance) const {
    return ends_at_corner ? point_along(from, move, length() - distance)
                          : point_along(from, move, distance);
  }

  // Distance from the corner to `p` (a point on the move's line or circle) along the move;
  // negative or beyond length() when p is not on the move.
  double distance_to(Point2 p) const {
    const Point2 c = corner();
    if (!is_arc()) {
      const Point2 away = ends_at_corner ? -1.0 * line_direction() : line_direction();
      return dot(p - c, away);
    }
    if (same_point(p, c)) {
      return 0.0;
    }
    PlaneMove piece = move;  // the arc between the corner and p, in the direction of travel
    piece.to = ends_at_corner ? c : p;
    return move_length(ends_at_corner ? p : c, piece);
  }

  // Largest straight-line distance from the corner of a point of the move.
  double chord_limit() const {
    if (!is_arc()) {
      return length();
    }
    const double angle = std::min(std::fabs(arc_sweep(from, move)), kPi);
    return 2.0 * radius() * std::sin(0.5 * angle);
  }

  // The point at straight-line distance `chord` (<= chord_limit()) from the corner, the
  // nearest to the corner along the move.
  Point2 point_at_chord(double chord) const {
    if (!is_arc()) {
      return point_at(chord);
    }
    const double r = radius();
    const double angle = 2.0 * std::asin(std::min(1.0, chord / (2.0 * r)));
    return point_at(std::min(r * angle, length()));
  }
};

// Smallest equal setback from the corner at which the chamfer line has `chamfer_length`, or a
// negative value when even the largest setback that fits on both moves is too short.
double setback_for_length(const Side& first, const Side& second, double chamfer_length) {
  const double limit = std::min(first.chord_limit(), second.chord_limit());
  const auto chamfer = [&](double s) {
    return path::length(second.point_at_chord(s) - first.point_at_chord(s));
  };
  // On arcs the chamfer length need not grow monotonically with the setback: walk up in steps
  // to the first one that is long enough, then bisect.
  constexpr int kSteps = 256;
  double low = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    double high = limit * i / kSteps;
    if (chamfer(high) < chamfer_length) {
      low = high;
      continue;
    }
    for (int k = 0; k < 200 && high - low > 1e-15 * limit; ++k) {
      const double mid = 0.5 * (low + high);
      (chamfer(mid) >= chamfer_length ? high : low) = mid;
    }
    return high;
  }
  return -1.0;
}

// The line or circle on which the centres of the radius-`r` arcs touching the move from side
// `side` (+1 left of travel, -1 right) lie. A circle of radius 0 (the fillet is concentric with
// the arc) has none.
struct Offset {
  bool circle = false;
  Point2 point;      // line: a point; circle: the centre
  Point2 direction;  // line
  double radius = 0.0;
  double signed_radius = 0.0;  // circle: < 0 when the centres lie beyond the arc's centre
};

Offset offset_of(const Side& s, double side, double r) {
  Offset o;
  if (!s.is_arc()) {
    o.direction = s.line_direction();
    o.point = s.corner() + side * r * left_normal(o.direction);
    return o;
  }
  o.circle = true;
  o.point = s.move.center;
  // Left of travel is towards the centre on a G03 arc, away from it on a G02 arc.
  o.signed_radius = s.radius() - (s.move.ccw ? side : -side) * r;
  o.radius = std::fabs(o.signed_radius);
  return o;
}

// Where a fillet centred at `c` touches the move.
Point2 touch_point(const Side& s, const Offset& o, Point2 c) {
  if (!o.circle) {
    const Point2 base = s.corner();
    return base + dot(c - base, o.direction) * o.direction;
  }
  const double r = s.radius();
  return o.point + (o.signed_radius < 0.0 ? -r : r) * unit(c - o.point);
}

PointHits fillet_centres(const Offset& o1, const Offset& o2) {
  return intersect(LineOrCircle{o1.circle, o1.point, o1.direction, o1.radius},
                   LineOrCircle{o2.circle, o2.point, o2.direction, o2.radius});
}

struct Fillet {
  Point2 center;
  Point2 touch1;
  Point2 touch2;
};

// The fillet of radius r on the inside of the corner (side +1: the path turns left) whose
// touching points lie on both moves, the nearest to the corner; false when there is none.
bool find_fillet(const Side& first, const Side& second, double side, double r, Fillet& out) {
  const Offset o1 = offset_of(first, side, r);
  const Offset o2 = offset_of(second, side, r);
  if ((o1.circle && o1.radius <= kLengthEpsilon) || (o2.circle && o2.radius <= kLengthEpsilon)) {
    return false;
  }
  const PointHits centres = fillet_centres(o1, o2);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < centres.count; ++i) {
    const Point2 c = centres.p[i];
    const Point2 t1 = touch_point(first, o1, c);
    const Point2 t2 = touch_point(second, o2, c);
    const double d1 = first.distance_to(t1);
    const double d2 = second.distance_to(t2);
    const bool on_first = d1 >= -kLengthEpsilon && d1 <= first.length() + kLengthEpsilon;
    const bool on_second = d2 >= -kLengthEpsilon && d2 <= second.length() + kLengthEpsilon;
    if (on_first && on_second && d1 + d2 < best) {
      best = d1 + d2;
      out = {c, t1, t2};
    }
  }
  return best < std::numeric_limits<double>::infinity();
}

// An arc shortened to nothing would read as a full circle: it becomes a feed of length 0.
void flatten_if_empty(Point2 from, PlaneMove& m) {
  if (m.kind == MoveKind::arc && same_point(from, m.to)) {
    m.kind = MoveKind::feed;
  }
}

std::string between_the_moves(CornerKind kind, double size, const Side& first, const Side& second) {
  return size_word(kind, size) + " does not fit between the moves (" + mm(first.length()) +
         " and " + mm(second.length()) + " long)";
}

bool is_cut(const PlaneMove& m) {
  return m.kind == MoveKind::feed || m.kind == MoveKind::arc;
}

}  // namespace

PathResult insert_corner(Point2 start, PlaneMove& first, PlaneMove& second, CornerKind kind,
                         double size, double feed, CornerResult& result) {
  result = CornerResult{};
  if (!(size > 0.0)) {
    return does_not_fit(first, size_word(kind, size) + " is not greater than 0");
  }
  if (!is_cut(first) || !is_cut(second)) {
    return does_not_fit(first, size_word(kind, size) + " needs G01/G02/G03 moves on both sides");
  }
  const Point2 corner = first.to;
  const Side before{start, first, true};
  const Side after{corner, second, false};
  const Point2 d1 = end_direction(start, first);
  const Point2 d2 = start_direction(corner, second);
  if (before.length() <= kLengthEpsilon || after.length() <= kLengthEpsilon) {
    return does_not_fit(first, size_word(kind, size) + " next to a move of length 0");
  }
  const double turn = cross(d1, d2);
  if (std::fabs(turn) <= kSameDirection) {
    if (dot(d1, d2) > 0.0) {
      return std::nullopt;  // no corner (gsk A.6.10 special case 1)
    }
    return does_not_fit(first,
                        size_word(kind, size) + ": the second move turns back along the first");
  }

  if (kind == CornerKind::round) {
    Fillet f;
    if (!find_fillet(before, after, turn > 0.0 ? 1.0 : -1.0, size, f)) {
      return does_not_fit(first, between_the_moves(kind, size, before, after));
    }
    first.to = f.touch1;
    result.corner.kind = MoveKind::arc;
    result.corner.to = f.touch2;
    result.corner.center = f.center;
    result.corner.ccw = turn > 0.0;
  } else {
    double setback = size;
    if (kind == CornerKind::chamfer_length) {
      setback = setback_for_length(before, after, size);
      if (setback < 0.0) {
        return does_not_fit(first, between_the_moves(kind, size, before, after));
      }
    }
    const double fits1 = before.chord_limit();
    const double fits2 = after.chord_limit();
    if (setback > fits1 + kLengthEpsilon || setback > fits2 + kLengthEpsilon) {
      return does_not_fit(first, size_word(kind, size) + " does not fit: at most " + mm(fits1) +
                                     " on the first move and " + mm(fits2) + " on the second");
    }
    first.to = before.point_at_chord(setback);
    result.corner.kind = MoveKind::feed;
    result.corner.to = after.point_at_chord(setback);
  }
  flatten_if_empty(start, first);
  flatten_if_empty(result.corner.to, second);
  result.inserted = true;
  result.corner.feed = feed;
  result.corner.source = -1;
  return std::nullopt;
}

}  // namespace mcnc::interp::path
