#pragma once
// Link: a rotation in the plane of two axes about a centre (G68.1, spec dafeng L4502-4652).
// `axes` are the plane's first and second axis (G18: Z then X); a positive angle turns the first
// axis towards the second, counter-clockwise as the plane is seen. Promises: the centre stays
// where it is, lengths in the plane are kept, the other axes are kept exactly.
#include "channel/interp/transform/axis_point.hpp"

#include <array>

namespace mcnc::interp::transform {

struct PlaneRotation {
  std::array<int, 2> axes{0, 1};
  std::array<double, 2> centre{};
  double degrees = 0.0;

  AxisMap map() const;
};

}  // namespace mcnc::interp::transform
