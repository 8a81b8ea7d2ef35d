#include "channel/interp/cycles/single_cycles.hpp"

#include "channel/interp/cycles/cycle_moves.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"

#include <cmath>

namespace mcnc::interp::cycles {

namespace {

using path::mm_text;
using path::MoveKind;
using path::PlaneMove;
using path::Point2;

path::PathError error(int alarm, const std::string& text) {
  return path::PathError{alarm, text, -1};
}

}  // namespace

path::PathResult expand_single_cycle(Point2 start, const SingleCycle& c, path::PlanePath& out) {
  if (c.kind == SingleCycleKind::facing) {
    const Point2 cut_start{c.end.a + c.taper, start.b};
    out.push_back(rapid_to(cut_start));
    out.push_back(feed_to(c.end, c.feed));
    out.push_back(feed_to({start.a, c.end.b}, c.feed));
    out.push_back(rapid_to(start));
    return std::nullopt;
  }
  const Point2 cut_start{start.a, c.end.b + c.taper};
  if (c.kind == SingleCycleKind::turning) {
    out.push_back(rapid_to(cut_start));
    out.push_back(feed_to(c.end, c.feed));
    out.push_back(feed_to({c.end.a, start.b}, c.feed));
    out.push_back(rapid_to(start));
    return std::nullopt;
  }

  if (c.starts < 1) {
    return error(alarm::kCycleValue,
                 "G92 needs at least one start (L" + std::to_string(c.starts) + ")");
  }
  if (c.lead <= 0.0) {
    return error(alarm::kThreadLead, "thread lead F" + mm_text(c.lead) + " must be greater than 0");
  }
  const double length = std::fabs(c.end.a - cut_start.a);
  // With a lead change K the lead after s millimetres is sqrt(F^2 + 2 K s).
  if (c.lead * c.lead + 2.0 * c.lead_change * length <= 0.0) {
    return error(alarm::kThreadLead, "the lead change K" + mm_text(c.lead_change) +
                                         " brings the lead to 0 within the thread");
  }
  if (c.chamfer_a < 0.0 || c.chamfer_a > length) {
    return error(alarm::kCycleValue,
                 "thread chamfer " + mm_text(c.chamfer_a) + " longer than the thread");
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
    out.push_back(rapid_to(cut_start));
    PlaneMove t;
    t.kind = MoveKind::thread;
    t.to = chamfer ? chamfer_start : c.end;
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
    out.push_back(rapid_to({thread_end.a, start.b}));
    out.push_back(rapid_to(start));
  }
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
