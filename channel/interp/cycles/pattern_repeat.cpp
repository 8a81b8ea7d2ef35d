#include "channel/interp/cycles/pattern_repeat.hpp"

#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"

#include <string>

namespace mcnc::interp::cycles {

path::PathResult expand_pattern_repeat(path::Point2 start, const path::PlanePath& contour,
                                       const PatternParams& p, path::PlanePath& out) {
  if (contour.empty()) {
    return path::PathError{alarm::kContourMissing, "G73 contour has no move", -1};
  }
  if (static_cast<int>(contour.size()) > p.max_elements) {
    return path::PathError{alarm::kContourTooLong,
                           "G73 contour has " + std::to_string(contour.size()) +
                               " moves, more than " + std::to_string(p.max_elements),
                           -1};
  }
  if (p.passes < 1 || p.passes > 10000) {
    return path::PathError{alarm::kCycleValue,
                           "G73 R (passes) must be 1-10000, not " + std::to_string(p.passes), -1};
  }
  if (contour.front().kind == path::MoveKind::arc) {
    return path::PathError{alarm::kContourStart, "G73 contour must start with G00 or G01", 0};
  }
  for (int k = 1; k <= p.passes; ++k) {
    // Pass k lies relief * (passes - k) / (passes - 1) off the contour plus the allowance: the
    // first at the full relief, the last on the allowance (gsk A.6.30, FANUC).
    const double f =
        p.passes == 1 ? 0.0 : static_cast<double>(p.passes - k) / static_cast<double>(p.passes - 1);
    const path::Point2 shift{p.allowance_a + f * p.relief_a, p.allowance_b + f * p.relief_b};
    path::PlaneMove to_start;
    to_start.kind = path::MoveKind::rapid;
    to_start.to = start + shift;
    out.push_back(to_start);
    for (const path::PlaneMove& m : contour) {
      path::PlaneMove c = m;
      c.to = m.to + shift;
      c.center = m.center + shift;
      if (c.kind != path::MoveKind::rapid || &m != &contour.front()) {
        c.feed = p.feed;
        if (c.kind == path::MoveKind::rapid) {
          c.kind = path::MoveKind::feed;  // after the approach every element is cut
        }
      }
      out.push_back(c);
    }
  }
  path::PlaneMove back;
  back.kind = path::MoveKind::rapid;
  back.to = start;
  out.push_back(back);
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
