#pragma once
// The motion planner interface: takes canonical commands one at a time and yields one
// position/velocity/acceleration sample per axis per cycle. The motion issue replaces the
// exact-stop trapezoid behind this interface with look-ahead; the channel does not change.
#include "channel/interp/canonical_command.hpp"

#include <cstddef>

namespace mcnc::motion {

using interp::AxisVector;

struct AxisLimits {
  double rapid_rate = 0.0;    // units/s
  double max_feed = 0.0;      // units/s
  double acceleration = 0.0;  // units/s^2
};

struct MotionSample {
  AxisVector pos{};
  AxisVector vel{};
  AxisVector acc{};
};

enum class StepResult { moving, block_done };

class BlockPlanner {
 public:
  virtual ~BlockPlanner() = default;
  // Starts a motion or dwell command from `start`. Returns false (and does nothing) for a
  // command it cannot plan (e.g. zero feed on a move): the caller raises an alarm.
  virtual bool begin(const interp::CanonicalCommand& command, const AxisVector& start) noexcept = 0;
  // Advances one cycle of `dt` seconds and writes the sample for the end of that cycle.
  // block_done: the sample is exactly the block's end point (exact stop), velocity zero.
  virtual StepResult step(double dt, MotionSample& out) noexcept = 0;
};

}  // namespace mcnc::motion
