#include "channel/motion/jerk_limited_profile.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::motion {

namespace {

// Jerk-phase and constant-acceleration durations of a speed change of `dv` >= 0.
struct ChangeTimes {
  double jerk = 0.0;
  double constant = 0.0;
};

ChangeTimes change_times(double dv, const JerkLimits& l) noexcept {
  const double a = l.acceleration;
  const double j = l.jerk;
  if (dv >= a * a / j) {
    return {a / j, dv / a - a / j};
  }
  return {std::sqrt(dv / j), 0.0};
}

ProfileSample advance(const ProfileSample& s, double jerk, double t) noexcept {
  ProfileSample out;
  out.s = s.s + s.v * t + s.a * t * t / 2.0 + jerk * t * t * t / 6.0;
  out.v = s.v + s.a * t + jerk * t * t / 2.0;
  out.a = s.a + jerk * t;
  return out;
}

}  // namespace

double speed_change_time(double v0, double v1, const JerkLimits& limits) noexcept {
  const ChangeTimes c = change_times(std::fabs(v1 - v0), limits);
  return 2.0 * c.jerk + c.constant;
}

double speed_change_distance(double v0, double v1, const JerkLimits& limits) noexcept {
  // The velocity curve of a change is point-symmetric about its middle: the mean velocity is
  // the mean of the ends.
  return (v0 + v1) / 2.0 * speed_change_time(v0, v1, limits);
}

ProfileResult JerkLimitedProfile::plan(double distance, double v_start, double v_end,
                                       const JerkLimits& limits, JerkLimitedProfile& out) noexcept {
  const JerkLimits& l = limits;
  if (!(l.velocity > 0.0) || !(l.acceleration > 0.0) || !(l.jerk > 0.0) || !(distance >= 0.0) ||
      !(v_start >= 0.0) || !(v_end >= 0.0) || v_end > l.velocity * (1.0 + 1e-12)) {
    return ProfileResult::bad_limits;
  }
  const auto needed = [&](double vp) {
    return speed_change_distance(v_start, vp, l) + speed_change_distance(vp, v_end, l);
  };
  constexpr double kRounding = 1e-9;        // 1 nm (relative and absolute) of rounding
  const bool above = v_start > l.velocity;  // slows down to the limit first
  double vp = l.velocity;
  if (above) {
    // Down to a plateau at most the limit, then to the end. A plateau on the way costs
    // distance: with no room for the limit the plateau is lower, down to one straight change
    // to the end speed.
    if (needed(v_end) > distance * (1.0 + kRounding) + kRounding) {
      return ProfileResult::unreachable;
    }
    if (needed(vp) > distance) {
      double low = v_end;
      double high = l.velocity;
      for (int i = 0; i < 64 && high - low > 1e-15 * high; ++i) {
        const double mid = (low + high) / 2.0;
        (needed(mid) > distance ? high : low) = mid;
      }
      vp = low;
    }
  }
  double low = above ? vp : std::max(v_start, v_end);
  if (!above && needed(low) > distance * (1.0 + kRounding) + kRounding) {
    return ProfileResult::unreachable;
  }
  if (!above && needed(vp) > distance) {
    // The distance is too short for the limit: the peak where up and down meet. needed() grows
    // with vp; bisection to the last representable digit keeps it deterministic.
    double high = l.velocity;
    for (int i = 0; i < 64 && high - low > 1e-15 * high; ++i) {
      const double mid = (low + high) / 2.0;
      (needed(mid) > distance ? high : low) = mid;
    }
    vp = low;
  }
  const ChangeTimes up = change_times(std::fabs(vp - v_start), l);
  const double up_sign = vp >= v_start ? 1.0 : -1.0;
  const ChangeTimes down = change_times(vp - v_end, l);
  const double cruise = vp > 0.0 ? std::max(0.0, (distance - needed(vp)) / vp) : 0.0;
  JerkLimitedProfile p;
  const double j = l.jerk;
  const std::array<std::pair<double, double>, 7> plan{{{up.jerk, up_sign * j},
                                                       {up.constant, 0.0},
                                                       {up.jerk, -up_sign * j},
                                                       {cruise, 0.0},
                                                       {down.jerk, -j},
                                                       {down.constant, 0.0},
                                                       {down.jerk, j}}};
  ProfileSample state{0.0, v_start, 0.0};
  double total = 0.0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    p.phases_[i] = Phase{plan[i].first, plan[i].second, state};
    state = advance(state, plan[i].second, plan[i].first);
    total += plan[i].first;
  }
  p.distance_ = distance;
  p.v_end_ = v_end;
  p.v_peak_ = vp;
  p.total_ = total;
  out = p;
  return ProfileResult::ok;
}

ProfileSample JerkLimitedProfile::at(double t) const noexcept {
  if (t <= 0.0) {
    return phases_[0].start;
  }
  if (t >= total_) {
    return ProfileSample{distance_, v_end_, 0.0};
  }
  double begin = 0.0;
  for (const Phase& ph : phases_) {
    if (t < begin + ph.duration) {
      return advance(ph.start, ph.jerk, t - begin);
    }
    begin += ph.duration;
  }
  return ProfileSample{distance_, v_end_, 0.0};
}

}  // namespace mcnc::motion
