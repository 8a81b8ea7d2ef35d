// The look-ahead side of MotionPlanner: blocks in, segments and runs out, the backward pass.
#include "channel/motion/motion_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mcnc::motion {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxRunSegments = 64;  // a run ends well inside the window
constexpr double kMaxFeedOverride = 2.0;
constexpr double kLikeCaps = 0.95;  // runs join segments whose limits differ by < 5 %

}  // namespace

MotionPlanner::MotionPlanner(const MotionConfig& config, const AxisVector& start)
    : config_(config), tail_pos_(start) {
  config_.axis_count = std::min(config_.axis_count, interp::kMaxChannelAxes);
  config_.lookahead_blocks = std::max<std::size_t>(config_.lookahead_blocks, 2);
  if (!config_.jerk_limited) {
    // Trapezoidal: a jerk so high that its phases last far less than a cycle.
    for (std::size_t i = 0; i < config_.axis_count; ++i) {
      config_.axes[i].jerk = config_.axes[i].acceleration / (config_.cycle_s * 1e-6);
    }
  }
  segments_.resize(3 * config_.lookahead_blocks + 8);
  items_.resize(config_.lookahead_blocks + 4);
  out_.sample.pos = start;
}

bool MotionPlanner::accepts() const noexcept {
  return item_count_ + 1 < items_.size() && item_count_ < config_.lookahead_blocks &&
         seg_tail_ - seg_head_ + 3 < segments_.size();
}

PushResult MotionPlanner::push(const interp::Command& c) noexcept {
  using interp::Op;
  if (c.op == Op::spindle) {
    if (c.channel == 0 && c.spindle <= 1) {
      spindle_.css = c.css;
      spindle_.rpm =
          c.css ? 0.0 : (c.spindle_direction == interp::SpindleDirection::stop ? 0.0 : c.rpm);
      spindle_.surface = c.surface;
      spindle_.max_rpm = c.max_rpm;
      switch (c.spindle_direction) {
        case interp::SpindleDirection::cw:
          spindle_.direction = 1;
          break;
        case interp::SpindleDirection::ccw:
          spindle_.direction = -1;
          break;
        case interp::SpindleDirection::stop:
        case interp::SpindleDirection::orient:
          spindle_.direction = 0;
          break;
        case interp::SpindleDirection::keep:
          break;
      }
    }
    return PushResult::accepted;
  }
  if (c.op != Op::rapid && c.op != Op::linear && c.op != Op::arc && c.op != Op::thread &&
      c.op != Op::dwell && c.op != Op::oscillate && c.op != Op::oscillate_end) {
    return PushResult::not_a_motion;
  }
  if (!accepts()) {
    return PushResult::full;
  }
  for (std::size_t i = 0; i < config_.axis_count; ++i) {
    if (!std::isfinite(c.to[i])) {
      return PushResult::bad_target;
    }
  }
  switch (c.op) {
    case Op::rapid:
      return config_.rapid_interpolated ? push_path(c, Feed::rapid) : push_rapid_axes(c);
    case Op::linear:
    case Op::arc:
      return push_path(c, c.feed_mode == interp::FeedMode::per_rev ? Feed::per_rev : Feed::per_min);
    case Op::thread:
      return push_thread(c);
    case Op::dwell:
      return push_dwell(c);
    case Op::oscillate:
    case Op::oscillate_end:
      return push_oscillation(c);
    default:
      return PushResult::not_a_motion;
  }
}

