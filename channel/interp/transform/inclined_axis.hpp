#pragma once
// Link: inclined-axis control (spec dafeng §2.9, L4653-4767; params 5690 angle, 5691 inclined
// axis, 5692 orthogonal axis). The program works in Cartesian coordinates; the machine's
// inclined axis stands at `degrees` from the perpendicular to the orthogonal axis:
//   inclined (machine)   = inclined (Cartesian) / cos(degrees)
//   orthogonal (machine) = orthogonal (Cartesian) + inclined (Cartesian) * tan(degrees)
// both physical (a diameter axis as its radius: the spec's factor C = 0.5). Promises: an affine
// map, invertible for |degrees| < 90, the other axes kept exactly. It is not a rigid map: an arc
// of the program is not an arc of the machine.
#include "channel/interp/transform/axis_point.hpp"

namespace mcnc::interp::transform {

struct InclinedAxis {
  int inclined = 0;
  int orthogonal = 1;
  double degrees = 0.0;

  AxisMap map() const;
};

}  // namespace mcnc::interp::transform
