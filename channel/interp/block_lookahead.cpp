#include "channel/interp/block_lookahead.hpp"

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <climits>
#include <string>

namespace mcnc::interp {

namespace {

path::PathError with_line(path::PathError e, int line) {
  e.text += " (the move of line " + std::to_string(line) + ")";
  return e;
}

}  // namespace

void BlockLookahead::reset(const AxisVector& position) {
  corner_position_ = position;
  comp_position_ = position;
  corner_held_.reset();
  compensation_ = path::NoseCompensation{};
  mode_ = Command::Compensation::off;
  entries_.clear();
}

void BlockLookahead::set_plane(std::array<int, 2> axes, Plane plane) {
  axes_ = axes;
  plane_ = plane;
}

bool BlockLookahead::holds_normal_direction() const {
  auto turned = [](const Command& c) {
    return c.normal == Command::Normal::left || c.normal == Command::Normal::right;
  };
  auto any_turned = [&](const std::vector<Command>& list) {
    for (const Command& c : list) {
      if (turned(c)) {
        return true;
      }
    }
    return false;
  };
  if (corner_held_ && (turned(corner_held_->move) || any_turned(corner_held_->after))) {
    return true;
  }
  for (const Entry& e : entries_) {
    if (turned(e.move) || any_turned(e.generated) || any_turned(e.after)) {
      return true;
    }
  }
  return false;
}

path::Point2 BlockLookahead::plane_point(const AxisVector& v) const {
  return {v[static_cast<std::size_t>(axes_[0])], v[static_cast<std::size_t>(axes_[1])]};
}

bool BlockLookahead::is_motion(Op op) {
  return op == Op::rapid || op == Op::linear || op == Op::arc || op == Op::thread;
}

path::PathResult BlockLookahead::push(Command c, std::vector<Command>& ready) {
  if (c.barrier && corner_held_) {
    return path::PathError{alarm::kCornerDoesNotFit,
                           "the corner (,C/,R) of line " + std::to_string(corner_held_->move.line) +
                               " needs the next move, but this block stops the read-ahead",
                           -1};
  }
  return corner_stage(std::move(c), ready);
}

path::PathResult BlockLookahead::flush(std::vector<Command>& ready) {
  if (corner_held_) {
    return path::PathError{alarm::kCornerDoesNotFit,
                           "the corner (,C/,R) of line " + std::to_string(corner_held_->move.line) +
                               " has no move after it",
                           -1};
  }
  return end_compensation(nullptr, ready);
}

namespace {

path::PlaneMove plane_move_of(const Command& c, path::Point2 to) {
  path::PlaneMove m;
  switch (c.op) {
    case Op::rapid:
      m.kind = path::MoveKind::rapid;
      break;
    case Op::arc:
      m.kind = path::MoveKind::arc;
      m.ccw = c.direction == ArcDirection::ccw;
      m.center = {c.center[0], c.center[1]};
      break;
    case Op::thread:
      m.kind = path::MoveKind::thread;
      break;
    default:
      m.kind = path::MoveKind::feed;
      break;
  }
  m.to = to;
  m.feed = c.feed;
  m.lead = c.lead;
  return m;
}

}  // namespace

path::PathResult BlockLookahead::corner_stage(Command c, std::vector<Command>& ready) {
  if (!is_motion(c.op)) {
    if (corner_held_) {
      corner_held_->after.push_back(std::move(c));
      return std::nullopt;
    }
    return compensation_stage(std::move(c), ready);
  }
  const path::Point2 from = plane_point(corner_position_);
  corner_position_ = c.to;
  if (corner_held_) {
    CornerHeld held = std::move(*corner_held_);
    corner_held_.reset();
    if (c.op != Op::linear && c.op != Op::arc) {
      return path::PathError{alarm::kCornerDoesNotFit,
                             "the corner (,C/,R) of line " + std::to_string(held.move.line) +
                                 " needs a G01/G02/G03 move after it",
                             -1};
    }
    path::PlaneMove first = plane_move_of(held.move, plane_point(held.move.to));
    path::PlaneMove second = plane_move_of(c, plane_point(c.to));
    const path::CornerKind kind =
        held.move.corner == Command::Corner::round            ? path::CornerKind::round
        : held.move.corner == Command::Corner::chamfer_length ? path::CornerKind::chamfer_length
                                                              : path::CornerKind::chamfer_setback;
    const double feed = held.move.corner_feed > 0.0 ? held.move.corner_feed : held.move.feed;
    path::CornerResult corner;
    if (path::PathResult e = path::insert_corner(held.from, first, second, kind,
                                                 held.move.corner_size, feed, corner)) {
      return with_line(*e, held.move.line);
    }
    held.move.corner = Command::Corner::none;
    held.move.to[static_cast<std::size_t>(axes_[0])] = first.to.a;
    held.move.to[static_cast<std::size_t>(axes_[1])] = first.to.b;
    const Command original = held.move;
    if (path::PathResult e = compensation_stage(std::move(held.move), ready)) {
      return e;
    }
    if (corner.inserted) {
      Command k = command_of(original, corner.corner);
      k.feed = corner.corner.feed > 0.0 ? corner.corner.feed : feed;
      if (path::PathResult e = compensation_stage(std::move(k), ready)) {
        return e;
      }
    }
    for (Command& a : held.after) {
      if (path::PathResult e = compensation_stage(std::move(a), ready)) {
        return e;
      }
    }
  }
  if (c.corner != Command::Corner::none && (c.op == Op::linear || c.op == Op::arc)) {
    corner_held_ = CornerHeld{std::move(c), from, {}};
    return std::nullopt;
  }
  return compensation_stage(std::move(c), ready);
}

path::PathResult BlockLookahead::compensation_stage(Command c, std::vector<Command>& ready) {
  if (!is_motion(c.op)) {
    if (c.barrier && compensation_.active()) {
      // The read-ahead stops here: the waiting move ends with its offset normal to it, and
      // compensation goes on from there after the barrier (spec dafeng §4.3).
      path::PlanePath out;
      compensation_.flush(out);
      take(out);
      release_before(INT_MAX, ready);
    }
    if (!entries_.empty()) {
      entries_.back().after.push_back(std::move(c));
    } else {
      ready.push_back(std::move(c));
    }
    return std::nullopt;
  }
  const path::Point2 from = plane_point(comp_position_);
  comp_position_ = c.to;
  const bool wanted = c.compensation != Command::Compensation::off;
  if (c.barrier || c.op == Op::thread) {
    // G53 and threads are not compensated: the compensation ends before them and starts again
    // with the next compensated move.
    if (path::PathResult e = end_compensation(nullptr, ready)) {
      return e;
    }
    ready.push_back(std::move(c));
    return std::nullopt;
  }
  if (compensation_.active()) {
    if (!wanted) {
      return end_compensation(&c, ready, from);
    }
    if (c.compensation != mode_ || c.nose_radius != radius_ || c.nose_tip != tip_) {
      // Another side or another offset: end the old compensation, start the new one here.
      if (path::PathResult e = end_compensation(nullptr, ready)) {
        return e;
      }
    }
  }
  if (!compensation_.active()) {
    const path::Point2 to = plane_point(c.to);
    if (!wanted || path::same_point(from, to)) {
      ready.push_back(std::move(c));
      return std::nullopt;
    }
    if (c.op == Op::arc) {
      return path::PathError{alarm::kCompensationStart,
                             "tool-nose compensation cannot start on an arc: give a G01 move "
                             "after G41/G42 (line " +
                                 std::to_string(c.line) + ")",
                             -1};
    }
    if (c.op == Op::rapid && !settings_.rapid_startup) {
      ready.push_back(std::move(c));  // spec L3745: G00 start-up blocks are not compensated
      return std::nullopt;
    }
    mode_ = c.compensation;
    radius_ = c.nose_radius;
    tip_ = c.nose_tip;
    compensation_.start(from,
                        mode_ == Command::Compensation::left ? path::CompensationSide::left
                                                             : path::CompensationSide::right,
                        radius_, tip_);
  }
  Entry e;
  e.id = next_id_++;
  path::PlaneMove m = plane_move_of(c, plane_point(c.to));
  m.source = e.id;
  const int line = c.line;
  e.move = std::move(c);
  entries_.push_back(std::move(e));
  path::PlanePath out;
  if (path::PathResult err = compensation_.push(m, out)) {
    return with_line(*err, line);
  }
  take(out);
  release_before(entries_.back().id, ready);
  return std::nullopt;
}

path::PathResult BlockLookahead::end_compensation(const Command* cancel_move,
                                                  std::vector<Command>& ready, path::Point2 from) {
  (void)from;
  path::PlanePath out;
  if (!compensation_.active()) {
    release_before(INT_MAX, ready);
    if (cancel_move != nullptr) {
      ready.push_back(*cancel_move);
    }
    return std::nullopt;
  }
  path::PlaneMove m;
  if (cancel_move != nullptr) {
    Entry e;
    e.id = next_id_++;
    e.move = *cancel_move;
    m = plane_move_of(*cancel_move, plane_point(cancel_move->to));
    m.source = e.id;
    entries_.push_back(std::move(e));
  }
  const path::PathResult r = compensation_.cancel(cancel_move != nullptr ? &m : nullptr, out);
  mode_ = Command::Compensation::off;
  if (r) {
    return with_line(*r, cancel_move != nullptr ? cancel_move->line : 0);
  }
  take(out);
  release_before(INT_MAX, ready);
  return std::nullopt;
}

void BlockLookahead::take(const path::PlanePath& moves) {
  for (const path::PlaneMove& m : moves) {
    Entry* owner = entries_.empty() ? nullptr : &entries_.front();
    for (Entry& e : entries_) {
      owner = e.id == m.source ? &e : owner;
    }
    if (owner != nullptr) {
      owner->generated.push_back(command_of(owner->move, m));
    }
  }
}

void BlockLookahead::release_before(int id, std::vector<Command>& ready) {
  while (!entries_.empty() && entries_.front().id < id) {
    Entry& e = entries_.front();
    for (Command& g : e.generated) {
      ready.push_back(std::move(g));
    }
    for (Command& a : e.after) {
      ready.push_back(std::move(a));
    }
    entries_.pop_front();
  }
}

Command BlockLookahead::command_of(const Command& source, const path::PlaneMove& m) const {
  Command c = source;
  c.corner = Command::Corner::none;
  switch (m.kind) {
    case path::MoveKind::rapid:
      c.op = Op::rapid;
      break;
    case path::MoveKind::arc:
      c.op = Op::arc;
      c.plane = plane_;
      c.center_axes = axes_;
      c.center = {m.center.a, m.center.b};
      c.direction = m.ccw ? ArcDirection::ccw : ArcDirection::cw;
      c.turns = 0;
      break;
    case path::MoveKind::thread:
      c.op = Op::thread;
      break;
    default:
      c.op = Op::linear;
      break;
  }
  c.to[static_cast<std::size_t>(axes_[0])] = m.to.a;
  c.to[static_cast<std::size_t>(axes_[1])] = m.to.b;
  if (m.feed > 0.0 && c.op != Op::rapid) {
    c.feed = m.feed;
  }
  return c;
}

}  // namespace mcnc::interp
