#include "channel/interp/path/plane_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::interp::path {

double length(Point2 p) {
  return std::hypot(p.a, p.b);
}

Point2 unit(Point2 p) {
  const double n = length(p);
  return n > 0.0 ? Point2{p.a / n, p.b / n} : Point2{};
}

Point2 left_normal(Point2 dir) {
  return {-dir.b, dir.a};
}

bool same_point(Point2 p, Point2 q, double tolerance) {
  return length(p - q) <= tolerance;
}

double arc_radius(Point2 from, const PlaneMove& arc) {
  return length(from - arc.center);
}

double arc_sweep(Point2 from, const PlaneMove& arc) {
  const Point2 s = from - arc.center;
  const Point2 e = arc.to - arc.center;
  double sweep = std::atan2(cross(s, e), dot(s, e));  // (-pi, pi]
  if (arc.ccw) {
    if (sweep <= 1e-12) {
      sweep += 2.0 * kPi;
    }
  } else if (sweep >= -1e-12) {
    sweep -= 2.0 * kPi;
  }
  return sweep;
}

double move_length(Point2 from, const PlaneMove& m) {
  switch (m.kind) {
    case MoveKind::arc:
      return std::fabs(arc_sweep(from, m)) * arc_radius(from, m);
    case MoveKind::dwell:
      return 0.0;
    default:
      return length(m.to - from);
  }
}

Point2 start_direction(Point2 from, const PlaneMove& m) {
  if (m.kind != MoveKind::arc) {
    return unit(m.to - from);
  }
  const Point2 n = unit(from - m.center);
  return m.ccw ? left_normal(n) : -1.0 * left_normal(n);
}

Point2 end_direction(Point2 from, const PlaneMove& m) {
  if (m.kind != MoveKind::arc) {
    return unit(m.to - from);
  }
  (void)from;
  const Point2 n = unit(m.to - m.center);
  return m.ccw ? left_normal(n) : -1.0 * left_normal(n);
}

Point2 point_along(Point2 from, const PlaneMove& m, double distance) {
  const double total = move_length(from, m);
  if (total <= 0.0) {
    return from;
  }
  const double f = std::clamp(distance / total, 0.0, 1.0);
  if (m.kind != MoveKind::arc) {
    return from + f * (m.to - from);
  }
  const double angle = f * arc_sweep(from, m);
  const Point2 s = from - m.center;
  const double c = std::cos(angle);
  const double sn = std::sin(angle);
  return m.center + Point2{s.a * c - s.b * sn, s.a * sn + s.b * c};
}

bool within_arc(Point2 from, const PlaneMove& arc, Point2 p, double tolerance) {
  const double sweep = arc_sweep(from, arc);
  const Point2 s = from - arc.center;
  const Point2 q = p - arc.center;
  double angle = std::atan2(cross(s, q), dot(s, q));  // from the start, (-pi, pi]
  if (sweep > 0.0 && angle < 0.0) {
    angle += 2.0 * kPi;
  } else if (sweep < 0.0 && angle > 0.0) {
    angle -= 2.0 * kPi;
  }
  const double r = std::max(arc_radius(from, arc), kLengthEpsilon);
  const double slack = tolerance / r;
  if (sweep > 0.0) {
    return (angle >= -slack && angle <= sweep + slack) || angle >= 2.0 * kPi - slack;
  }
  return (angle <= slack && angle >= sweep - slack) || angle <= -2.0 * kPi + slack;
}

LineHits intersect_lines(Point2 p0, Point2 d0, Point2 p1, Point2 d1) {
  LineHits hits;
  const double den = cross(d0, d1);
  // Relative to the lengths: short direction vectors are as good as long ones.
  if (std::fabs(den) <= 1e-12 * length(d0) * length(d1)) {
    return hits;
  }
  hits.count = 1;
  hits.t[0] = cross(p1 - p0, d1) / den;
  return hits;
}

