#include "channel/motion/speed_transition.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::motion {

namespace {

ProfileSample advance(const ProfileSample& s, double jerk, double t) noexcept {
  return ProfileSample{s.s + s.v * t + s.a * t * t / 2.0 + jerk * t * t * t / 6.0,
                       s.v + s.a * t + jerk * t * t / 2.0, s.a + jerk * t};
}

}  // namespace

void JerkPhases::add(double duration, double jerk) noexcept {
  if (!(duration > 0.0) || count_ >= phases_.size()) {
    return;
  }
  phases_[count_++] = Phase{duration, jerk};
  end_ = advance(end_, jerk, duration);
  total_ += duration;
}

ProfileSample JerkPhases::at(double t) const noexcept {
  if (count_ == 0) {
    return ProfileSample{start_.s + start_.v * std::max(0.0, t), start_.v, 0.0};
  }
  if (t >= total_) {
    return ProfileSample{end_.s + end_.v * (t - total_), end_.v, 0.0};
  }
  ProfileSample state = start_;
  double begin = 0.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Phase& p = phases_[i];
    if (t < begin + p.duration) {
      return advance(state, p.jerk, std::max(0.0, t - begin));
    }
    state = advance(state, p.jerk, p.duration);
    begin += p.duration;
  }
  return end_;
}

double released_velocity(double v0, double a0, double jerk) noexcept {
  return v0 + a0 * std::fabs(a0) / (2.0 * jerk);
}

JerkPhases speed_transition(double v0, double a0, double v1, const JerkLimits& limits) noexcept {
  const double a_max = limits.acceleration;
  const double j = limits.jerk;
  a0 = std::clamp(a0, -a_max, a_max);
  JerkPhases out(ProfileSample{0.0, v0, a0});
  const double released = released_velocity(v0, a0, j);
  const double sign = v1 >= released ? 1.0 : -1.0;
  // Mirror so that the change needs more acceleration (sign +1): then the acceleration rises
  // from a0 to a peak, holds, and falls back to zero.
  const double a0m = sign * a0;
  const double dv = sign * (v1 - v0);
  // Velocity change with peak p and no hold: (2 p^2 - a0^2) / (2 j).
  double peak = std::sqrt(std::max(0.0, (a0m * a0m + 2.0 * j * dv) / 2.0));
  double hold = 0.0;
  if (peak > a_max) {
    peak = a_max;
    hold = std::max(0.0, (dv - (2.0 * peak * peak - a0m * a0m) / (2.0 * j)) / peak);
  }
  peak = std::max(peak, a0m);  // no rise when a0 already is the peak (only the release)
  out.add((peak - a0m) / j, sign * j);
  out.add(hold, 0.0);
  out.add(peak / j, -sign * j);
  return out;
}

double max_speed_within(double distance, double v_other, const JerkLimits& limits) noexcept {
  const double a = limits.acceleration;
  const double j = limits.jerk;
  const double w = v_other;
  if (!(distance > 0.0)) {
    return std::min(w, limits.velocity);
  }
  if (w <= limits.velocity && speed_change_distance(limits.velocity, w, limits) <= distance) {
    return limits.velocity;  // the common case: room to change from the limit itself
  }
  double dv = 0.0;
  // With a constant-acceleration phase (dv >= a^2/j):
  //   distance = (2w + dv)/2 * (dv/a + a/j), a quadratic in dv.
  const double qa = 1.0 / (2.0 * a);
  const double qb = w / a + a / (2.0 * j);
  const double qc = w * a / j - distance;
  const double disc = std::max(0.0, qb * qb - 4.0 * qa * qc);
  dv = 2.0 * (-qc) / (qb + std::sqrt(disc));  // the stable root of the quadratic
  if (dv < a * a / j) {
    // Without: distance = (2w + dv) sqrt(dv/j); with x = sqrt(dv/j): j x^3 + 2w x - distance.
    const double p = 2.0 * w / j;
    const double q = -distance / j;
    const double root = std::sqrt(q * q / 4.0 + p * p * p / 27.0);
    double x = std::cbrt(-q / 2.0 + root) + std::cbrt(-q / 2.0 - root);
    for (int i = 0; i < 3; ++i) {  // Newton polishes the cancellation of the Cardano form
      const double f = j * x * x * x + 2.0 * w * x - distance;
      const double df = 3.0 * j * x * x + 2.0 * w;
      if (df > 0.0) {
        x -= f / df;
      }
    }
    x = std::max(0.0, x);
    dv = j * x * x;
  }
  dv = std::max(0.0, dv);
  double v = std::min(w + dv, limits.velocity);
  // A small change on a high speed loses digits in w + dv, and the distance grows with its
  // square root: back off until the result really fits.
  for (int i = 0; i < 40 && speed_change_distance(v, w, limits) > distance; ++i) {
    dv *= 0.99;
    v = std::min(w + dv, limits.velocity);
  }
  return std::max(v, std::min(w, limits.velocity));
}

}  // namespace mcnc::motion
