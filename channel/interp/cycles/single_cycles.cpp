#include "channel/interp/cycles/single_cycles.hpp"

#include "channel/interp/program_alarms.hpp"

#include <cmath>
#include <cstdio>

namespace mcnc::interp::cycles {

namespace {

using path::MoveKind;
using path::PlaneMove;
using path::Point2;

PlaneMove move(MoveKind kind, Point2 to, double feed = 0.0) {
  PlaneMove m;
  m.kind = kind;
  m.to = to;
  m.feed = feed;
  return m;
}

path::PathError error(int alarm, const char* format, double value) {
  char text[160];
  std::snprintf(text, sizeof text, format, value);
  return path::PathError{alarm, text, -1};
}

}  // namespace

path::PathResult expand_single_cycle(Point2 start, const SingleCycle& c, path::PlanePath& out) {
  if (c.kind == SingleCycleKind::facing) {
    const Point2 cut_start{c.end.a + c.taper, start.b};
    out.push_back(move(MoveKind::rapid, cut_start));
    out.push_back(move(MoveKind::feed, c.end, c.feed));
    out.push_back(move(MoveKind::feed, {start.a, c.end.b}, c.feed));
    out.push_back(move(MoveKind::rapid, start));
    return std::nullopt;
  }
  const Point2 cut_start{start.a, c.end.b + c.taper};
  if (c.kind == SingleCycleKind::turning) {
    out.push_back(move(MoveKind::rapid, cut_start));
    out.push_back(move(MoveKind::feed, c.end, c.feed));
    out.push_back(move(MoveKind::feed, {c.end.a, start.b}, c.feed));
    out.push_back(move(MoveKind::rapid, start));
    return std::nullopt;
  }

  if (c.starts < 1) {
    return error(alarm::kCycleValue, "G92 needs at least one start (L%.0f)", c.starts);
  }
  if (c.lead <= 0.0) {
    return error(alarm::kThreadLead, "thread lead F%.4f must be greater than 0", c.lead);
  }
  const double length = std::fabs(c.end.a - cut_start.a);
  // With a lead change K the lead after s millimetres is sqrt(F^2 + 2 K s).
  if (c.lead * c.lead + 2.0 * c.lead_change * length <= 0.0) {
    return error(alarm::kThreadLead, "the lead change K%.4f brings the lead to 0 within the thread",
                 c.lead_change);
  }
  if (c.chamfer_a < 0.0 || c.chamfer_a > length) {
    return error(alarm::kCycleValue, "thread chamfer %.4f longer than the thread", c.chamfer_a);
  }
  const double along = c.end.a >= cut_start.a ? 1.0 : -1.0;
  const double outward = start.b >= c.end.b ? 1.0 : -1.0;
  // The thread's b on the taper line where the chamfer begins.
  const double f = length > 0.0 ? (length - c.chamfer_a) / length : 1.0;
  const Point2 chamfer_start{c.end.a - along * c.chamfer_a,
                             cut_start.b + f * (c.end.b - cut_start.b)};
  const Point2 thread_end{c.end.a, c.end.b + outward * c.chamfer_b};
  const bool chamfer = c.chamfer_a > 0.0 || c.chamfer_b > 0.0;
  for (int s = 0; s < c.starts; ++s) {
    const double angle = std::fmod(c.start_angle + 360.0 * s / c.starts, 360.0);
    out.push_back(move(MoveKind::rapid, cut_start));
    PlaneMove t = move(MoveKind::thread, chamfer ? chamfer_start : c.end);
    t.lead = c.lead;
    t.lead_change = c.lead_change;
    t.start_angle = angle;
    out.push_back(t);
    if (chamfer) {
      PlaneMove rise = t;
      rise.to = thread_end;
      // The chamfer continues the thread: its lead is the one reached at the chamfer start.
      rise.lead = std::sqrt(c.lead * c.lead +
                            2.0 * c.lead_change * std::fabs(chamfer_start.a - cut_start.a));
      rise.start_angle = 0.0;
      out.push_back(rise);
    }
    out.push_back(move(MoveKind::rapid, {thread_end.a, start.b}));
    out.push_back(move(MoveKind::rapid, start));
  }
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
