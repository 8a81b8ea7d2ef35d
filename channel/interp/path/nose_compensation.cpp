#include "channel/interp/path/nose_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

namespace mcnc::interp::path {

namespace {

// The offset copy of one programmed line or arc, untrimmed: the path of the nose centre while
// the nose touches that element. Measures along it are in mm.
struct OffsetElement {
  bool arc = false;
  Point2 start;
  Point2 end;
  Point2 dir;  // line: unit direction of travel
  Point2 center;
  double radius = 0.0;  // arc: the offset radius
  bool ccw = false;
  double sweep = 0.0;   // arc: |sweep| in radians
  double length = 0.0;  // line length or arc length
};

bool is_arc(const PlaneMove& m) {
  return m.kind == MoveKind::arc;
}

// Signed length that moves the nose to the compensation side: + left of travel (G41).
double side_sign(CompensationSide side) {
  return side == CompensationSide::left ? 1.0 : -1.0;
}

// `shift` = side sign * nose radius. False when an arc's offset radius would be <= 0.
bool make_offset(Point2 from, const PlaneMove& m, double shift, OffsetElement& el) {
  el.arc = is_arc(m);
  if (!el.arc) {
    el.dir = unit(m.to - from);
    const Point2 v = shift * left_normal(el.dir);
    el.start = from + v;
    el.end = m.to + v;
    el.length = length(m.to - from);
    return true;
  }
  // Left of travel is towards the centre on a G03 arc and away from it on a G02 arc.
  el.center = m.center;
  el.ccw = m.ccw;
  el.radius = arc_radius(from, m) + (m.ccw ? -shift : shift);
  if (el.radius <= kLengthEpsilon) {
    return false;
  }
  el.sweep = std::fabs(arc_sweep(from, m));
  el.start = m.center + el.radius * unit(from - m.center);
  el.end = m.center + el.radius * unit(m.to - m.center);
  el.length = el.sweep * el.radius;
  return true;
}

// Length along an offset element from `p` to `q` (both on it), in the direction of travel. On an
// arc the angle is taken in the window centred on the middle of the arc, so that points a
// little before the start or past the end come out negative or beyond the arc's length.
double travel(const OffsetElement& el, Point2 p, Point2 q) {
  if (!el.arc) {
    return dot(q - p, el.dir);
  }
  const Point2 u = p - el.center;
  const Point2 v = q - el.center;
  double angle = std::atan2(cross(u, v), dot(u, v));
  if (!el.ccw) {
    angle = -angle;
  }
  const double low = el.sweep / 2.0 - kPi;
  while (angle < low) {
    angle += 2.0 * kPi;
  }
  while (angle >= low + 2.0 * kPi) {
    angle -= 2.0 * kPi;
  }
  return angle * el.radius;
}

// Whether the turn from `from_vector` to `to_vector` (the offset vectors at a corner) goes away
// from the compensation side: the nose has to go round the corner.
bool is_outside_turn(Point2 from_vector, Point2 to_vector, CompensationSide side) {
  const double c = cross(from_vector, to_vector);
  const double scale = length(from_vector) * length(to_vector);
  if (std::fabs(c) <= 1e-12 * scale) {
    return dot(from_vector, to_vector) < 0.0;  // a reversal goes round the end point
  }
  return side == CompensationSide::left ? c < 0.0 : c > 0.0;
}

PointHits intersect(const OffsetElement& e1, const OffsetElement& e2) {
  return path::intersect(LineOrCircle{e1.arc, e1.arc ? e1.center : e1.start, e1.dir, e1.radius},
                         LineOrCircle{e2.arc, e2.arc ? e2.center : e2.start, e2.dir, e2.radius});
}

PathError geometry_error(const char* what, const PlaneMove& m, double radius) {
  char text[200];
  std::snprintf(text, sizeof text, "nose radius compensation: %s (nose radius %.3f, at %.3f %.3f)",
                what, radius, m.to.a, m.to.b);
  return PathError{alarm::kCompensationGeometry, text, m.source};
}

}  // namespace

Point2 tip_offset(int tip, double radius) {
  // Unit directions of tips 0-9 (a, b); 0 and 9 are the centre.
  static constexpr double kTip[10][2] = {{0, 0}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1},
                                         {1, 0}, {0, 1}, {-1, 0}, {0, -1},  {0, 0}};
  if (tip < 0 || tip > 9) {
    return {};
  }
  return {kTip[tip][0] * radius, kTip[tip][1] * radius};
}