void MotionPlanner::set_segment_limits(Segment& s) const noexcept {
  const std::size_t n = config_.axis_count;
  const PathSegment& g = s.geometry;
  if (!g.is_arc()) {
    std::array<AxisDynamics, interp::kMaxChannelAxes> axes = config_.axes;
    if (s.feed_kind == Feed::rapid) {
      for (std::size_t i = 0; i < n; ++i) {
        axes[i].velocity = config_.rapid_rate[i];
      }
    }
    AxisVector direction{};
    for (std::size_t i = 0; i < n; ++i) {
      direction[i] = g.end()[i] - g.start()[i];
    }
    const JerkLimits l = line_limits(direction, std::span(axes.data(), n), 0.0);
    s.v_geometry = l.velocity;
    s.limits = JerkLimits{kInf, l.acceleration, l.jerk};
    if (!std::isfinite(s.v_geometry)) {  // a move of length 0
      s.v_geometry = 1.0;
      s.limits = JerkLimits{kInf, 1.0, 1.0};
    }
    return;
  }
  // An arc: the acceleration and jerk vectors turn with it, so every moving axis may take all
  // of them: the smallest axis limits bound the path. Tangent T and curvature direction N are
  // orthogonal, so an axis sees at most sqrt(a_t^2 + (v^2 k)^2): the curve takes `share` of
  // the acceleration, the path sqrt(1 - share^2) of it. The jerk is j_t - k^2 v^3 along T,
  // 3 k v a_t along N and k t v^3 across: budgets of J/2, J/5, 0.68 J keep the sum of
  // squares below J^2 (docs/motion.md).
  double v_axes = kInf;
  double a = kInf;
  double j = kInf;
  for (std::size_t i = 0; i < n; ++i) {
    const double share = g.axis_share()[i];
    if (share <= 1e-12) {
      continue;
    }
    v_axes = std::min(v_axes, config_.axes[i].velocity / share);
    a = std::min(a, config_.axes[i].acceleration);
    j = std::min(j, config_.axes[i].jerk);
  }
  if (!std::isfinite(a)) {
    s.v_geometry = 1.0;
    s.limits = JerkLimits{kInf, 1.0, 1.0};
    return;
  }
  const double share = std::clamp(config_.curve_acceleration_share, 0.1, 0.95);
  const double a_t = std::sqrt(1.0 - share * share) * a;
  const double j_t = j / 2.0;
  const double k = g.curvature_norm();
  const double k3 = g.curvature_rate();
  double v = v_axes;
  if (k > 0.0) {
    v = std::min(v, std::sqrt(share * a / k));
    v = std::min(v, 0.68 * j / (3.0 * k * a_t));
    // The chord between two cycle samples sags v^2 t^2 k / 8: at most the path tolerance.
    v = std::min(v, std::sqrt(8.0 * config_.path_tolerance / k) / config_.cycle_s);
  }
  if (k3 > 0.0) {
    v = std::min(v, std::cbrt(j / (5.0 * k3)));
  }
  s.v_geometry = v;
  s.limits = JerkLimits{kInf, a_t, j_t};
}

double MotionPlanner::factor(Feed kind) const noexcept {
  switch (kind) {
    case Feed::per_min:
      return feed_factor_;
    case Feed::per_rev:
      return rev_factor_;
    case Feed::rapid:
      return rapid_factor_;
  }
  return 1.0;
}

double MotionPlanner::cap_of(const Item& it) const noexcept {
  if (it.feed_kind == Feed::rapid) {
    return it.v_geometry * rapid_factor_;
  }
  return std::min(it.v_geometry, it.programmed * factor(it.feed_kind));
}

MotionPlanner::Item& MotionPlanner::new_item(ItemKind kind) noexcept {
  Item& it = item(item_head_ + item_count_);
  it = Item{};
  it.kind = kind;
  it.first = seg_tail_;
  ++item_count_;
  return it;
}

// The junction between two segments that meet at an angle or with a jump in curvature: the
// step it makes in one cycle (velocity v |dT|, acceleration v^2 |dK|) takes at most a share of
// the limits, the blocks on either side give up that share (docs/motion.md).
double MotionPlanner::junction_cap(Segment& prev, Segment& next, bool prev_open) const noexcept {
  const std::size_t n = config_.axis_count;
  // One point per end: its tangent and curvature come together (an arc's sine and cosine once).
  const PathPoint in = prev.geometry.point(prev.geometry.length());
  const PathPoint out = next.geometry.point(0.0);
  AxisVector dt{};
  AxisVector dk{};
  double a = kInf;
  double j = kInf;
  for (std::size_t i = 0; i < n; ++i) {
    dt[i] = out.tangent[i] - in.tangent[i];
    dk[i] = out.curvature[i] - in.curvature[i];
    if (prev.geometry.axis_share()[i] > 1e-12 || next.geometry.axis_share()[i] > 1e-12) {
      a = std::min(a, config_.axes[i].acceleration);
      j = std::min(j, config_.axes[i].jerk);
    }
  }
  const double step_t = vector_norm(dt, n);
  const double step_k = vector_norm(dk, n);
  if (step_t <= 1e-12 && step_k <= 1e-12) {
    return kInf;
  }
  const double cycle = config_.cycle_s;
  const double kink_limit = std::min(0.01, 0.2 * j * cycle / a);
  if (step_t > kink_limit || !prev_open) {
    return 0.0;
  }
  double cap = kInf;
  if (step_t > 1e-12) {
    cap = std::min(cap, 0.5 * a * cycle / step_t);
    prev.limits.acceleration = std::min(prev.limits.acceleration, a / 2.0);
    next.limits.acceleration = std::min(next.limits.acceleration, a / 2.0);
  }
  if (step_k > 1e-12) {
    cap = std::min(cap, std::sqrt(0.4 * j * cycle / step_k));
  }
  prev.limits.jerk = std::min(prev.limits.jerk, j / 2.0);
  next.limits.jerk = std::min(next.limits.jerk, j / 2.0);
  return cap;
}

