#include "channel/motion/trapezoid_planner.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mcnc::motion {

namespace {

bool all_finite(const AxisVector& v, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      return false;
    }
  }
  return true;
}

bool valid_limit(double value) {
  return std::isfinite(value) && value >= 0.0;
}

}  // namespace

TrapezoidPlanner::TrapezoidPlanner(std::size_t axis_count, const std::vector<AxisLimits>& limits)
    : axis_count_(axis_count) {
  if (axis_count > interp::kMaxChannelAxes || limits.size() < axis_count) {
    throw std::invalid_argument("TrapezoidPlanner: axis count does not match the limits");
  }
  for (std::size_t i = 0; i < axis_count; ++i) {
    const AxisLimits& l = limits[i];
    if (!valid_limit(l.rapid_rate) || !valid_limit(l.max_feed) || !valid_limit(l.acceleration)) {
      throw std::invalid_argument("TrapezoidPlanner: limits must be finite and not negative");
    }
    limits_[i] = l;
  }
}

bool TrapezoidPlanner::begin(const interp::CanonicalCommand& command,
                             const AxisVector& start) noexcept {
  using interp::CommandKind;
  if (!all_finite(start, axis_count_)) {
    return false;
  }
  // Axes past axis_count_ do not belong to the channel: they hold their start value.
  AxisVector end = start;

  switch (command.kind) {
    case CommandKind::program_end:
      start_ = start;
      end_ = end;
      duration_ = 0.0;
      phase_ = Phase::finish;
      break;

    case CommandKind::dwell:
      if (!std::isfinite(command.dwell_s) || command.dwell_s < 0.0) {
        return false;
      }
      start_ = start;
      end_ = end;
      duration_ = command.dwell_s;
      phase_ = Phase::dwell;
      break;

    case CommandKind::rapid:
    case CommandKind::linear: {
      const bool linear = command.kind == CommandKind::linear;
      if (linear && !(std::isfinite(command.feed) && command.feed > 0.0)) {
        return false;
      }
      if (!all_finite(command.target, axis_count_)) {
        return false;
      }
      AxisVector delta{};
      double sum_sq = 0.0;
      for (std::size_t i = 0; i < axis_count_; ++i) {
        end[i] = command.target[i];
        delta[i] = end[i] - start[i];
        sum_sq += delta[i] * delta[i];
      }
      const double length = std::sqrt(sum_sq);
      if (!std::isfinite(length)) {
        return false;
      }
      if (length == 0.0) {
        // Nothing to travel (or too little to represent): end on the target at once.
        start_ = start;
        end_ = end;
        duration_ = 0.0;
        phase_ = Phase::finish;
        break;
      }
      AxisVector direction{};
      double v_max = linear ? command.feed / 60.0 : std::numeric_limits<double>::infinity();
      double a_max = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < axis_count_; ++i) {
        direction[i] = delta[i] / length;
        const double share = std::fabs(direction[i]);
        if (share == 0.0) {
          continue;
        }
        // The path speed at which axis i alone reaches its own limit.
        const double axis_rate = linear ? limits_[i].max_feed : limits_[i].rapid_rate;
        v_max = std::fmin(v_max, axis_rate / share);
        a_max = std::fmin(a_max, limits_[i].acceleration / share);
      }
      if (!(v_max > 0.0 && std::isfinite(v_max) && a_max > 0.0 && std::isfinite(a_max))) {
        return false;
      }
      start_ = start;
      end_ = end;
      delta_ = delta;
      direction_ = direction;
      length_ = length;
      profile_ = TrapezoidProfile(length, v_max, a_max);
      duration_ = profile_.duration();
      phase_ = Phase::profile;
      break;
    }
  }
  time_ = 0.0;
  time_carry_ = 0.0;
  return true;
}

void TrapezoidPlanner::advance_time(double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  // Kahan summation: thousands of cycles of 0.001 s must add up to the whole-cycle count.
  const double y = dt - time_carry_;
  const double t = time_ + y;
  time_carry_ = (t - time_) - y;
  time_ = t;
}

void TrapezoidPlanner::write_end(MotionSample& out) const noexcept {
  out.pos = end_;
  out.vel = AxisVector{};
  out.acc = AxisVector{};
}

StepResult TrapezoidPlanner::step(double dt, MotionSample& out) noexcept {
  if (phase_ == Phase::idle || phase_ == Phase::finish) {
    phase_ = Phase::idle;
    write_end(out);
    return StepResult::block_done;
  }
  advance_time(dt);
  // A sliver of a cycle below the end is rounding, not another cycle of motion.
  const double slack = std::isfinite(dt) && dt > 0.0 ? 1e-9 * dt : 0.0;
  if (time_ >= duration_ - slack) {
    phase_ = Phase::idle;
    write_end(out);
    return StepResult::block_done;
  }
  if (phase_ == Phase::dwell) {
    out.pos = start_;
    out.vel = AxisVector{};
    out.acc = AxisVector{};
    return StepResult::moving;
  }
  const ProfileSample p = profile_.at(time_);
  const double fraction = p.s / length_;
  out.pos = start_;
  out.vel = AxisVector{};
  out.acc = AxisVector{};
  for (std::size_t i = 0; i < axis_count_; ++i) {
    out.pos[i] = start_[i] + delta_[i] * fraction;
    out.vel[i] = p.v * direction_[i];
    out.acc[i] = p.a * direction_[i];
  }
  return StepResult::moving;
}

}  // namespace mcnc::motion
