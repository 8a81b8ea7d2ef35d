#include "channel/motion/trapezoid_profile.hpp"

#include <cmath>

namespace mcnc::motion {

TrapezoidProfile::TrapezoidProfile(double distance, double v_max, double a_max) noexcept
    : distance_(distance), accel_(a_max) {
  if (distance <= 0.0) {
    return;
  }
  // Reaching v_max and stopping again takes v_max^2 / a_max of travel.
  if (distance * a_max >= v_max * v_max) {
    v_peak_ = v_max;
    t_accel_ = v_max / a_max;
    s_accel_ = 0.5 * v_max * t_accel_;
    t_cruise_ = (distance - 2.0 * s_accel_) / v_max;
  } else {
    v_peak_ = std::sqrt(distance * a_max);
    t_accel_ = v_peak_ / a_max;
    s_accel_ = 0.5 * distance;
    t_cruise_ = 0.0;
  }
  t_total_ = 2.0 * t_accel_ + t_cruise_;
}

ProfileSample TrapezoidProfile::at(double t) const noexcept {
  if (t <= 0.0) {
    return {};
  }
  if (t >= t_total_) {
    return {distance_, 0.0, 0.0};
  }
  if (t < t_accel_) {
    return {0.5 * accel_ * t * t, accel_ * t, accel_};
  }
  if (t < t_accel_ + t_cruise_) {
    return {s_accel_ + v_peak_ * (t - t_accel_), v_peak_, 0.0};
  }
  // Measured back from the end so that the last samples close on the distance without drift.
  // Rounding can put `remaining` an ulp past t_accel_; the speed must still not exceed the peak.
  const double remaining = std::fmin(t_total_ - t, t_accel_);
  return {distance_ - 0.5 * accel_ * remaining * remaining, accel_ * remaining, -accel_};
}

}  // namespace mcnc::motion
