#include "channel/interp/cycles/chip_breaking.hpp"

#include "channel/interp/path/plane_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mcnc::interp::cycles {

namespace {

// The move as a function of its fraction t in [0, 1]: a line, or an arc swept from a0 by
// `sweep` radians with the other axes in proportion.
struct MovePath {
  const Command* c = nullptr;
  AxisVector from{};
  std::size_t axes = 0;
  bool arc = false;
  std::size_t ia = 0;
  std::size_t ib = 0;
  double radius = 0.0;
  double a0 = 0.0;
  double sweep = 0.0;
  double length = 0.0;

  AxisVector at(double t) const {
    AxisVector p = from;
    for (std::size_t i = 0; i < axes; ++i) {
      p[i] = from[i] + t * (c->to[i] - from[i]);
    }
    if (t >= 1.0) {
      return c->to;
    }
    if (arc) {
      const double angle = a0 + t * sweep;
      p[ia] = c->center[0] + radius * std::cos(angle);
      p[ib] = c->center[1] + radius * std::sin(angle);
    }
    return p;
  }

  // The piece from t0 to t1 (t1 < t0: backwards) as a command like c.
  Command piece(double t0, double t1) const {
    Command p = *c;
    p.to = at(t1);
    p.exact_stop = false;
    p.barrier = false;
    if (arc) {
      const double swept = std::fabs(t1 - t0) * std::fabs(sweep);
      const bool ccw = (sweep > 0.0) == (t1 > t0);
      p.direction = ccw ? ArcDirection::ccw : ArcDirection::cw;
      // Whole turns beyond the first (a piece of exactly one turn ends where it starts).
      p.turns = std::max(0, static_cast<int>(std::ceil(swept / (2.0 * path::kPi) - 1e-9)) - 1);
    }
    return p;
  }
};

MovePath path_of(const Command& c, const AxisVector& from, std::size_t axes) {
  MovePath m;
  m.c = &c;
  m.from = from;
  m.axes = axes;
  m.arc = c.op == Op::arc;
  double others = 0.0;  // squared length along the axes that move straight
  if (m.arc) {
    m.ia = static_cast<std::size_t>(c.center_axes[0]);
    m.ib = static_cast<std::size_t>(c.center_axes[1]);
    path::PlaneMove move;
    move.kind = path::MoveKind::arc;
    move.to = {c.to[m.ia], c.to[m.ib]};
    move.center = {c.center[0], c.center[1]};
    move.ccw = c.direction == ArcDirection::ccw;
    const path::Point2 start{from[m.ia], from[m.ib]};
    m.radius = path::arc_radius(start, move);
    m.sweep = path::arc_sweep(start, move);
    m.sweep += (m.sweep < 0.0 ? -1.0 : 1.0) * 2.0 * path::kPi * c.turns;
    m.a0 = std::atan2(start.b - move.center.b, start.a - move.center.a);
  }
  for (std::size_t i = 0; i < axes; ++i) {
    if (m.arc && (i == m.ia || i == m.ib)) {
      continue;
    }
    others += (c.to[i] - from[i]) * (c.to[i] - from[i]);
  }
  const double plane = m.arc ? m.radius * std::fabs(m.sweep) : 0.0;
  m.length = std::sqrt(plane * plane + others);
  return m;
}

// The revolutions of feed from the move's start to its fraction t: in proportion to the path
// at a constant speed, else (G96) summed along the path from the speed at each point.
class RevCount {
 public:
  RevCount(const MovePath& m, const Command& c) {
    if (c.chip_surface <= 0.0) {
      total_ = m.length / c.chip_rev_length;
      return;
    }
    // Steps of at most 0.01 mm (at least 64, at most 4096 a move): the speed changes little
    // along one, and the midpoint's speed counts for it.
    const auto steps =
        static_cast<std::size_t>(std::clamp(std::ceil(m.length / 0.01), 64.0, 4096.0));
    const auto axis = static_cast<std::size_t>(c.chip_radius_axis);
    const double k = 1000.0 * c.chip_surface / (2.0 * path::kPi);  // rpm times radius (mm)
    table_.resize(steps + 1);
    table_[0] = 0.0;
    for (std::size_t i = 0; i < steps; ++i) {
      const double t = (static_cast<double>(i) + 0.5) / static_cast<double>(steps);
      const double r = std::fabs(m.at(t)[axis] - c.chip_centre);
      const double rpm = r * c.chip_max_rpm > k ? k / r : c.chip_max_rpm;
      table_[i + 1] = table_[i] + m.length / static_cast<double>(steps) * rpm / c.feed;
    }
    total_ = table_.back();
  }
  [[nodiscard]] double total() const { return total_; }
  [[nodiscard]] double at(double t) const {
    if (table_.empty()) {
      return t * total_;
    }
    const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(table_.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(x), table_.size() - 2);
    return table_[i] + (x - static_cast<double>(i)) * (table_[i + 1] - table_[i]);
  }
  // The fraction where the count reaches `revs` (0 <= revs <= total()).
  [[nodiscard]] double fraction(double revs) const {
    if (table_.empty()) {
      return total_ > 0.0 ? revs / total_ : 1.0;
    }
    const auto hi = std::lower_bound(table_.begin() + 1, table_.end(), revs);
    if (hi == table_.end()) {
      return 1.0;
    }
    const auto i = static_cast<std::size_t>(hi - table_.begin()) - 1;
    const double span = table_[i + 1] - table_[i];
    const double within = span > 0.0 ? (revs - table_[i]) / span : 0.0;
    return (static_cast<double>(i) + within) / static_cast<double>(table_.size() - 1);
  }

 private:
  double total_ = 0.0;
  std::vector<double> table_;  // the count at step ends (G96), empty at a constant speed
};

}  // namespace

bool split_for_chip_breaking(const Command& c, const AxisVector& from, std::size_t axes,
                             double& revs, std::vector<Command>& out) {
  const MovePath m = path_of(c, from, axes);
  if (c.chip_rev_length <= 0.0 || c.chip_every <= 0.0 || m.length <= 0.0) {
    out.push_back(c);
    return true;
  }
  // At most the shortest revolution's count, before the table of a G96 count is made.
  if (!((revs + m.length / c.chip_rev_length) / c.chip_every <= kMaxChipBreaks)) {
    return false;  // the pieces alone would be gigabytes (found by the fuzzer: S50810, F0.2)
  }
  const RevCount count(m, c);
  const double move_revs = count.total();
  double done = 0.0;  // fraction of the move cut so far
  while (revs + move_revs - count.at(done) >= c.chip_every - 1e-9) {
    const double t = std::min(1.0, count.fraction(count.at(done) + c.chip_every - revs));
    out.push_back(m.piece(done, t));
    if (c.chip_break > 0.0) {
      Command& d = out.emplace_back();
      d.op = Op::dwell;
      d.line = c.line;
      d.file = c.file;
      d.modal = c.modal;
      d.seconds = c.chip_break;
      d.in_revs = true;
    } else {
      const double back_to = count.fraction(std::max(0.0, count.at(t) + c.chip_break));
      out.push_back(m.piece(t, back_to));
      out.push_back(m.piece(back_to, t));
    }
    revs = 0.0;
    done = t;
    if (done >= 1.0) {
      break;
    }
  }
  if (done < 1.0) {
    Command last = m.piece(done, 1.0);
    last.exact_stop = c.exact_stop;
    last.barrier = c.barrier;
    out.push_back(last);
    revs += move_revs - count.at(done);
  } else {
    out.back().barrier = out.back().barrier || c.barrier;
  }
  return true;
}

}  // namespace mcnc::interp::cycles
