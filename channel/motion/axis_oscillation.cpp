#include "channel/motion/axis_oscillation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::motion {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kAtPoint = 1e-9;  // units: the axis stands at a point

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

double AxisOscillation::stroke_time(double distance, double feed,
                                    const AxisDynamics& limits) noexcept {
  const double d = std::fabs(distance);
  // Half a cosine of amplitude d/2 over T: peak speed pi d / 2T, acceleration pi^2 d / 2T^2,
  // jerk pi^3 d / 2T^3. The slowest of the three bounds sets T.
  double t = kPi * d / (2.0 * feed);
  if (positive(limits.velocity)) {
    t = std::max(t, kPi * d / (2.0 * limits.velocity));
  }
  if (positive(limits.acceleration)) {
    t = std::max(t, kPi * std::sqrt(d / (2.0 * limits.acceleration)));
  }
  if (positive(limits.jerk)) {
    t = std::max(t, kPi * std::cbrt(d / (2.0 * limits.jerk)));
  }
  return t;
}

bool AxisOscillation::start(double from, double top, double bottom, double feed,
                            const AxisDynamics& limits) noexcept {
  if (!std::isfinite(from) || !std::isfinite(top) || !std::isfinite(bottom) || !positive(feed) ||
      std::fabs(top - bottom) <= kAtPoint) {
    return false;
  }
  limits_ = limits;
  feed_ = feed;
  top_ = top;
  bottom_ = bottom;
  last_stroke_ = false;
  phase_ = Phase::running;
  sample_ = OscillationSample{from, 0.0, 0.0};
  if (std::fabs(from - top) > kAtPoint) {
    begin_stroke(from, top);
  } else {
    begin_stroke(top, bottom);
  }
  return true;
}

void AxisOscillation::finish_at(double end) noexcept {
  if (phase_ == Phase::running) {
    phase_ = Phase::finishing;
    end_ = end;
  }
}

void AxisOscillation::stop(double deceleration) noexcept {
  if (phase_ == Phase::running || phase_ == Phase::finishing) {
    phase_ = Phase::stopping;
    deceleration_ = positive(deceleration) ? deceleration : 1.0;
  }
}

void AxisOscillation::begin_stroke(double from, double to) noexcept {
  from_ = from;
  to_ = to;
  duration_ = stroke_time(to - from, feed_, limits_);
  t_ = 0.0;
}

OscillationSample AxisOscillation::stroke_at(double t) const noexcept {
  const double d = to_ - from_;
  const double w = kPi / duration_;
  return OscillationSample{from_ + d * (1.0 - std::cos(w * t)) / 2.0, d * w * std::sin(w * t) / 2.0,
                           d * w * w * std::cos(w * t) / 2.0};
}

OscillationSample AxisOscillation::step(double dt) noexcept {
  switch (phase_) {
    case Phase::off:
      break;
    case Phase::stopping: {
      const double v = sample_.vel;
      const double dv = std::min(std::fabs(v), deceleration_ * dt);
      const double v1 = v - std::copysign(dv, v);
      sample_.pos += (v + v1) / 2.0 * dt;
      sample_.vel = v1;
      sample_.acc = v1 == 0.0 ? 0.0 : -std::copysign(deceleration_, v);
      if (v1 == 0.0) {
        phase_ = Phase::off;
      }
      break;
    }
    case Phase::running:
    case Phase::finishing: {
      t_ += dt;
      // A step may pass a dead point: the time beyond it runs on the next stroke.
      while (t_ >= duration_) {
        const double over = t_ - duration_;
        if (last_stroke_) {
          sample_ = OscillationSample{to_, 0.0, 0.0};
          phase_ = Phase::off;
          return sample_;
        }
        const double at = to_;
        if (phase_ == Phase::finishing) {
          last_stroke_ = true;
          if (std::fabs(end_ - at) <= kAtPoint) {
            sample_ = OscillationSample{at, 0.0, 0.0};
            phase_ = Phase::off;
            return sample_;
          }
          begin_stroke(at, end_);
        } else {
          begin_stroke(at, std::fabs(at - top_) <= kAtPoint ? bottom_ : top_);
        }
        t_ = over;
      }
      sample_ = stroke_at(t_);
      break;
    }
  }
  return sample_;
}

}  // namespace mcnc::motion
