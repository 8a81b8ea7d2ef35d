#include "channel/motion/path_segment.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::motion {

double vector_norm(const AxisVector& v, std::size_t n) noexcept {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += v[i] * v[i];
  }
  return std::sqrt(sum);
}

PathSegment PathSegment::line(const AxisVector& from, const AxisVector& to,
                              std::size_t axes) noexcept {
  PathSegment p;
  p.axes_ = axes;
  p.start_ = from;
  p.end_ = to;
  AxisVector d{};
  for (std::size_t i = 0; i < axes; ++i) {
    d[i] = to[i] - from[i];
  }
  p.length_ = vector_norm(d, axes);
  for (std::size_t i = 0; i < axes && p.length_ > 0.0; ++i) {
    p.dir_[i] = d[i] / p.length_;
    p.share_[i] = std::fabs(p.dir_[i]);
  }
  return p;
}

PathSegment PathSegment::arc(const AxisVector& from, const AxisVector& to, std::size_t axes,
                             std::size_t a, std::size_t b, double center_a, double center_b,
                             bool ccw, int turns) noexcept {
  PathSegment p;
  p.arc_ = true;
  p.axes_ = axes;
  p.start_ = from;
  p.end_ = to;
  p.centre_ = from;
  p.centre_[a] = center_a;
  p.centre_[b] = center_b;
  const double sa = from[a] - center_a;
  const double sb = from[b] - center_b;
  const double ea = to[a] - center_a;
  const double eb = to[b] - center_b;
  p.r0_ = std::hypot(sa, sb);
  p.r1_ = std::hypot(ea, eb);
  if (p.r0_ > 0.0) {
    p.u_[a] = sa / p.r0_;
    p.u_[b] = sb / p.r0_;
  }
  const double turn = ccw ? 1.0 : -1.0;  // w: u turned 90 degrees in the direction of travel
  p.w_[a] = -turn * p.u_[b];
  p.w_[b] = turn * p.u_[a];
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double start_angle = std::atan2(sb, sa);
  const double end_angle = std::atan2(eb, ea);
  double sweep = turn * (end_angle - start_angle);
  while (sweep <= 1e-12) {
    sweep += kTwoPi;  // equal ends: a full circle
  }
  while (sweep > kTwoPi + 1e-12) {
    sweep -= kTwoPi;
  }
  p.sweep_ = sweep + kTwoPi * std::max(0, turns);
  for (std::size_t i = 0; i < axes; ++i) {
    if (i != a && i != b) {
      p.h_[i] = to[i] - from[i];
    }
  }
  p.finish_arc();
  return p;
}

PathSegment PathSegment::blend(const AxisVector& from, const AxisVector& to, const AxisVector& in,
                               const AxisVector& out, double radius, double angle,
                               std::size_t axes) noexcept {
  PathSegment p;
  p.arc_ = true;
  p.axes_ = axes;
  p.start_ = from;
  p.end_ = to;
  p.r0_ = radius;
  p.r1_ = radius;
  p.sweep_ = angle;
  // Toward the centre: the part of `out` across `in`.
  double along = 0.0;
  for (std::size_t i = 0; i < axes; ++i) {
    along += in[i] * out[i];
  }
  AxisVector n{};
  for (std::size_t i = 0; i < axes; ++i) {
    n[i] = out[i] - along * in[i];
  }
  const double nn = vector_norm(n, axes);
  for (std::size_t i = 0; i < axes; ++i) {
    n[i] = nn > 0.0 ? n[i] / nn : 0.0;
    p.centre_[i] = from[i] + radius * n[i];
    p.u_[i] = -n[i];
    p.w_[i] = in[i];
  }
  p.finish_arc();
  return p;
}

double PathSegment::length_without(std::size_t axis) const noexcept {
  if (axis >= axes_) {
    return length_;
  }
  // A line's and an arc's helical share of `axis` are both straight: take it off the square.
  const double along = arc_ ? h_[axis] : end_[axis] - start_[axis];
  return std::sqrt(std::max(0.0, length_ * length_ - along * along));
}

void PathSegment::finish_arc() noexcept {
  const double r_mean = (r0_ + r1_) / 2.0;
  double h2 = 0.0;
  for (std::size_t i = 0; i < axes_; ++i) {
    h2 += h_[i] * h_[i];
  }
  length_ = std::sqrt(r_mean * sweep_ * r_mean * sweep_ + h2);
  if (length_ > 0.0) {
    const double rate = sweep_ / length_;  // radians per unit of path
    kappa_ = r_mean * rate * rate;
    kappa_rate_ = r_mean * rate * rate * rate;
  }
  const double plane = length_ > 0.0 ? std::max(r0_, r1_) * sweep_ / length_ : 0.0;
  for (std::size_t i = 0; i < axes_; ++i) {
    const double in_plane = std::hypot(u_[i], w_[i]);
    share_[i] =
        std::min(1.0, plane * in_plane + (length_ > 0.0 ? std::fabs(h_[i]) / length_ : 0.0));
  }
}

void PathSegment::trim_line_start(double d) noexcept {
  for (std::size_t i = 0; i < axes_; ++i) {
    start_[i] += dir_[i] * d;
  }
  length_ -= d;
}

void PathSegment::trim_line_end(double d) noexcept {
  for (std::size_t i = 0; i < axes_; ++i) {
    end_[i] -= dir_[i] * d;
  }
  length_ -= d;
}

PathPoint PathSegment::point(double s) const noexcept {
  PathPoint p;
  if (!arc_) {
    p.tangent = dir_;
    p.pos = s >= length_ ? end_ : start_;
    for (std::size_t i = 0; i < axes_ && s > 0.0 && s < length_; ++i) {
      p.pos[i] = start_[i] + dir_[i] * s;
    }
    return p;
  }
  if (length_ <= 0.0) {
    p.pos = end_;
    return p;
  }
  const double f = std::clamp(s / length_, 0.0, 1.0);
  const double angle = sweep_ * f;
  const double r = r0_ + (r1_ - r0_) * f;
  const double rate = sweep_ / length_;  // radians per unit of path
  const double dr = (r1_ - r0_) / length_;
  const double c = std::cos(angle);
  const double sn = std::sin(angle);
  p.pos = start_;
  for (std::size_t i = 0; i < axes_; ++i) {
    const double radial = c * u_[i] + sn * w_[i];
    p.pos[i] = centre_[i] + r * radial + f * h_[i];
    p.tangent[i] = r * rate * (-sn * u_[i] + c * w_[i]) + dr * radial + h_[i] / length_;
    p.curvature[i] = -r * rate * rate * radial;
  }
  if (s >= length_) {
    p.pos = end_;
  } else if (s <= 0.0) {
    p.pos = start_;
  }
  return p;
}

}  // namespace mcnc::motion
