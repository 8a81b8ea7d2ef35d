#pragma once
// Exact stop per block with a trapezoidal (or triangular) feed profile along the straight
// path; the path feed is limited so that no axis exceeds its rate or acceleration.
// G00 moves interpolated on a straight line at the slowest axis's rapid rate.
#include "channel/motion/block_planner.hpp"
#include "channel/motion/trapezoid_profile.hpp"

#include <array>
#include <vector>

namespace mcnc::motion {

class TrapezoidPlanner final : public BlockPlanner {
 public:
  TrapezoidPlanner(std::size_t axis_count, const std::vector<AxisLimits>& limits);
  bool begin(const interp::CanonicalCommand& command, const AxisVector& start) noexcept override;
  StepResult step(double dt, MotionSample& out) noexcept override;

 private:
  enum class Phase { idle, profile, dwell, finish };

  void write_end(MotionSample& out) const noexcept;
  void advance_time(double dt) noexcept;

  std::size_t axis_count_ = 0;
  std::array<AxisLimits, interp::kMaxChannelAxes> limits_{};
  Phase phase_ = Phase::idle;
  AxisVector start_{};
  AxisVector end_{};        // exact end point written by the last sample
  AxisVector delta_{};      // end - start
  AxisVector direction_{};  // unit vector of the path
  double length_ = 0.0;
  TrapezoidProfile profile_;
  double duration_ = 0.0;  // profile or dwell time
  double time_ = 0.0;      // since begin(), Kahan-summed so long blocks end on the right cycle
  double time_carry_ = 0.0;
};

}  // namespace mcnc::motion