// G64 between two lines: an arc tangent to both that leaves the corner by at most the path
// tolerance and takes at most half of either line. Appends the blend; returns false for a
// corner that must stop instead (a reversal).
bool MotionPlanner::try_blend(std::size_t prev_index, Segment& next) noexcept {
  Segment& prev = seg(prev_index);
  const std::size_t n = config_.axis_count;
  const AxisVector d1 = prev.geometry.tangent(0.0);
  const AxisVector d2 = next.geometry.tangent(0.0);
  double cos_turn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    cos_turn += d1[i] * d2[i];
  }
  cos_turn = std::clamp(cos_turn, -1.0, 1.0);
  if (cos_turn >= 1.0 - 1e-15) {
    append_segment(next, kInf);  // straight on
    return true;
  }
  if (cos_turn <= -1.0 + 1e-9) {
    return false;
  }
  const double turn = std::acos(cos_turn);
  const double half = (std::numbers::pi - turn) / 2.0;  // half the corner's inner angle
  const double sin_half = std::sin(half);
  double radius = config_.path_tolerance * sin_half / (1.0 - sin_half);
  double setback = radius / std::tan(half);
  // Each blend may take what the blend before left of the line in front of it, and half of
  // the next line (the other half is for the next corner). A sliver left of the line would be
  // a straight piece between two arcs, a curvature step for nothing: the blend takes it too.
  const double prev_left = prev.geometry.length();
  double room = std::min(prev_left, 0.5 * next.full_length);
  if (prev_left - room < 0.01 * prev_left && prev_left <= 0.75 * next.full_length) {
    room = prev_left;
  }
  if (setback > room) {
    setback = room;
    radius = setback * std::tan(half);
  }
  if (!(radius > 1e-9) || !(setback > 1e-12)) {
    return false;
  }
  prev.geometry.trim_line_end(setback);
  item(item_head_ + item_count_ - 1).length -= setback;
  touch(item_head_ + item_count_ - 1);
  next.geometry.trim_line_start(setback);
  Segment blend = next;
  blend.geometry =
      PathSegment::blend(prev.geometry.end(), next.geometry.start(), d1, d2, radius, turn, n);
  blend.block_end = false;
  blend.exact_stop = false;
  set_segment_limits(blend);
  prev.block_end = true;
  // Blends that take all of a short line meet tangentially: the line's remnant goes, so the
  // two arcs join without a curvature step through a point of no length.
  std::size_t before = prev_index;
  const std::size_t last_item = item_head_ + item_count_ - 1;
  Item& tail = item(last_item);
  if (prev.geometry.length() <= 1e-9 && !tail.frozen && prev_index > seg_head_ &&
      seg(prev_index - 1).geometry.is_arc()) {
    bool removed = false;
    if (tail.count > 1) {
      tail.count -= 1;
      tail.length -= prev.geometry.length();
      removed = true;
    } else if (item_count_ >= 2 && item(last_item - 1).kind == ItemKind::path &&
               item(last_item - 1).first + item(last_item - 1).count == prev_index) {
      --item_count_;
      removed = true;
    }
    if (removed) {
      --seg_tail_;
      before = prev_index - 1;
      seg(before).block_end = true;
    }
  }
  Segment& pred = seg(before);
  const bool pred_open = !item(item_head_ + item_count_ - 1).frozen;
  const double in_cap = junction_cap(pred, blend, pred_open);
  append_segment(blend, in_cap);
  Segment& placed = seg(seg_tail_ - 1);
  const double out_cap = junction_cap(placed, next, true);
  // The blend's own limits changed with its junctions: refresh the run that holds it.
  Item& it = item(item_head_ + item_count_ - 1);
  it.limits.acceleration = std::min(it.limits.acceleration, placed.limits.acceleration);
  it.limits.jerk = std::min(it.limits.jerk, placed.limits.jerk);
  append_segment(next, out_cap);
  return true;
}

