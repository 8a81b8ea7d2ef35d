#pragma once
// Link: programmed units to physical units, axis by axis (inch to mm, a diameter to its radius).
// Promises: a diagonal map; an axis with factor 1 keeps its coordinate exactly.
#include "channel/interp/transform/axis_point.hpp"

namespace mcnc::interp::transform {

struct UnitScale {
  AxisPoint factor = AxisPoint::Ones();  // physical = factor * programmed

  AxisMap map() const {
    AxisMap m = AxisMap::Identity();
    m.linear() = factor.asDiagonal();
    return m;
  }
};

}  // namespace mcnc::interp::transform
