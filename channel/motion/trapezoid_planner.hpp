#pragma once
// Exact stop per block with a trapezoidal (or triangular) feed profile along the straight
// path; the path feed is limited so that no axis exceeds its rate or acceleration.
// G00 moves interpolated on a straight line at the slowest axis's rapid rate.
#include "channel/motion/block_planner.hpp"

#include <vector>

namespace mcnc::motion {

class TrapezoidPlanner final : public BlockPlanner {
public:
  TrapezoidPlanner(std::size_t axis_count, const std::vector<AxisLimits>& limits);
  bool begin(const interp::CanonicalCommand& command, const AxisVector& start) noexcept override;
  StepResult step(double dt, MotionSample& out) noexcept override;
  // ...
};

} // namespace mcnc::motion
