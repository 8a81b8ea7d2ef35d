#pragma once
// One piece of the tool path in the channel's axis space: a straight line or a circular arc
// (with a linear part: a helix; with a changing radius: the spiral that closes an arc whose end
// lies a little off its circle). Parametrised by path length s; position(length()) is exactly
// the programmed end point, so chained pieces never drift. Pure math, no allocation.
#include "channel/interp/axis_vector.hpp"

#include <cstddef>

namespace mcnc::motion {

using interp::AxisVector;

// Euclidean length of the first n components.
double vector_norm(const AxisVector& v, std::size_t n) noexcept;

// Position, unit tangent and curvature vector (d tangent / ds: toward the centre, of length
// 1/radius on a plane circle) at one point of a segment.
struct PathPoint {
  AxisVector pos{};
  AxisVector tangent{};
  AxisVector curvature{};
};

class PathSegment {
 public:
  PathSegment() = default;
  static PathSegment line(const AxisVector& from, const AxisVector& to, std::size_t axes) noexcept;
  // An arc in the plane of axes `a` and `b` around `center` (those two axes), counter-clockwise
  // when turning from axis a toward axis b, with `turns` extra full turns; the other axes move
  // linearly (a helix). Equal start and end points make a full circle.
  static PathSegment arc(const AxisVector& from, const AxisVector& to, std::size_t axes,
                         std::size_t a, std::size_t b, double center_a, double center_b, bool ccw,
                         int turns) noexcept;
  // The arc of radius `radius` tangent to direction `in` at `from` and turning toward `out`
  // through `angle` radians (the blend of a corner between two lines); ends at `to`.
  static PathSegment blend(const AxisVector& from, const AxisVector& to, const AxisVector& in,
                           const AxisVector& out, double radius, double angle,
                           std::size_t axes) noexcept;

  [[nodiscard]] bool is_arc() const noexcept { return arc_; }
  [[nodiscard]] double length() const noexcept { return length_; }
  // The length of the path without the travel of `axis`, an axis that moves straight along the
  // segment (any axis of a line, a helical axis of an arc); an arc's circle stays whole.
  [[nodiscard]] double length_without(std::size_t axis) const noexcept;
  [[nodiscard]] const AxisVector& start() const noexcept { return start_; }
  [[nodiscard]] const AxisVector& end() const noexcept { return end_; }

  // At s (clamped to the segment); from length() on the position is exactly end().
  [[nodiscard]] PathPoint point(double s) const noexcept;
  [[nodiscard]] AxisVector position(double s) const noexcept { return point(s).pos; }
  [[nodiscard]] AxisVector tangent(double s) const noexcept { return point(s).tangent; }
  [[nodiscard]] AxisVector curvature(double s) const noexcept { return point(s).curvature; }
  // |curvature| and |d curvature / ds| (constant along the piece).
  [[nodiscard]] double curvature_norm() const noexcept { return kappa_; }
  [[nodiscard]] double curvature_rate() const noexcept { return kappa_rate_; }
  // The largest share of the direction any axis takes, per axis: |tangent component| <= this.
  [[nodiscard]] const AxisVector& axis_share() const noexcept { return share_; }
  // Trims the first or last `d` of a line (a corner blend takes it); d < length.
  void trim_line_start(double d) noexcept;
  void trim_line_end(double d) noexcept;

 private:
  void finish_arc() noexcept;

  bool arc_ = false;
  std::size_t axes_ = 0;
  AxisVector start_{};
  AxisVector end_{};
  double length_ = 0.0;
  AxisVector dir_{};  // line: unit direction
  // arc: p(s) = centre + r(f) (cos(sweep f) u + sin(sweep f) w) + f h, f = s / length
  AxisVector centre_{};
  AxisVector u_{};
  AxisVector w_{};
  AxisVector h_{};
  double r0_ = 0.0;
  double r1_ = 0.0;
  double sweep_ = 0.0;
  double kappa_ = 0.0;
  double kappa_rate_ = 0.0;
  AxisVector share_{};
};

}  // namespace mcnc::motion
