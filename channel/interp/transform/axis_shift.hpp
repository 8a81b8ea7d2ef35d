#pragma once
// Link: a translation of every axis (work offsets, G50 shift, G52 local origin, tool offset).
// Promises: the linear part is the identity, so directions and arc senses are unchanged.
#include "channel/interp/transform/axis_point.hpp"

namespace mcnc::interp::transform {

struct AxisShift {
  AxisPoint offset = AxisPoint::Zero();  // out = in + offset

  AxisMap map() const {
    AxisMap m = AxisMap::Identity();
    m.translation() = offset;
    return m;
  }
};

}  // namespace mcnc::interp::transform
