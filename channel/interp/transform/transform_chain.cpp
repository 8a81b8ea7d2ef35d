#include "channel/interp/transform/transform_chain.hpp"

namespace mcnc::interp::transform {

TransformChain& TransformChain::then(const AxisMap& link) {
  forward_ = link * forward_;
  inverse_ = inverse_ * link.inverse(Eigen::Affine);
  identity_ = identity_ && link.matrix().isIdentity(0.0);
  return *this;
}

AxisPoint TransformChain::to_machine(const AxisPoint& program) const {
  return identity_ ? program : AxisPoint(forward_ * program);
}

AxisPoint TransformChain::to_program(const AxisPoint& machine) const {
  return identity_ ? machine : AxisPoint(inverse_ * machine);
}

AxisPoint TransformChain::direction_to_machine(const AxisPoint& v) const {
  return identity_ ? v : AxisPoint(forward_.linear() * v);
}

bool TransformChain::reverses(int a, int b) const {
  Eigen::Matrix2d block;
  block << forward_.linear()(a, a), forward_.linear()(a, b), forward_.linear()(b, a),
      forward_.linear()(b, b);
  return block.determinant() < 0.0;
}

}  // namespace mcnc::interp::transform
