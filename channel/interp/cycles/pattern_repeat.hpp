#pragma once
// G73, the pattern-repeating (closed-loop) cycle of spec dafeng §2.5 L1664-1708 and gsk A.6.30:
// `passes` copies of the finishing contour, the first moved away by the total relief plus the
// allowance, each next one closer, the last one on the contour plus the allowance; a rapid back
// to the start point between passes and at the end.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::cycles {

struct PatternParams {
  // U(i)/2 and W(k): total relief in b and a (signed, physical), the offset of the first pass.
  double relief_a = 0.0;
  double relief_b = 0.0;
  int passes = 1;  // R(d), >= 1
  double allowance_a = 0.0;  // W(w)
  double allowance_b = 0.0;  // U(u)/2
  double feed = 0.0;
  int max_elements = 100;
};

// Pass k (1..passes) is the contour moved by allowance + relief * (passes - k) / (passes - 1)
// (a single pass: allowance only). `start`, `contour`, `out` and the alarms as
// expand_rough_turning (rough_turning.hpp); 1143 for passes < 1.
path::PathResult expand_pattern_repeat(path::Point2 start, const path::PlanePath& contour,
                                       const PatternParams& params, path::PlanePath& out);

}  // namespace mcnc::interp::cycles