void NoseCompensation::start(Point2 position, CompensationSide side, double radius, int tip) {
  if (radius < 0.0) {  // a negative radius swaps the sides, as FANUC does
    side = side == CompensationSide::left ? CompensationSide::right : CompensationSide::left;
    radius = -radius;
  }
  active_ = true;
  holding_ = false;
  started_ = false;
  side_ = side;
  radius_ = radius;
  tip_ = tip;
  programmed_at_ = position;
  offset_at_ = position - tip_offset(tip, radius);
  held_start_trim_ = 0.0;
  last_source_ = -1;
}

void NoseCompensation::emit(const PlaneMove& programmed, Point2 nose_to, Point2 nose_center,
                            PlanePath& out) const {
  const Point2 tip = tip_offset(tip_, radius_);
  PlaneMove m = programmed;
  m.to = nose_to + tip;
  if (is_arc(m)) {
    m.center = nose_center + tip;
  }
  out.push_back(m);
}

void NoseCompensation::emit_held(Point2 nose_to, double end_trim, PlanePath& out) const {
  OffsetElement el;
  make_offset(held_from_, held_, side_sign(side_) * radius_, el);
  // A line trimmed to nothing is left out; an arc must be, as start = end means a full circle.
  if (el.length - held_start_trim_ - end_trim > kLengthEpsilon) {
    emit(held_, nose_to, el.center, out);
  }
}

void NoseCompensation::emit_corner_arc(Point2 corner, Point2 nose_to, double feed, PlanePath& out) {
  PlaneMove arc;
  arc.kind = MoveKind::arc;
  arc.ccw = side_ == CompensationSide::right;  // G42 goes round left turns
  arc.feed = feed;
  arc.source = last_source_;
  emit(arc, nose_to, corner, out);
}

PathResult NoseCompensation::push(const PlaneMove& programmed, PlanePath& out) {
  if (!active_) {
    out.push_back(programmed);
    return std::nullopt;
  }
  if (programmed.kind == MoveKind::dwell) {
    // A dwell ends the look-ahead: the tool dwells at the offset end of the held move.
    flush(out);
    emit(programmed, offset_at_, {}, out);
    return std::nullopt;
  }
  const bool arc = is_arc(programmed);
  if (!started_ && !holding_ && arc) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "nose radius compensation cannot start on an arc (G%02d to %.3f %.3f)",
                  programmed.ccw ? 3 : 2, programmed.to.a, programmed.to.b);
    return PathError{alarm::kCompensationStart, text, programmed.source};
  }
  // Axis words without travel do not count as a move (dafeng §2.8 L986-988).
  const bool no_travel = arc ? arc_radius(programmed_at_, programmed) <= kLengthEpsilon
                             : same_point(programmed.to, programmed_at_);
  if (no_travel) {
    return std::nullopt;
  }
  if (radius_ <= 0.0) {
    out.push_back(programmed);
    started_ = true;
    programmed_at_ = programmed.to;
    offset_at_ = programmed.to;
    return std::nullopt;
  }
  if (!started_ && !holding_) {
    hold(programmed);
    return std::nullopt;
  }
  OffsetElement next;
  if (!make_offset(programmed_at_, programmed, side_sign(side_) * radius_, next)) {
    char what[120];
    std::snprintf(what, sizeof what, "arc radius %.3f is not larger than the nose on its inside",
                  arc_radius(programmed_at_, programmed));
    return geometry_error(what, programmed, radius_);
  }
  double next_start_trim = 0.0;
  if (holding_ && !started_) {
    // Start-up (FANUC type A): straight to the offset start of the first element.
    emit(held_, next.start, {}, out);
    offset_at_ = next.start;
    started_ = true;
  } else if (holding_) {
    if (PathResult error = join_corner(programmed, out, next_start_trim)) {
      return error;
    }
  } else {
    join_after_flush(programmed, out);
  }
  hold(programmed);
  held_start_trim_ = next_start_trim;
  return std::nullopt;
}

void NoseCompensation::hold(const PlaneMove& programmed) {
  held_ = programmed;
  held_from_ = programmed_at_;
  held_start_trim_ = 0.0;
  programmed_at_ = programmed.to;
  holding_ = true;
}

