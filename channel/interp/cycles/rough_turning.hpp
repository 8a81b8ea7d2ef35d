#pragma once
// G71 (stock removal along the plane's first axis: OD/ID turning) and G72 (along the second:
// facing) of spec dafeng §2.5 L1480-1663 and gsk A.6.30, expanded into the moves a control makes:
// roughing passes parallel to the cutting axis down to the finishing contour plus allowance, a
// retract after each pass, the semi-finishing pass along the contour offset by the allowance,
// and the return to the start point.
//
// In G18 a G71 pass cuts along a (Z) at a constant b (X radius) and steps in b; a G72 pass cuts
// along b at a constant a and steps in a. Everything is physical: X allowances and depths as
// radii, the caller halves diameter values.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::cycles {

enum class RoughingAxis : std::uint8_t {
  a,  // G71: passes along the first axis (Z), depth steps in the second (X)
  b,  // G72: passes along the second axis (X), depth steps in the first (Z)
};

struct RoughingParams {
  RoughingAxis axis = RoughingAxis::a;
  double depth = 0.0;    // U(d) of G71 / W(d) of G72: depth of one pass, > 0
  double retract = 0.0;  // R(e): lift off the stock after a pass, >= 0
  // U(u)/2 and W(w): finishing allowance in b and a, signed as the spec's quadrant table (the
  // roughing contour is the finishing contour moved by (allowance_a, allowance_b)).
  double allowance_a = 0.0;
  double allowance_b = 0.0;
  double feed = 0.0;  // of the roughing and semi-finishing passes
  // Type II (pockets): the first contour element moves both axes (gsk A.6.30 "type selection"),
  // the contour need be monotonic along the cutting axis only.
  bool type2 = false;
  bool retract_along_contour = false;  // J1 (dafeng): lift along the contour instead of 45 deg
  bool check_monotonic = false;        // K1 (gsk): also alarm a type I contour that is not
  int max_elements = 100;              // gsk A.6.30 rule 5
};

// `start` is the tool position at the cycle block (point A). `contour` is the finishing contour
// N(P)..N(Q) as the program would run it from A: its first move goes to B, its last ends at C
// (rapid, feed and arc moves; `source` = the element's index in the contour, which the caller
// maps back to its block). `out` receives every move of the cycle, ending at A with a rapid.
// Alarms (program_alarms.hpp): 1140 contour not monotonic, 1141 first element not G00/G01 or
// an arc, 1142 more than max_elements, 1143 depth/retract out of range, 1144 contour empty.
path::PathResult expand_rough_turning(path::Point2 start, const path::PlanePath& contour,
                                      const RoughingParams& params, path::PlanePath& out);

}  // namespace mcnc::interp::cycles
