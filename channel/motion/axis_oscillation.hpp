#pragma once
// G81.1 / G80.1 sine-profile oscillation of one axis (spec dafeng L2454-2505): the axis moves
// between its top and bottom dead points by itself while the path goes on. Every stroke is half
// a cosine, from rest to rest: x(t) = from + (to - from) (1 - cos(pi t / T)) / 2, so the axis
// reverses exactly at the dead points, and equal strokes join into one sine with a continuous
// acceleration. Pure and deterministic: no clock, no allocation, no exceptions.
#include "channel/motion/path_limits.hpp"

#include <cstdint>

namespace mcnc::motion {

struct OscillationSample {
  double pos = 0.0;
  double vel = 0.0;
  double acc = 0.0;
};

class AxisOscillation {
 public:
  enum class Phase : std::uint8_t {
    off,        // not oscillating (never started, or ended and at rest)
    running,    // stroking between the dead points
    finishing,  // G80.1: the stroke under way, then one to the end position
    stopping,   // reset: decelerating to rest where it is
  };

  // Starts at rest at `from`: a first stroke to `top` when the axis is not there, then top to
  // bottom and back. `feed` (units/s) is the highest speed of a stroke; the axis's limits
  // (velocity, acceleration, jerk > 0) lengthen a stroke that would exceed them. False, and
  // nothing changes, when a value is not finite, top equals bottom or feed is not > 0.
  bool start(double from, double top, double bottom, double feed,
             const AxisDynamics& limits) noexcept;
  // G80.1: the stroke under way ends at its dead point, then one stroke to `end` (none when it
  // is there already); then at rest and off. Ignored unless running.
  void finish_at(double end) noexcept;
  // Reset: decelerates at `deceleration` (units/s^2, > 0) to rest where it is; then off.
  void stop(double deceleration) noexcept;
  // Advances by dt seconds and returns the axis's setpoint then.
  OscillationSample step(double dt) noexcept;

  [[nodiscard]] Phase phase() const noexcept { return phase_; }
  [[nodiscard]] bool active() const noexcept { return phase_ != Phase::off; }
  [[nodiscard]] const OscillationSample& sample() const noexcept { return sample_; }
  // The duration of a stroke of length `distance` at `feed` within `limits`.
  [[nodiscard]] static double stroke_time(double distance, double feed,
                                          const AxisDynamics& limits) noexcept;

 private:
  void begin_stroke(double from, double to) noexcept;
  [[nodiscard]] OscillationSample stroke_at(double t) const noexcept;

  Phase phase_ = Phase::off;
  AxisDynamics limits_{};
  double feed_ = 0.0;
  double top_ = 0.0;
  double bottom_ = 0.0;
  double end_ = 0.0;
  bool last_stroke_ = false;  // finishing: the stroke under way goes to end_
  double from_ = 0.0;         // the stroke under way
  double to_ = 0.0;
  double duration_ = 0.0;
  double t_ = 0.0;
  double deceleration_ = 0.0;
  OscillationSample sample_{};
};

}  // namespace mcnc::motion