PathResult NoseCompensation::join_corner(const PlaneMove& programmed, PlanePath& out,
                                         double& next_start_trim) {
  OffsetElement held;
  OffsetElement next;
  make_offset(held_from_, held_, side_sign(side_) * radius_, held);
  make_offset(programmed_at_, programmed, side_sign(side_) * radius_, next);
  const Point2 corner = held_.to;
  last_source_ = held_.source;
  next_start_trim = 0.0;
  if (same_point(held.end, next.start)) {  // tangent: the offset elements meet end to start
    emit_held(held.end, 0.0, out);
    offset_at_ = held.end;
    return std::nullopt;
  }
  if (is_outside_turn(held.end - corner, next.start - corner, side_)) {
    emit_held(held.end, 0.0, out);
    emit_corner_arc(corner, next.start, programmed.feed, out);
    offset_at_ = next.start;
    return std::nullopt;
  }
  // Inside corner: both elements end at their intersection. It must lie on the held element
  // after the point where that one starts and on the next one before its offset end, or the
  // path would go backwards (FANUC "interference"). Of two valid points the one nearer the
  // corner along both elements is taken.
  const PointHits hits = intersect(held, next);
  const double available = held.length - held_start_trim_;
  int best = -1;
  double best_trim = 0.0;
  bool held_too_short = false;
  for (int i = 0; i < hits.count; ++i) {
    const double back = travel(held, hits.p[i], held.end);
    const double ahead = travel(next, next.start, hits.p[i]);
    if (back < -kLengthEpsilon || ahead < -kLengthEpsilon) {
      continue;  // the intersection of the extensions, away from the corner
    }
    if (back > available + kLengthEpsilon || ahead > next.length + kLengthEpsilon) {
      held_too_short = held_too_short || back > available + kLengthEpsilon;
      continue;
    }
    if (best < 0 || back + ahead < best_trim) {
      best = i;
      best_trim = back + ahead;
    }
  }
  if (best < 0) {
    if (hits.count == 0) {
      return geometry_error("the offsets of the two moves at the inside corner do not meet", held_,
                            radius_);
    }
    return held_too_short
               ? geometry_error("the move before the inside corner is too short", held_, radius_)
               : geometry_error("the move after the inside corner is too short", programmed,
                                radius_);
  }
  const Point2 x = hits.p[best];
  emit_held(x, travel(held, x, held.end), out);
  offset_at_ = x;
  next_start_trim = std::max(0.0, travel(next, next.start, x));
  return std::nullopt;
}

void NoseCompensation::join_after_flush(const PlaneMove& programmed, PlanePath& out) {
  OffsetElement next;
  make_offset(programmed_at_, programmed, side_sign(side_) * radius_, next);
  if (same_point(offset_at_, next.start)) {
    return;
  }
  // The flushed point is the offset end of the previous move, at the nose radius from the
  // programmed corner: an outside corner is gone round as in a normal corner, an inside one
  // straight.
  const Point2 corner = programmed_at_;
  if (is_outside_turn(offset_at_ - corner, next.start - corner, side_)) {
    emit_corner_arc(corner, next.start, programmed.feed, out);
  } else {
    PlaneMove line;
    line.kind = programmed.kind == MoveKind::rapid ? MoveKind::rapid : MoveKind::feed;
    line.feed = programmed.feed;
    line.source = programmed.source;
    emit(line, next.start, {}, out);
  }
  offset_at_ = next.start;
}

void NoseCompensation::flush(PlanePath& out) {
  if (!active_ || !holding_) {
    return;
  }
  OffsetElement held;
  make_offset(held_from_, held_, side_sign(side_) * radius_, held);
  if (started_) {
    emit_held(held.end, 0.0, out);
  } else {
    emit(held_, held.end, {}, out);  // a start-up move with nothing after it
    started_ = true;
  }
  offset_at_ = held.end;
  last_source_ = held_.source;
  holding_ = false;
}

PathResult NoseCompensation::cancel(const PlaneMove* programmed, PlanePath& out) {
  if (programmed != nullptr && is_arc(*programmed)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "nose radius compensation cannot be cancelled on an arc (G%02d to %.3f %.3f)",
                  programmed->ccw ? 3 : 2, programmed->to.a, programmed->to.b);
    return PathError{alarm::kCompensationStart, text, programmed->source};
  }
  if (!active_) {
    if (programmed != nullptr) {
      out.push_back(*programmed);
    }
    return std::nullopt;
  }
  flush(out);
  if (programmed != nullptr) {
    if (programmed->kind == MoveKind::dwell) {
      emit(*programmed, offset_at_, {}, out);
    } else if (!same_point(offset_at_ + tip_offset(tip_, radius_), programmed->to)) {
      out.push_back(*programmed);  // from the offset point back to the programmed end point
      programmed_at_ = programmed->to;
    }
  }
  active_ = false;
  holding_ = false;
  started_ = false;
  return std::nullopt;
}

}  // namespace mcnc::interp::path
