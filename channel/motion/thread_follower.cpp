#include "channel/motion/thread_follower.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::motion {

double ThreadFollower::sync_s(double u) const noexcept {
  const double du = u - u_in_;
  return s_in_ + lead_at(u_in_) * du + geometry_.path_change * du * du / 2.0;
}

bool ThreadFollower::plan(const ThreadGeometry& geometry, double rev_per_s,
                          const JerkLimits& limits) noexcept {
  if (!(geometry.length > 0.0) || !(geometry.path_lead > 0.0) || !(rev_per_s > 0.0) ||
      !(limits.acceleration > 0.0) || !(limits.jerk > 0.0)) {
    return false;
  }
  geometry_ = geometry;
  n_ = rev_per_s;
  u_in_ = 0.0;
  s_in_ = 0.0;
  ramp_in_ = JerkPhases(ProfileSample{});
  if (geometry.ramp_in) {
    ramp_in_ = speed_transition(0.0, 0.0, geometry.path_lead * n_, limits);
    u_in_ = ramp_in_.duration() * n_;
    s_in_ = ramp_in_.end().s;
    if (geometry.path_change != 0.0) {  // G34: reach the lead the thread has at the ramp's end
      const double v = std::max(0.0, lead_at(u_in_)) * n_;
      ramp_in_ = speed_transition(0.0, 0.0, v, limits);
      u_in_ = ramp_in_.duration() * n_;
      s_in_ = ramp_in_.end().s;
    }
  }
  // Where the synchronous part reaches `s`: solve s_in + l du + c du^2 / 2 = s.
  const auto sync_u = [&](double s) {
    const double l = lead_at(u_in_);
    const double c = geometry_.path_change;
    const double d = s - s_in_;
    if (std::fabs(c) < 1e-15) {
      return u_in_ + d / l;
    }
    const double disc = std::max(0.0, l * l + 2.0 * c * d);
    return u_in_ + 2.0 * d / (l + std::sqrt(disc));
  };
  s_out_ = 0.0;
  ramp_out_ = JerkPhases(ProfileSample{});
  if (geometry.ramp_out) {
    double u = sync_u(geometry.length);
    for (int i = 0; i < 3; ++i) {  // the ramp-out's speed depends (G34) on where it starts
      ramp_out_ = speed_transition(0.0, 0.0, std::max(0.0, lead_at(u)) * n_, limits);
      s_out_ = ramp_out_.end().s;
      u = sync_u(geometry.length - s_out_);
    }
    u_out_ = std::max(u_in_, u);
    u_end_ = u_out_ + ramp_out_.duration() * n_;
  } else {
    u_out_ = sync_u(geometry.length);
    u_end_ = u_out_;
  }
  return true;
}

ThreadSample ThreadFollower::at(double u) const noexcept {
  ThreadSample out;
  if (u <= 0.0) {
    out.ds_du = geometry_.ramp_in ? 0.0 : geometry_.path_lead;
    return out;
  }
  if (u >= u_end_) {
    out.s = geometry_.length;
    out.ds_du = geometry_.ramp_out ? 0.0 : lead_at(u_end_);
    return out;
  }
  if (u < u_in_) {
    const ProfileSample p = ramp_in_.at(u / n_);
    return ThreadSample{p.s, p.v / n_, p.a / (n_ * n_)};
  }
  if (u < u_out_ || !geometry_.ramp_out) {
    out.s = std::min(sync_s(u), geometry_.length);
    out.ds_du = lead_at(u);
    out.d2s_du2 = geometry_.path_change;
    return out;
  }
  // Ramp-out: the ramp-in of the end speed run backward, ending exactly at the length.
  const double t_left = std::max(0.0, (u_end_ - u) / n_);
  const ProfileSample p = ramp_out_.at(t_left);
  out.s = geometry_.length - p.s;
  out.ds_du = p.v / n_;
  out.d2s_du2 = -p.a / (n_ * n_);
  return out;
}

}  // namespace mcnc::motion