void MotionPlanner::append_segment(const Segment& s, double cap) noexcept {
  Item* tail = item_count_ > 0 ? &item(item_head_ + item_count_ - 1) : nullptr;
  const bool joins_path =
      tail != nullptr && tail->kind == ItemKind::path && tail->count > 0 && seg_tail_ > seg_head_;
  if (joins_path) {
    Segment& prev = seg(seg_tail_ - 1);
    prev.end_cap = cap;
    tail->limits.acceleration = std::min(tail->limits.acceleration, prev.limits.acceleration);
    tail->limits.jerk = std::min(tail->limits.jerk, prev.limits.jerk);
  }
  const auto reach = [&](double g, double programmed, Feed kind) {
    return kind == Feed::rapid ? g : std::min(g, programmed * kMaxFeedOverride);
  };
  bool merge = false;
  if (joins_path && !tail->frozen && tail->feed_kind == s.feed_kind &&
      tail->count < kMaxRunSegments &&
      std::fabs(tail->programmed - s.programmed) <= 1e-9 * std::max(1.0, s.programmed)) {
    const double run = reach(tail->v_geometry, tail->programmed, tail->feed_kind);
    const double add = reach(s.v_geometry, s.programmed, s.feed_kind);
    merge = cap >= std::min(run, add) && add >= kLikeCaps * run && run >= kLikeCaps * add;
  }
  seg(seg_tail_) = s;
  ++seg_tail_;
  if (merge) {
    tail->count += 1;
    tail->length += s.geometry.length();
    tail->v_geometry = std::min(tail->v_geometry, s.v_geometry);
    tail->limits.acceleration = std::min(tail->limits.acceleration, s.limits.acceleration);
    tail->limits.jerk = std::min(tail->limits.jerk, s.limits.jerk);
  } else {
    Item& it = new_item(ItemKind::path);
    it.first = seg_tail_ - 1;
    it.count = 1;
    it.length = s.geometry.length();
    it.feed_kind = s.feed_kind;
    it.programmed = s.programmed;
    it.v_geometry = s.v_geometry;
    it.limits = s.limits;
    it.start_cap = joins_path ? cap : 0.0;
    it.block = s.block;
    it.line = s.line;
  }
  touch(item_head_ + item_count_ - 1);
}

PushResult MotionPlanner::push_path(const interp::Command& c, Feed feed_kind) noexcept {
  const std::size_t n = config_.axis_count;
  if (feed_kind != Feed::rapid && !(c.feed > 0.0 && std::isfinite(c.feed))) {
    return PushResult::bad_feed;
  }
  Segment s;
  if (c.op == interp::Op::arc) {
    const auto a = static_cast<std::size_t>(c.center_axes[0]);
    const auto b = static_cast<std::size_t>(c.center_axes[1]);
    if (a >= n || b >= n || a == b || !std::isfinite(c.center[0]) || !std::isfinite(c.center[1])) {
      return PushResult::bad_target;
    }
    s.geometry = PathSegment::arc(tail_pos_, c.to, n, a, b, c.center[0], c.center[1],
                                  c.direction == interp::ArcDirection::ccw, c.turns);
    if (!(std::hypot(tail_pos_[a] - c.center[0], tail_pos_[b] - c.center[1]) > 1e-9)) {
      return PushResult::bad_target;
    }
  } else {
    s.geometry = PathSegment::line(tail_pos_, c.to, n);
  }
  if (!(s.geometry.length() > 1e-12)) {
    tail_pos_ = c.to;
    return PushResult::accepted;  // a block that does not move
  }
  s.full_length = s.geometry.length();
  s.block = c.n;
  s.line = c.line;
  s.block_end = true;
  s.exact_stop = c.exact_stop || feed_kind == Feed::rapid || single_block_;
  s.feed_kind = feed_kind;
  s.programmed = feed_kind == Feed::per_min ? c.feed / 60.0 : c.feed;
  if (feed_kind != Feed::rapid && c.feed_without_axis >= 0) {
    // The feed holds along the path the other axes make; the planner runs on the whole path,
    // so the same time there is a proportionally higher speed (the axes' limits still cap it).
    const double counted = s.geometry.length_without(static_cast<std::size_t>(c.feed_without_axis));
    if (counted > 1e-9) {
      s.programmed *= s.geometry.length() / counted;
    }
  }
  s.spindle = spindle_;
  set_segment_limits(s);
  tail_pos_ = c.to;

  Item* tail = item_count_ > 0 ? &item(item_head_ + item_count_ - 1) : nullptr;
  const bool after_path = tail != nullptr && tail->kind == ItemKind::path && seg_tail_ > seg_head_;
  if (!after_path) {
    append_segment(s, 0.0);
    return PushResult::accepted;
  }
  Segment& prev = seg(seg_tail_ - 1);
  const bool open = !tail->frozen;
  if (prev.exact_stop || prev.feed_kind != feed_kind || feed_kind == Feed::rapid) {
    append_segment(s, 0.0);
    return PushResult::accepted;
  }
  if (!prev.geometry.is_arc() && !s.geometry.is_arc() && open) {
    if (!try_blend(seg_tail_ - 1, s)) {
      append_segment(s, 0.0);
    }
    return PushResult::accepted;
  }
  const double cap = junction_cap(prev, s, open);
  append_segment(s, cap);
  return PushResult::accepted;
}

