#pragma once
// The types every link of the coordinate chain is written in: a point with one coordinate per
// channel axis (in the channel's axis order, physical units: mm, degrees) and an affine map of
// such points. Axes a link does not name keep their coordinate exactly (identity rows).
#include "channel/interp/axis_vector.hpp"

#include <Eigen/Geometry>

namespace mcnc::interp::transform {

inline constexpr int kAxes = static_cast<int>(kMaxChannelAxes);
using AxisPoint = Eigen::Matrix<double, kAxes, 1>;
using AxisMap = Eigen::Transform<double, kAxes, Eigen::Affine>;

inline AxisPoint to_point(const AxisVector& v) {
  return Eigen::Map<const AxisPoint>(v.data());
}

inline AxisVector to_vector(const AxisPoint& p) {
  AxisVector v{};
  Eigen::Map<AxisPoint>(v.data()) = p;
  return v;
}

}  // namespace mcnc::interp::transform
