#include "channel/interp/transform/plane_rotation.hpp"

#include <numbers>

namespace mcnc::interp::transform {

AxisMap PlaneRotation::map() const {
  const Eigen::Matrix2d turn =
      Eigen::Rotation2Dd(degrees * std::numbers::pi / 180.0).toRotationMatrix();
  const Eigen::Vector2d c(centre[0], centre[1]);
  const Eigen::Vector2d keep = c - turn * c;  // p -> turn (p - c) + c
  AxisMap m = AxisMap::Identity();
  for (int r = 0; r < 2; ++r) {
    const int row = axes[static_cast<std::size_t>(r)];
    for (int k = 0; k < 2; ++k) {
      m.linear()(row, axes[static_cast<std::size_t>(k)]) = turn(r, k);
    }
    m.translation()(row) = keep(r);
  }
  return m;
}

}  // namespace mcnc::interp::transform
