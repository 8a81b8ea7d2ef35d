#include "channel/interp/transform/inclined_axis.hpp"

#include <cmath>
#include <numbers>

namespace mcnc::interp::transform {

AxisMap InclinedAxis::map() const {
  const double a = degrees * std::numbers::pi / 180.0;
  AxisMap m = AxisMap::Identity();
  m.linear()(inclined, inclined) = 1.0 / std::cos(a);
  m.linear()(orthogonal, inclined) = std::tan(a);
  return m;
}

}  // namespace mcnc::interp::transform