PushResult MotionPlanner::push_thread(const interp::Command& c) noexcept {
  const std::size_t n = config_.axis_count;
  if (!(c.lead > 0.0) || !std::isfinite(c.lead) || !std::isfinite(c.lead_change) ||
      !std::isfinite(c.start_angle)) {
    return PushResult::bad_feed;
  }
  Segment s;
  if (c.thread_arc) {
    const auto a = static_cast<std::size_t>(c.center_axes[0]);
    const auto b = static_cast<std::size_t>(c.center_axes[1]);
    if (a >= n || b >= n || a == b) {
      return PushResult::bad_target;
    }
    s.geometry = PathSegment::arc(tail_pos_, c.to, n, a, b, c.center[0], c.center[1],
                                  c.direction == interp::ArcDirection::ccw, 0);
  } else {
    s.geometry = PathSegment::line(tail_pos_, c.to, n);
  }
  if (!(s.geometry.length() > 1e-12)) {
    return PushResult::bad_target;
  }
  double longest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    longest = std::max(longest, std::fabs(c.to[i] - tail_pos_[i]));
  }
  s.block = c.n;
  s.line = c.line;
  s.block_end = true;
  s.exact_stop = true;
  s.spindle = spindle_;
  set_segment_limits(s);
  // A continuous thread goes on from the one before at speed.
  if (c.continuous && item_count_ > 0) {
    Item& prev = item(item_head_ + item_count_ - 1);
    if (prev.kind == ItemKind::thread && prev.ramp_out) {
      // Under way already: it drops its ramp-out if it has not begun it (step_thread).
      prev.ramp_out = false;
      thread_drop_ramp_out_ = prev.frozen;
    }
  }
  seg(seg_tail_) = s;
  ++seg_tail_;
  Item& it = new_item(ItemKind::thread);
  it.first = seg_tail_ - 1;
  it.count = 1;
  it.length = s.geometry.length();
  it.v_geometry = s.v_geometry;
  it.limits = s.limits;
  it.lead = c.lead * s.geometry.length() / longest;  // along the path
  it.lead_change = c.lead_change * s.geometry.length() / longest;
  it.start_angle = c.start_angle;
  it.thread_rpm = c.rpm;
  it.continuous = c.continuous;
  it.ramp_out = true;
  it.block = c.n;
  it.line = c.line;
  it.spindle = spindle_;
  tail_pos_ = c.to;
  return PushResult::accepted;
}

PushResult MotionPlanner::push_dwell(const interp::Command& c) noexcept {
  if (!(c.seconds >= 0.0) || !std::isfinite(c.seconds)) {
    return PushResult::bad_feed;
  }
  Item& it = new_item(ItemKind::dwell);
  it.count = 0;
  it.dwell = c.seconds;
  it.in_revs = c.in_revs;
  it.block = c.n;
  it.line = c.line;
  it.spindle = spindle_;
  it.to = tail_pos_;
  touch(item_head_ + item_count_ - 1);
  return PushResult::accepted;
}

PushResult MotionPlanner::push_rapid_axes(const interp::Command& c) noexcept {
  Item& it = new_item(ItemKind::rapid_axes);
  it.count = 0;
  it.from = tail_pos_;
  it.to = c.to;
  it.block = c.n;
  it.line = c.line;
  it.spindle = spindle_;
  tail_pos_ = c.to;
  return PushResult::accepted;
}