LineHits intersect_line_circle(Point2 p, Point2 d, Point2 center, double radius) {
  LineHits hits;
  const double aa = dot(d, d);
  if (aa <= 0.0) {
    return hits;
  }
  const Point2 f = p - center;
  const double bb = 2.0 * dot(f, d);
  const double cc = dot(f, f) - radius * radius;
  double disc = bb * bb - 4.0 * aa * cc;
  // A tangent line computed in floating point may miss the circle by a rounding error, which
  // scales with every term of the discriminant (bb is 0 when p is the tangent point itself).
  const double slack = 1e-12 * (bb * bb + 4.0 * aa * (dot(f, f) + radius * radius));
  if (disc < -slack) {
    return hits;
  }
  disc = std::max(disc, 0.0);
  const double root = std::sqrt(disc);
  if (root == 0.0) {
    hits.count = 1;
    hits.t[0] = -bb / (2.0 * aa);
    return hits;
  }
  hits.count = 2;
  hits.t[0] = (-bb - root) / (2.0 * aa);
  hits.t[1] = (-bb + root) / (2.0 * aa);
  return hits;
}

PointHits intersect_circles(Point2 c0, double r0, Point2 c1, double r1) {
  PointHits hits;
  const Point2 d = c1 - c0;
  const double dist = length(d);
  if (dist <= kLengthEpsilon) {
    return hits;  // concentric: none or infinitely many
  }
  const double along = (r0 * r0 - r1 * r1 + dist * dist) / (2.0 * dist);
  double h2 = r0 * r0 - along * along;
  const double slack = 1e-9 * std::max(1.0, r0 * r0);
  if (h2 < -slack) {
    return hits;
  }
  h2 = std::max(h2, 0.0);
  const Point2 u = (1.0 / dist) * d;
  const Point2 mid = c0 + along * u;
  const double h = std::sqrt(h2);
  if (h == 0.0) {
    hits.count = 1;
    hits.p[0] = mid;
    return hits;
  }
  hits.count = 2;
  hits.p[0] = mid + h * left_normal(u);
  hits.p[1] = mid - h * left_normal(u);
  return hits;
}

std::optional<ThreePointArc> arc_through(Point2 start, Point2 middle, Point2 end) {
  const Point2 u = middle - start;
  const Point2 v = end - start;
  const double turn = cross(u, v);
  // Collinear within a relative 1e-12 of the chords' lengths (as intersect_lines decides).
  if (std::fabs(turn) <= 1e-12 * std::max(1.0, length(u) * length(v))) {
    return std::nullopt;
  }
  // The circumcentre relative to `start`: equidistant from 0, u and v.
  const double uu = dot(u, u);
  const double vv = dot(v, v);
  const Point2 rel{(v.b * uu - u.b * vv) / (2.0 * turn), (u.a * vv - v.a * uu) / (2.0 * turn)};
  return ThreePointArc{start + rel, turn > 0.0};
}

PointHits intersect(const LineOrCircle& e1, const LineOrCircle& e2) {
  if (e1.circle && e2.circle) {
    return intersect_circles(e1.point, e1.radius, e2.point, e2.radius);
  }
  PointHits hits;
  if (!e1.circle && !e2.circle) {
    const LineHits h = intersect_lines(e1.point, e1.direction, e2.point, e2.direction);
    hits.count = h.count;
    hits.p[0] = e1.point + h.t[0] * e1.direction;
    return hits;
  }
  const LineOrCircle& line = e1.circle ? e2 : e1;
  const LineOrCircle& circle = e1.circle ? e1 : e2;
  const LineHits h = intersect_line_circle(line.point, line.direction, circle.point, circle.radius);
  hits.count = h.count;
  for (int i = 0; i < h.count; ++i) {
    hits.p[static_cast<std::size_t>(i)] =
        line.point + h.t[static_cast<std::size_t>(i)] * line.direction;
  }
  return hits;
}

}  // namespace mcnc::interp::path
