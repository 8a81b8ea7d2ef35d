#include "channel/interp/normal_direction.hpp"

#include "channel/interp/path/plane_geometry.hpp"

#include <cmath>
#include <optional>

namespace mcnc::interp {

namespace {

constexpr double kDegrees = 180.0 / path::kPi;

struct InPlane {
  path::Point2 from;
  path::PlaneMove move;
};

// The move `c` from `from` in the plane of its normal control.
InPlane in_plane(const Command& c, const AxisVector& from) {
  const auto a = static_cast<std::size_t>(c.normal_plane[0]);
  const auto b = static_cast<std::size_t>(c.normal_plane[1]);
  InPlane p;
  p.from = {from[a], from[b]};
  p.move.kind = c.op == Op::arc ? path::MoveKind::arc : path::MoveKind::feed;
  p.move.to = {c.to[a], c.to[b]};
  p.move.center = {c.center[0], c.center[1]};
  p.move.ccw = c.direction == ArcDirection::ccw;
  return p;
}

// The direction (degrees) in which the move starts; none when it does not travel in the plane.
std::optional<double> start_degrees(const InPlane& p) {
  const bool arc = p.move.kind == path::MoveKind::arc;
  const double travel = arc ? path::arc_radius(p.from, p.move) : path::length(p.move.to - p.from);
  if (travel < path::kLengthEpsilon) {
    return std::nullopt;
  }
  const path::Point2 d = path::start_direction(p.from, p.move);
  return std::atan2(d.b, d.a) * kDegrees;
}

// `angle` moved by the multiple of 360 that brings it nearest `from`: the shorter turn.
double nearest_turn(double from, double angle) {
  return from + std::remainder(angle - from, 360.0);
}

}  // namespace

void NormalDirection::reset(const AxisVector& position) {
  at_ = position;
  if (settings_.axis >= 0) {
    angle_ = position[static_cast<std::size_t>(settings_.axis)];
  }
}

Command NormalDirection::turn_before(const Command& move, double to_angle) const {
  // The axis alone: none of the move's other requests (skip, exact stop, chip breaking).
  Command r;
  r.op = Op::linear;
  r.line = move.line;
  r.file = move.file;
  r.block_text = move.block_text;
  r.modal = move.modal;
  r.to = at_;
  r.to[static_cast<std::size_t>(settings_.axis)] = to_angle;
  r.feed = settings_.feed;
  r.feed_mode = FeedMode::per_min;
  return r;
}

void NormalDirection::turn(std::vector<Command>& list, std::size_t from) {
  if (settings_.axis < 0) {
    return;  // nothing to turn, and no position needed for it
  }
  const auto rot = static_cast<std::size_t>(settings_.axis);
  for (std::size_t k = from; k < list.size(); ++k) {
    if (!list[k].moves()) {
      continue;
    }
    Command& c = list[k];
    if (c.normal == Command::Normal::off) {
      angle_ = c.to[rot];
      at_ = c.to;
      continue;
    }
    if (c.normal == Command::Normal::hold || (c.op != Op::linear && c.op != Op::arc)) {
      c.to[rot] = angle_;
      at_ = c.to;
      continue;
    }
    const InPlane p = in_plane(c, at_);
    const std::optional<double> dir = start_degrees(p);
    if (dir) {
      const double side = c.normal == Command::Normal::left ? 90.0 : -90.0;
      const double want = nearest_turn(angle_, *dir + side);
      if (std::fabs(want - angle_) > kFoldedTurn) {
        Command r = turn_before(c, want);
        list.insert(list.begin() + static_cast<std::ptrdiff_t>(k), std::move(r));
        ++k;  // `c` moved one place on
      }
      angle_ = want;
      if (p.move.kind == path::MoveKind::arc) {
        // The axis turns with the arc: its sweep and its full turns.
        double sweep = path::arc_sweep(p.from, p.move);
        sweep += (sweep < 0.0 ? -1.0 : 1.0) * 2.0 * path::kPi * list[k].turns;
        angle_ += sweep * kDegrees;
        list[k].feed_without_axis = settings_.axis;  // F is the feed along the arc in the plane
      }
    }
    list[k].to[rot] = angle_;
    at_ = list[k].to;
  }
}

}  // namespace mcnc::interp