PushResult MotionPlanner::push_oscillation(const interp::Command& c) noexcept {
  if (c.oscillating < 0 || static_cast<std::size_t>(c.oscillating) >= config_.axis_count) {
    return PushResult::bad_target;
  }
  const bool ending = c.op == interp::Op::oscillate_end;
  if (!ending && (!std::isfinite(c.top) || !std::isfinite(c.bottom) || c.top == c.bottom)) {
    return PushResult::bad_target;
  }
  if (!ending && !(c.feed > 0.0 && std::isfinite(c.feed))) {
    return PushResult::bad_feed;
  }
  Item& it = new_item(ItemKind::oscillation);
  it.count = 0;
  it.axis = static_cast<std::size_t>(c.oscillating);
  it.ending = ending;
  it.top = c.top;
  it.bottom = c.bottom;
  it.programmed = c.feed / 60.0;  // units/min, whatever the feed mode (L2484)
  it.block = c.n;
  it.line = c.line;
  it.spindle = spindle_;
  if (ending) {
    tail_pos_[it.axis] = c.to[it.axis];  // the path goes on from where G80.1 leaves the axis
  }
  it.to = tail_pos_;
  touch(item_head_ + item_count_ - 1);
  return PushResult::accepted;
}

double MotionPlanner::end_target(std::size_t index) const noexcept {
  const std::size_t last = item_head_ + item_count_;
  if (index + 1 >= last) {
    return 0.0;  // the end of the window: stop there
  }
  const Item& next = item(index + 1);
  return next.kind == ItemKind::path ? std::min(next.vb, next.start_cap) : 0.0;
}

bool MotionPlanner::window_end_binds() noexcept {
  update_lookahead();
  const std::size_t last = item_head_ + item_count_;
  // From the run after `from`: a chain of runs each slowed down to brake for the next is held
  // by the window's end when it reaches it, and by what the program asks for when it ends at a
  // run at its own limit, at a junction's cap or at a stop.
  const auto held_by_end = [&](std::size_t from) {
    for (std::size_t j = from + 1;; ++j) {
      if (j >= last) {
        return true;
      }
      const Item& it = item(j);
      if (it.kind != ItemKind::path || it.vb >= std::min(cap_of(it), it.start_cap) * (1.0 - 1e-9)) {
        return false;
      }
      if (j + 1 < last &&
          (item(j + 1).kind != ItemKind::path || item(j + 1).start_cap <= item(j + 1).vb)) {
        return false;
      }
    }
  };
  if (item_count_ == 0) {
    return true;
  }
  // Every run the next cycle may start: the one under way, and those after it within twice a
  // cycle's travel at the highest speed among them (short runs pass several in one cycle).
  double ahead = active_ ? -s_ : 0.0;
  double fastest = v_;
  for (std::size_t i = item_head_; i < last; ++i) {
    if (held_by_end(i)) {
      return true;
    }
    const Item& it = item(i);
    if (it.kind != ItemKind::path) {
      return false;
    }
    ahead += it.length;
    fastest = std::max(fastest, cap_of(it));
    if (ahead > 2.0 * fastest * config_.cycle_s) {
      return false;
    }
  }
  return false;
}

void MotionPlanner::touch(std::size_t index) noexcept {
  first_changed_ = std::min(first_changed_, index);
  backward_pending_ = true;
}

// Backward pass from the last run toward the head: each run's highest start speed such that it
// can still slow down to what the next allows. Runs at or after the first one changed since the
// last pass are all recomputed; before them it stops where a speed no longer changes (unless
// `all`: after an override change every run's limit moved).
void MotionPlanner::backward_pass(bool all) noexcept {
  backward_pending_ = false;
  if (item_count_ == 0) {
    first_changed_ = kNoneChanged;
    return;
  }
  const std::size_t first = item_head_ + (active_ ? 1 : 0);
  const std::size_t last = item_head_ + item_count_ - 1;
  for (std::size_t i = last + 1; i-- > first;) {
    Item& it = item(i);
    double vb = 0.0;
    if (it.kind == ItemKind::path) {
      const double cap = cap_of(it);
      const JerkLimits l{std::max(cap, 1e-12), it.limits.acceleration, it.limits.jerk};
      vb = std::min({cap, it.start_cap, max_speed_within(it.length, end_target(i), l)});
    }
    // Appending gives the runs before more room, never less: where a run's speed no longer
    // changes (to rounding), nothing before it does.
    if (!all && i < first_changed_ && std::fabs(vb - it.vb) <= 1e-12 * (1.0 + vb)) {
      break;
    }
    it.vb = vb;
  }
  first_changed_ = kNoneChanged;
}

}  // namespace mcnc::motion
