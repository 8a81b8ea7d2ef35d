#include "channel/interp/limits/stroke_zone.hpp"

#include "channel/interp/path/plane_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::interp::limits {

namespace {

// Whether the straight segment a-b passes through the open box of the limits (slab clipping):
// the part of the segment inside every axis's open interval is not empty.
bool segment_crosses_box(const StrokeZone& zone, const AxisVector& a, const AxisVector& b,
                         std::size_t axes) {
  double t0 = 0.0;
  double t1 = 1.0;
  for (std::size_t i = 0; i < axes; ++i) {
    const double lo = zone.minus[i] + kBoundaryTolerance;
    const double hi = zone.plus[i] - kBoundaryTolerance;
    const double d = b[i] - a[i];
    if (std::fabs(d) < 1e-15) {
      if (a[i] <= lo || a[i] >= hi) {
        return false;
      }
      continue;
    }
    double ta = (lo - a[i]) / d;
    double tb = (hi - a[i]) / d;
    if (ta > tb) {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 >= t1) {
      return false;
    }
  }
  return true;
}

bool segment_enters(const StrokeZone& zone, const AxisVector& a, const AxisVector& b,
                    std::size_t axes) {
  if (zone.inside_forbidden) {
    return segment_crosses_box(zone, a, b, axes);
  }
  // The allowed box is convex: a segment stays in it when both its ends do.
  return forbidden(zone, a, axes) || forbidden(zone, b, axes);
}

}  // namespace

bool StrokeZone::unlimited() const {
  for (std::size_t i = 0; i < kMaxChannelAxes; ++i) {
    if (std::isfinite(minus[i]) || std::isfinite(plus[i])) {
      return false;
    }
  }
  return true;
}

bool forbidden(const StrokeZone& zone, const AxisVector& p, std::size_t axes) {
  if (zone.unlimited()) {
    return false;
  }
  bool inside = true;
  bool outside = false;
  for (std::size_t i = 0; i < axes; ++i) {
    inside = inside && p[i] > zone.minus[i] + kBoundaryTolerance &&
             p[i] < zone.plus[i] - kBoundaryTolerance;
    outside = outside || p[i] < zone.minus[i] - kBoundaryTolerance ||
              p[i] > zone.plus[i] + kBoundaryTolerance;
  }
  return zone.inside_forbidden ? inside : outside;
}

bool enters(const StrokeZone& zone, const AxisVector& from, const Command& c, std::size_t axes) {
  if (zone.unlimited()) {
    return false;
  }
  const bool arc = c.op == Op::arc || (c.op == Op::thread && c.thread_arc);
  if (!arc) {
    return segment_enters(zone, from, c.to, axes);
  }
  const auto ia = static_cast<std::size_t>(c.center_axes[0]);
  const auto ib = static_cast<std::size_t>(c.center_axes[1]);
  path::PlaneMove move;
  move.kind = path::MoveKind::arc;
  move.to = {c.to[ia], c.to[ib]};
  move.center = {c.center[0], c.center[1]};
  move.ccw = c.direction == ArcDirection::ccw;
  const path::Point2 start{from[ia], from[ib]};
  const double radius = path::arc_radius(start, move);
  double sweep = path::arc_sweep(start, move);
  sweep += (sweep < 0.0 ? -1.0 : 1.0) * 2.0 * path::kPi * c.turns;
  // The chord's sagitta r (1 - cos(step / 2)) stays within the tolerance.
  const double step =
      radius > kChordTolerance ? 2.0 * std::acos(1.0 - kChordTolerance / radius) : path::kPi / 2.0;
  const int chords = std::max(1, static_cast<int>(std::ceil(std::fabs(sweep) / step)));
  const double a0 = std::atan2(start.b - move.center.b, start.a - move.center.a);
  AxisVector at = from;
  for (int k = 1; k <= chords; ++k) {
    const double f = static_cast<double>(k) / chords;
    AxisVector next = from;
    for (std::size_t i = 0; i < axes; ++i) {
      next[i] = from[i] + f * (c.to[i] - from[i]);  // the axes beside the plane: helical
    }
    if (k == chords) {
      next[ia] = c.to[ia];
      next[ib] = c.to[ib];
    } else {
      const double t = a0 + f * sweep;
      next[ia] = move.center.a + radius * std::cos(t);
      next[ib] = move.center.b + radius * std::sin(t);
    }
    if (segment_enters(zone, at, next, axes)) {
      return true;
    }
    at = next;
  }
  return false;
}

}  // namespace mcnc::interp::limits
