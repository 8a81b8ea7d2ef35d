#include "channel/interp/cycles/peck_grooving.hpp"

#include "channel/interp/cycles/cycle_moves.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::interp::cycles {

namespace {

using path::mm_text;
using path::PathError;
using path::PathResult;
using path::PlanePath;
using path::Point2;

constexpr double kTolerance = 1e-9;  // mm
// Pecks of all grooves together: a bound against a peck of a few microns over a long stroke
// that would make millions of moves.
constexpr int kMaxPecks = 100000;

// The cycle's two axes: pecks along one, grooves stepped along the other.
struct GrooveAxes {
  PeckAxis peck_axis;

  double peck(Point2 p) const { return peck_axis == PeckAxis::a ? p.a : p.b; }
  double step(Point2 p) const { return peck_axis == PeckAxis::a ? p.b : p.a; }
  Point2 point(double peck, double step) const {
    return peck_axis == PeckAxis::a ? Point2{peck, step} : Point2{step, peck};
  }
};

// How many moves of at most `stride` cover `span`; the tolerance keeps 0.3 / 0.1 at 3.
double strides_over(double span, double stride) {
  if (span <= kTolerance) {
    return 0.0;
  }
  return stride > 0.0 ? std::ceil(span / stride - 1e-9) : 1.0;
}

// Appends `m` unless it would not move from the end of `out` (or from `start`).
void push_moving(Point2 start, const path::PlaneMove& m, PlanePath& out) {
  const Point2 from = out.empty() ? start : out.back().to;
  if (!path::same_point(from, m.to)) {
    out.push_back(m);
  }
}

PathResult check_amounts(const PeckGrooving& c, const char* code, double step_span) {
  const bool g74 = c.axis == PeckAxis::a;
  if (c.peck < 0.0 || c.step < 0.0 || c.relief < 0.0 || c.retract < 0.0) {
    return PathError{alarm::kCycleValue,
                     std::string(code) + " amounts must not be negative: peck " +
                         (g74 ? "Q" : "P") + mm_text(c.peck) + ", shift " + (g74 ? "P" : "Q") +
                         mm_text(c.step) + ", relief R" + mm_text(c.relief) + ", retract R" +
                         mm_text(c.retract),
                     -1};
  }
  if (step_span > kTolerance && c.step <= 0.0) {
    return PathError{alarm::kCycleWordMissing,
                     std::string(code) + (g74 ? " X/U" : " Z/W") + " moves the grooves by " +
                         mm_text(step_span) + " but the shift between grooves " +
                         (g74 ? "P" : "Q") + " is missing",
                     -1};
  }
  return std::nullopt;
}

}  // namespace

path::PathResult expand_peck_grooving(path::Point2 start, const PeckGrooving& cycle,
                                      path::PlanePath& out) {
  const char* code = cycle.axis == PeckAxis::a ? "G74" : "G75";
  const GrooveAxes axes{cycle.axis};
  const double peck_start = axes.peck(start);
  const double peck_end = axes.peck(cycle.end);
  const double depth = std::fabs(peck_end - peck_start);
  const double peck_dir = peck_end < peck_start ? -1.0 : 1.0;
  const double step_end = axes.step(cycle.end);
  const double step_span = std::fabs(step_end - axes.step(start));
  const double step_dir = step_end < axes.step(start) ? -1.0 : 1.0;
  if (PathResult e = check_amounts(cycle, code, step_span)) {
    return e;
  }
  const double grooves = strides_over(step_span, cycle.step) + 1.0;
  const double pecks = std::max(strides_over(depth, cycle.peck), 1.0);
  if (grooves * pecks > kMaxPecks) {
    const bool g74 = cycle.axis == PeckAxis::a;
    return PathError{alarm::kCycleValue,
                     std::string(code) + " needs more than " + std::to_string(kMaxPecks) +
                         " pecks: peck " + (g74 ? "Q" : "P") + mm_text(cycle.peck) + " over " +
                         mm_text(depth) + ", shift " + (g74 ? "P" : "Q") + mm_text(cycle.step) +
                         " over " + mm_text(step_span),
                     -1};
  }

  PlanePath path;
  const int groove_count = static_cast<int>(grooves);
  const int peck_count = static_cast<int>(pecks);
  for (int g = 0; g < groove_count; ++g) {
    // The last groove is at the end point, nearer than `step` to the one before when the
    // span is no multiple of it.
    const double at =
        g + 1 == groove_count ? step_end : axes.step(start) + step_dir * g * cycle.step;
    push_moving(start, rapid_to(axes.point(peck_start, at)), path);
    for (int p = 1; p <= peck_count; ++p) {
      const double reach = p == peck_count ? depth : p * cycle.peck;
      push_moving(start, feed_to(axes.point(peck_start + peck_dir * reach, at), cycle.feed), path);
      if (p < peck_count) {
        // Back off, but not beyond the level the groove starts from.
        const double back = reach - std::min(cycle.retract, reach);
        push_moving(start, rapid_to(axes.point(peck_start + peck_dir * back, at)), path);
      }
    }
    // Relief off the wall, away from the next groove; a single groove (or hole) has no side to
    // go to.
    const double leave = groove_count > 1 ? at - step_dir * cycle.relief : at;
    push_moving(start, rapid_to(axes.point(peck_end, leave)), path);
    push_moving(start, rapid_to(axes.point(peck_start, leave)), path);
  }
  push_moving(start, rapid_to(start), path);
  out.insert(out.end(), path.begin(), path.end());
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
