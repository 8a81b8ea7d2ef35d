#pragma once
// The chain of coordinate transformations from program to machine coordinates: links applied in
// the order they are added (the first one to the programmed point). Promises: to_program undoes
// to_machine (within rounding, 1e-9 for coordinates below 1e6); an empty chain is the identity
// and changes no bit.
#include "channel/interp/transform/axis_point.hpp"

namespace mcnc::interp::transform {

class TransformChain {
 public:
  // Appends a link: it acts on what the links before it produced.
  TransformChain& then(const AxisMap& link);
  template <typename Link>
  TransformChain& then(const Link& link) {
    return then(link.map());
  }

  bool identity() const { return identity_; }
  const AxisMap& forward() const { return forward_; }
  AxisPoint to_machine(const AxisPoint& program) const;
  AxisPoint to_program(const AxisPoint& machine) const;
  // A direction or difference (an arc's centre offset): the linear part only.
  AxisPoint direction_to_machine(const AxisPoint& v) const;
  // Whether the chain turns the plane of axes a and b over (an odd number of mirrors in it):
  // an arc's sense and the side of a compensation swap.
  bool reverses(int a, int b) const;

 private:
  AxisMap forward_ = AxisMap::Identity();
  AxisMap inverse_ = AxisMap::Identity();
  bool identity_ = true;
};

}  // namespace mcnc::interp::transform
