// The interpolator side of MotionPlanner: one setpoint per cycle from the queued runs, dwells,
// threads and axis-wise rapids; feed hold, override, single block and reset.
#include "channel/motion/motion_planner.hpp"

#include "channel/motion/spindle_speed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mcnc::motion {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTiny = 1e-12;

}  // namespace

ProfileSample MotionPlanner::Piece::at(double t) const noexcept {
  if (t < prefix.duration() || stop_only) {
    return prefix.at(t);
  }
  const ProfileSample head = prefix.end();
  const ProfileSample p = profile.at(t - prefix.duration());
  return ProfileSample{head.s + p.s, p.v, p.a};
}

void MotionPlanner::restart(const AxisVector& at, bool keep_oscillations) noexcept {
  AxisVector tail = at;
  if (!keep_oscillations) {
    oscillations_.fill(AxisOscillation{});
    out_.oscillating = 0;
  }
  for (std::size_t k = 0; k < config_.axis_count; ++k) {
    // The path keeps an oscillating axis where G81.1 found it, not where its stroke is now.
    tail[k] = oscillations_[k].active() ? tail_pos_[k] : tail[k];
  }
  resetting_ = false;
  stopping_ = false;
  held_ = false;
  block_stopped_ = false;
  reset_requested_ = false;
  resume_requested_ = false;
  item_head_ += item_count_;
  item_count_ = 0;
  seg_head_ = seg_tail_;
  active_ = false;
  thread_chain_ = false;
  thread_drop_ramp_out_ = false;
  first_changed_ = kNoneChanged;
  backward_pending_ = false;
  tail_pos_ = tail;
  rapid_stopping_ = false;
  write_rest(at);
  out_.state = MotionState::idle;
  out_.fault = MotionFault::none;
  out_.block = 0;
  out_.line = 0;
  out_.completed_block = 0;
}

void MotionPlanner::set_single_block(bool on) noexcept {
  if (on != single_block_) {
    single_block_ = on;
    replan_needed_ = true;
  }
}

double MotionPlanner::spindle_rpm_at(const SpindleCommand& s,
                                     const AxisVector& pos) const noexcept {
  if (!s.css) {
    return s.rpm * in_.spindle_override;
  }
  if (config_.css_axis < 0 || static_cast<std::size_t>(config_.css_axis) >= config_.axis_count) {
    return 0.0;
  }
  return constant_surface_rpm(s.surface * in_.spindle_override,
                              pos[static_cast<std::size_t>(config_.css_axis)] - config_.css_centre,
                              s.max_rpm, config_.spindle_max_rpm);
}

void MotionPlanner::write_rest(const AxisVector& pos) noexcept {
  out_.sample.pos = pos;
  out_.sample.vel = AxisVector{};
  out_.sample.acc = AxisVector{};
  out_.path_velocity = 0.0;
  v_ = 0.0;
  a_ = 0.0;
}

// The first block end after run-local `from` inside the run under way, or the run's length.
double MotionPlanner::next_block_end(double from) const noexcept {
  const Item& it = item(item_head_);
  double base = 0.0;
  for (std::size_t k = 0; k < it.count; ++k) {
    const Segment& s = seg(it.first + k);
    base += s.geometry.length();
    if (s.block_end && base > from + 1e-9) {
      return std::min(base, it.length);
    }
  }
  return it.length;
}

bool MotionPlanner::plan_run(double v, double a, bool may_end_faster) noexcept {
  const Item& it = item(item_head_);
  const double cap = cap_of(it);
  if (!(cap > kTiny)) {
    start_stop(1.0);  // a 0 % override holds the feed
    return true;
  }
  const JerkLimits lim{cap, it.limits.acceleration, it.limits.jerk};
  double target = it.length;
  double v_end = end_target(item_head_);
  if (single_block_) {
    target = next_block_end(s_);
    v_end = 0.0;
  }
  v_end = std::min(v_end, cap);
  JerkPhases prefix(ProfileSample{0.0, v, 0.0});
  if (std::fabs(a) > kTiny) {
    prefix = speed_transition(v, a, released_velocity(v, a, lim.jerk), lim);
  }
  const double v1 = prefix.end().v;
  const double rest = target - s_ - prefix.end().s;
  if (rest < -1e-12 || v1 < -1e-9) {
    return false;
  }
  const double distance = std::max(0.0, rest);
  if (v_end > v1) {
    v_end = std::min(v_end, max_speed_within(distance, v1, lim));
  }
  JerkLimitedProfile profile;
  ProfileResult r = JerkLimitedProfile::plan(distance, std::max(0.0, v1), v_end, lim, profile);
  if (r == ProfileResult::unreachable && may_end_faster && !single_block_ && target >= it.length) {
    // Arrived too fast for a lowered override: end the run as slow as the distance allows.
    double low = v_end;
    double high = std::max(v1, v_end);
    for (int i = 0; i < 60; ++i) {
      const double mid = (low + high) / 2.0;
      JerkLimitedProfile trial;
      const JerkLimits wide{std::max(cap, mid), lim.acceleration, lim.jerk};
      if (JerkLimitedProfile::plan(distance, std::max(0.0, v1), mid, wide, trial) ==
          ProfileResult::ok) {
        high = mid;
        profile = trial;
      } else {
        low = mid;
      }
    }
    JerkLimitedProfile check;
    const JerkLimits wide{std::max(cap, high), lim.acceleration, lim.jerk};
    r = JerkLimitedProfile::plan(distance, std::max(0.0, v1), high, wide, check);
    profile = check;
    v_end = high;
  }
  if (r != ProfileResult::ok) {
    return false;
  }
  piece_ = Piece{};
  piece_.prefix = prefix;
  piece_.profile = profile;
  piece_.origin = s_;
  piece_.target = target;
  t_ = 0.0;
  planned_end_v_ = v_end;
  return true;
}

// A feed hold's or reset's stop on the path, run by run so that each run's own limits hold:
// the quickest stop with this run's limits if it ends inside the run; otherwise the run goes
// on to its end as slowly as its limits allow (never faster than the plan, which respected
// every corner and exact stop), and at that knot, where the acceleration is zero, the stop
// starts over with the next run's limits.
void MotionPlanner::start_stop(double scale) noexcept {
  stopping_ = true;
  stop_scale_ = scale;
  const Item& head = item(item_head_);
  const JerkLimits own{kInf, head.limits.acceleration * scale, head.limits.jerk * scale};
  const JerkPhases stop = speed_transition(v_, a_, 0.0, own);
  if (stop.end().s <= head.length - s_ || head.kind != ItemKind::path) {
    piece_ = Piece{};
    piece_.prefix = stop;
    piece_.stop_only = true;
    piece_.origin = s_;
    t_ = 0.0;
    return;
  }
  // To the end of the run as slowly as it can: the lowest end speed its length allows.
  JerkPhases prefix(ProfileSample{0.0, v_, 0.0});
  if (std::fabs(a_) > kTiny) {
    prefix = speed_transition(v_, a_, released_velocity(v_, a_, own.jerk), own);
  }
  const double v1 = std::max(0.0, prefix.end().v);
  const double distance = std::max(0.0, head.length - s_ - prefix.end().s);
  double low = 0.0;
  double high = std::max(v1, 1e-12);
  JerkLimitedProfile best;
  bool found = false;
  for (int k = 0; k < 60; ++k) {
    const double mid = k == 0 ? 0.0 : (low + high) / 2.0;
    JerkLimitedProfile trial;
    const JerkLimits l{std::max(v1, mid), own.acceleration, own.jerk};
    if (JerkLimitedProfile::plan(distance, v1, mid, l, trial) == ProfileResult::ok) {
      best = trial;
      found = true;
      high = mid;
      if (k == 0) {
        break;
      }
    } else {
      low = mid;
    }
  }
  const double slowest = found ? best.at(best.duration()).v : kInf;
  const bool plan_to_end = !piece_.stop_only && piece_.target >= head.length - 1e-12;
  if (!found || (plan_to_end && planned_end_v_ <= slowest)) {
    // The plan under way (already braking, say) ends the run at least as slowly: keep it.
    return;
  }
  piece_ = Piece{};
  piece_.prefix = prefix;
  piece_.profile = best;
  piece_.origin = s_;
  piece_.target = head.length;
  planned_end_v_ = slowest;
  t_ = 0.0;
}

// Moves to the next queued item; the run-local position restarts at 0.
void MotionPlanner::finish_item() noexcept {
  if (item_count_ == 0) {
    return;
  }
  const Item& it = item(item_head_);
  if (it.count > 0) {
    // A run may end inside a block (a blend belongs to the block after the corner): the blocks
    // before it are done, that block only at its own end.
    const Segment& last = seg(it.first + it.count - 1);
    out_.completed_block =
        std::max(out_.completed_block, last.block_end ? last.block : last.block - 1);
    seg_head_ = it.first + it.count;
  } else {
    out_.completed_block = std::max(out_.completed_block, it.block);
  }
  ++item_head_;
  --item_count_;
  active_ = false;
  s_ = 0.0;
  seg_base_ = 0.0;
  t_ = 0.0;
}

void MotionPlanner::write_path_sample(const ProfileSample& p) noexcept {
  s_ = p.s;
  v_ = p.v;
  a_ = p.a;
  // A stop may run past the end of the run under way into the next ones.
  while (item_count_ > 1 && s_ > item(item_head_).length + 1e-12 &&
         item(item_head_ + 1).kind == ItemKind::path) {
    const double length = item(item_head_).length;
    piece_.origin -= length;
    const double keep_s = s_ - length;
    const double keep_t = t_;  // the stop goes on where it is, not from its start
    finish_item();
    t_ = keep_t;
    item(item_head_).frozen = true;
    active_ = true;
    cur_seg_ = item(item_head_).first;
    s_ = keep_s;
  }
  Item& it = item(item_head_);
  s_ = std::clamp(s_, 0.0, it.length);
  const std::size_t last = it.first + it.count - 1;
  while (cur_seg_ < last && s_ >= seg_base_ + seg(cur_seg_).geometry.length()) {
    const Segment& done = seg(cur_seg_);
    if (done.block_end) {
      out_.completed_block = std::max(out_.completed_block, done.block);
    }
    seg_base_ += done.geometry.length();
    ++cur_seg_;
  }
  const Segment& s = seg(cur_seg_);
  const double local = s_ - seg_base_;
  const PathSegment& g = s.geometry;
  const PathPoint at = g.point(local);
  for (std::size_t i = 0; i < config_.axis_count; ++i) {
    out_.sample.pos[i] = at.pos[i];
    out_.sample.vel[i] = at.tangent[i] * v_;
    out_.sample.acc[i] = at.tangent[i] * a_ + at.curvature[i] * v_ * v_;
  }
  out_.path_velocity = v_;
  out_.block = s.block;
  out_.line = s.line;
  out_.css = s.spindle.css;
  // FANUC practice: G96 during a rapid computes the speed for the rapid's end point.
  out_.spindle_rpm =
      spindle_rpm_at(s.spindle, s.feed_kind == Feed::rapid ? g.end() : out_.sample.pos);
  out_.spindle_direction = s.spindle.direction;
}

void MotionPlanner::maybe_replan() noexcept {
  if (stopping_ || held_ || block_stopped_ || !active_) {
    return;
  }
  const Item& it = item(item_head_);
  const double cap = cap_of(it);
  const bool slower = v_ > cap * (1.0 + 1e-9);
  const bool wider = !single_block_ && piece_.target >= it.length &&
                     end_target(item_head_) > planned_end_v_ * (1.0 + 1e-9) + 1e-9;
  if (!(replan_needed_ || wider)) {
    return;
  }
  // Replan only where releasing the acceleration costs nothing: cruising, or speeding up when
  // the new limit is lower. While braking, the plan under way already slows down.
  if (a_ < -1e-9 || (a_ > 1e-9 && !slower)) {
    return;
  }
  const Piece keep = piece_;
  const double keep_t = t_;
  const double keep_end = planned_end_v_;
  if (plan_run(v_, a_, false)) {
    replan_needed_ = false;
  } else {
    piece_ = keep;
    t_ = keep_t;
    planned_end_v_ = keep_end;
  }
}

void MotionPlanner::step_path(double dt) noexcept {
  if (!active_) {
    Item& it = item(item_head_);
    it.frozen = true;
    active_ = true;
    cur_seg_ = it.first;
    seg_base_ = 0.0;
    s_ = 0.0;
    if (!plan_run(v_, 0.0, true)) {
      out_.fault = MotionFault::unplannable;
      out_.state = MotionState::fault;
      return;
    }
  } else {
    maybe_replan();
  }
  if (held_ || block_stopped_) {
    out_.state = held_ ? MotionState::held : MotionState::block_stop;
    write_path_sample(ProfileSample{s_, 0.0, 0.0});
    return;
  }
  t_ += dt;
  for (int guard = 0; guard < 1000; ++guard) {
    if (t_ < piece_.duration()) {
      break;
    }
    if (piece_.stop_only) {
      const ProfileSample end = piece_.prefix.end();
      write_path_sample(ProfileSample{piece_.origin + end.s, 0.0, 0.0});
      stopping_ = false;
      if (resetting_) {
        return;  // the caller clears the queue
      }
      held_ = true;
      out_.state = MotionState::held;
      return;
    }
    const double leftover = t_ - piece_.duration();
    const double v_end = planned_end_v_;
    const Item& it = item(item_head_);
    if (piece_.target < it.length - 1e-12) {
      // Single block: at rest at a block end inside the run.
      write_path_sample(ProfileSample{piece_.target, 0.0, 0.0});
      block_stopped_ = true;
      out_.state = MotionState::block_stop;
      return;
    }
    write_path_sample(ProfileSample{it.length, v_end, 0.0});
    const bool stop_here = single_block_ && seg(it.first + it.count - 1).block_end;
    finish_item();
    v_ = v_end;
    if (item_count_ == 0 || item(item_head_).kind != ItemKind::path || v_end <= kTiny) {
      v_ = 0.0;
      if (stop_here && item_count_ > 0) {
        block_stopped_ = true;
      }
      if (stopping_) {
        stopping_ = false;  // the stop ended at a knot: held there (or reset)
        held_ = !resetting_ && item_count_ > 0;
      }
      out_.state = item_count_ == 0 ? MotionState::idle : MotionState::moving;
      out_.sample.vel = AxisVector{};
      out_.sample.acc = AxisVector{};
      out_.path_velocity = 0.0;
      return;
    }
    Item& next = item(item_head_);
    next.frozen = true;
    active_ = true;
    cur_seg_ = next.first;
    seg_base_ = 0.0;
    s_ = 0.0;
    if (stopping_) {
      a_ = 0.0;
      start_stop(stop_scale_);  // a knot: the stop goes on with this run's limits
      t_ = leftover;
      continue;
    }
    if (!plan_run(v_end, 0.0, true)) {
      out_.fault = MotionFault::unplannable;
      out_.state = MotionState::fault;
      return;
    }
    t_ = leftover;
  }
  const ProfileSample p = piece_.at(t_);
  write_path_sample(ProfileSample{piece_.origin + p.s, p.v, p.a});
  out_.state = stopping_ ? MotionState::stopping : MotionState::moving;
}

void MotionPlanner::step_dwell(double dt) noexcept {
  Item& it = item(item_head_);
  if (!active_) {
    active_ = true;
    it.frozen = true;
    dwell_left_ = it.dwell;
    dwell_angle_ = in_.spindle_angle;
    dwell_last_angle_ = in_.spindle_angle;
  }
  write_rest(it.to);
  out_.block = it.block;
  out_.line = it.line;
  out_.css = it.spindle.css;
  out_.spindle_rpm = spindle_rpm_at(it.spindle, it.to);
  out_.spindle_direction = it.spindle.direction;
  out_.state = MotionState::dwelling;
  bool done = false;
  if (it.in_revs) {
    if (in_.feed_hold) {
      dwell_angle_ += in_.spindle_angle - dwell_last_angle_;  // held turns do not count
    }
    dwell_last_angle_ = in_.spindle_angle;
    done = std::fabs(in_.spindle_angle - dwell_angle_) >= 360.0 * it.dwell - 1e-9;
  } else {
    if (!in_.feed_hold) {
      dwell_left_ -= dt;
    }
    done = dwell_left_ <= dt * 1e-6;
  }
  if (done) {
    finish_item();
    out_.state = item_count_ == 0 ? MotionState::idle : MotionState::moving;
  }
}

// Plans every axis of an axis-wise rapid from rest where it stands to the rapid's end.
bool MotionPlanner::plan_rapid_axes(const Item& it) noexcept {
  t_ = 0.0;
  for (std::size_t i = 0; i < config_.axis_count; ++i) {
    const double d = it.to[i] - out_.sample.pos[i];
    axis_start_[i] = out_.sample.pos[i];
    axis_sign_[i] = d < 0.0 ? -1.0 : 1.0;
    const JerkLimits l{config_.rapid_rate[i] * std::max(rapid_factor_, 1e-3),
                       config_.axes[i].acceleration, config_.axes[i].jerk};
    if (JerkLimitedProfile::plan(std::fabs(d), 0.0, 0.0, l, axis_profiles_[i]) !=
        ProfileResult::ok) {
      return false;
    }
  }
  return true;
}

void MotionPlanner::step_rapid_axes(double dt) noexcept {
  Item& it = item(item_head_);
  const std::size_t n = config_.axis_count;
  if (!active_) {
    active_ = true;
    it.frozen = true;
    rapid_stopping_ = false;
    out_.sample.pos = it.from;
    if (!plan_rapid_axes(it)) {
      out_.fault = MotionFault::unplannable;
      out_.state = MotionState::fault;
      return;
    }
  }
  out_.block = it.block;
  out_.line = it.line;
  out_.css = it.spindle.css;
  out_.spindle_rpm = spindle_rpm_at(it.spindle, it.to);
  out_.spindle_direction = it.spindle.direction;
  // Feed hold: each axis stops as quickly as it can; it goes on from there at the release.
  if ((in_.feed_hold || resetting_) && !rapid_stopping_ && !held_) {
    rapid_stopping_ = true;
    for (std::size_t i = 0; i < n; ++i) {
      const ProfileSample p = axis_profiles_[i].at(t_);
      axis_stops_[i] = speed_transition(
          p.v, p.a, 0.0, JerkLimits{kInf, config_.axes[i].acceleration, config_.axes[i].jerk});
      axis_start_[i] += axis_sign_[i] * p.s;
    }
    t_ = 0.0;
  }
  if (!in_.feed_hold && held_ && !resetting_) {
    held_ = false;
    if (!plan_rapid_axes(it)) {
      out_.fault = MotionFault::unplannable;
      out_.state = MotionState::fault;
      return;
    }
  }
  if (held_) {
    write_rest(out_.sample.pos);
    out_.state = MotionState::held;
    return;
  }
  t_ += dt;
  bool done = true;
  for (std::size_t i = 0; i < n; ++i) {
    const bool ended =
        rapid_stopping_ ? t_ >= axis_stops_[i].duration() : t_ >= axis_profiles_[i].duration();
    const ProfileSample p = rapid_stopping_ ? axis_stops_[i].at(t_) : axis_profiles_[i].at(t_);
    done = done && ended;
    out_.sample.pos[i] =
        ended && !rapid_stopping_ ? it.to[i] : axis_start_[i] + axis_sign_[i] * p.s;
    out_.sample.vel[i] = axis_sign_[i] * p.v;
    out_.sample.acc[i] = axis_sign_[i] * p.a;
  }
  out_.state = rapid_stopping_ ? MotionState::stopping : MotionState::moving;
  if (done && rapid_stopping_) {
    rapid_stopping_ = false;
    held_ = true;
    write_rest(out_.sample.pos);
    out_.state = MotionState::held;
  } else if (done) {
    write_rest(it.to);
    finish_item();
    out_.state = item_count_ == 0 ? MotionState::idle : MotionState::moving;
  }
}

void MotionPlanner::step_thread() noexcept {
  Item& it = item(item_head_);
  const double angle = in_.spindle_angle;
  if (!active_) {
    const double rpm_now = std::fabs(in_.spindle_rpm);
    double rpm = it.thread_rpm > 0.0 ? it.thread_rpm : (it.spindle.css ? 0.0 : it.spindle.rpm);
    if (!(rpm > 0.0)) {
      rpm = rpm_now;  // no commanded speed known: plan the ramps for the measured one
    }
    if (!(rpm > 0.0) || rpm_now < 1e-6) {
      write_rest(seg(it.first).geometry.start());
      out_.state = MotionState::waiting_spindle;
      out_.block = it.block;
      out_.line = it.line;
      prev_angle_ = angle;
      return;
    }
    const double margin = 1.0 + std::max(0.0, config_.thread_speed_margin);
    const double n = rpm / 60.0;
    if (it.lead * n * margin > it.v_geometry) {
      out_.fault = MotionFault::thread_too_fast;
      out_.state = MotionState::fault;
      return;
    }
    const bool chained = it.continuous && thread_chain_;
    ThreadGeometry g;
    g.length = it.length;
    g.path_lead = it.lead;
    g.path_change = it.lead_change;
    g.ramp_in = !chained;
    g.ramp_out = it.ramp_out;
    // The ramps are laid out in revolutions: a faster spindle scales their acceleration with
    // the square and their jerk with the cube of the speed; the spindle's own acceleration
    // adds lead * dn/dt and 3 s'' n dn/dt, for which a tenth and a quarter stay in reserve.
    const JerkLimits l{kInf, it.limits.acceleration / (margin * margin * 1.1),
                       it.limits.jerk / (margin * margin * margin * 1.25)};
    if (!thread_.plan(g, n, l)) {
      out_.fault = MotionFault::unplannable;
      out_.state = MotionState::fault;
      return;
    }
    thread_geometry_ = g;
    thread_rev_per_s_ = n;
    thread_limits_ = l;
    thread_drop_ramp_out_ = false;
    it.frozen = true;
    active_ = true;
    cur_seg_ = it.first;
    seg_base_ = 0.0;
    s_ = 0.0;
    thread_dir_ = in_.spindle_rpm < 0.0 ? -1.0 : 1.0;
    if (chained) {
      thread_started_ = true;
      thread_angle0_ = thread_next_angle0_;
    } else if (it.continuous) {
      thread_started_ = true;  // no one-revolution signal to wait for
      thread_angle0_ = angle;
    } else {
      thread_started_ = false;
      prev_angle_ = angle;  // the start angle counts from now on, never from an earlier pass
    }
  }
  if (!thread_started_) {
    // Wait for the spindle to pass the start angle (start_angle + k 360) since the last cycle.
    const double from = prev_angle_;
    const double to = angle;
    prev_angle_ = angle;
    const double d = thread_dir_ * (to - from);
    if (d > 0.0) {
      const double base = thread_dir_ > 0.0 ? from : -from;
      const double start = thread_dir_ > 0.0 ? it.start_angle : -it.start_angle;
      const double k = std::floor((base - start) / 360.0) + 1.0;
      const double crossing = start + 360.0 * k;  // the first after `base`
      if (crossing <= base + d) {
        thread_started_ = true;
        thread_angle0_ = thread_dir_ * crossing;
      }
    }
    if (!thread_started_) {
      write_path_sample(ProfileSample{0.0, 0.0, 0.0});
      out_.state = MotionState::waiting_spindle;
      return;
    }
  }
  prev_angle_ = angle;
  const double n_now = std::fabs(in_.spindle_rpm) / 60.0;
  const double u = thread_dir_ * (angle - thread_angle0_) / 360.0;
  if (thread_drop_ramp_out_) {
    // A continuous block came after this one started: the ramp-in and the synchronous part do
    // not depend on the ramp-out, so the thread goes on unchanged, at speed into the next.
    thread_drop_ramp_out_ = false;
    if (u < thread_.ramp_out_start()) {
      thread_geometry_.ramp_out = false;
      thread_.plan(thread_geometry_, thread_rev_per_s_, thread_limits_);
    } else {
      it.ramp_out = true;  // too late: it stops, the next block starts from rest
    }
  }
  const ThreadSample ts = thread_.at(u);
  write_path_sample(ProfileSample{ts.s, ts.ds_du * n_now, ts.d2s_du2 * n_now * n_now});
  out_.state = MotionState::moving;
  if (u >= thread_.end_revolutions()) {
    const bool ramp_out = it.ramp_out;
    thread_chain_ = !ramp_out;
    thread_next_angle0_ = thread_angle0_ + thread_dir_ * 360.0 * thread_.end_revolutions();
    v_ = ramp_out ? 0.0 : v_;
    finish_item();
    if (ramp_out) {
      out_.sample.vel = AxisVector{};
      out_.sample.acc = AxisVector{};
      v_ = 0.0;
    }
    if (item_count_ > 0 && item(item_head_).kind == ItemKind::thread && thread_chain_) {
      step_thread();  // the next block of a continuous thread takes over in the same cycle
      return;
    }
    thread_chain_ = thread_chain_ && item_count_ > 0;
    out_.state = item_count_ == 0 ? MotionState::idle : MotionState::moving;
  }
}

// G81.1 starts the oscillation where the axis stands and is done; G80.1 lasts until the
// oscillation ended at the block's end position.
void MotionPlanner::step_oscillation_item() noexcept {
  Item& it = item(item_head_);
  AxisOscillation& o = oscillations_[it.axis];
  out_.block = it.block;
  out_.line = it.line;
  write_rest(out_.sample.pos);
  if (!it.ending) {
    const std::size_t k = it.axis;
    (void)o.start(out_.sample.pos[k], it.top, it.bottom, it.programmed, config_.axes[k]);
  } else if (!active_) {
    active_ = true;
    it.frozen = true;
    o.finish_at(it.to[it.axis]);
  }
  if (it.ending && o.active()) {
    out_.state = MotionState::moving;
    return;
  }
  finish_item();
  out_.state = item_count_ == 0 ? MotionState::idle : MotionState::moving;
}

void MotionPlanner::step_oscillations(double dt) noexcept {
  out_.oscillating = 0;
  for (std::size_t k = 0; k < config_.axis_count; ++k) {
    AxisOscillation& o = oscillations_[k];
    if (!o.active()) {
      continue;
    }
    const OscillationSample s = o.step(dt);
    out_.sample.pos[k] = s.pos;
    out_.sample.vel[k] = s.vel;
    out_.sample.acc[k] = s.acc;
    if (o.active()) {
      out_.oscillating |= 1U << k;
    }
  }
}

const MotionOutput& MotionPlanner::step(const CycleInput& input) noexcept {
  step_items(input);
  step_oscillations(config_.cycle_s);
  return out_;
}

void MotionPlanner::step_items(const CycleInput& input) noexcept {
  in_ = input;
  const double dt = config_.cycle_s;
  const double feed = std::clamp(input.feed_override, 0.0, 2.0);
  const double rapid = std::clamp(input.rapid_override, 0.0, 1.0);
  const double rev = feed * std::fabs(input.spindle_rpm) / 60.0;
  const bool changed = feed != feed_factor_ || rapid != rapid_factor_ ||
                       std::fabs(rev - rev_factor_) > 0.01 * std::max(rev_factor_, 1e-9);
  if (changed) {
    feed_factor_ = feed;
    rapid_factor_ = rapid;
    rev_factor_ = rev;
    backward_pass(true);
    replan_needed_ = true;
  }
  update_lookahead();
  if (out_.state == MotionState::fault) {
    return;
  }
  if (reset_requested_) {
    reset_requested_ = false;
    resetting_ = true;
    const bool moving = item_count_ > 0 && active_ && (v_ > kTiny || std::fabs(a_) > kTiny);
    const ItemKind kind = item_count_ > 0 ? item(item_head_).kind : ItemKind::dwell;
    if (moving && (kind == ItemKind::path || kind == ItemKind::thread)) {
      start_stop(std::max(config_.reset_deceleration_scale, 1e-3));  // a thread stops on its path
    } else {
      stopping_ = false;
    }
    for (std::size_t k = 0; k < config_.axis_count; ++k) {
      oscillations_[k].stop(config_.axes[k].acceleration *
                            std::max(config_.reset_deceleration_scale, 1e-3));
    }
  }
  if (resetting_) {
    const bool axes = item_count_ > 0 && active_ && item(item_head_).kind == ItemKind::rapid_axes;
    if (stopping_) {
      step_path(dt);
    } else if (axes && !held_) {
      step_rapid_axes(dt);  // each axis stops on its own ramp
    }
    if (!stopping_ && (!axes || held_) && out_.oscillating == 0) {
      restart(out_.sample.pos);  // the next block starts from where the axes stand
    }
    return;
  }
  const bool resume = resume_requested_;
  resume_requested_ = false;
  if (item_count_ == 0) {
    if (resume) {
      block_stopped_ = false;  // stopped after the last block queued: the next one runs
    }
    write_rest(out_.sample.pos);
    out_.state = MotionState::idle;
    // Everything taken has run: a spindle command after the last move (M03 before a G04.1
    // wait) takes effect now, not with the next move.
    out_.spindle_rpm = spindle_rpm_at(spindle_, out_.sample.pos);
    out_.spindle_direction = spindle_.direction;
    return;
  }
  const Item& head = item(item_head_);
  if (!active_ && v_ <= kTiny && !input.in_position) {
    write_rest(out_.sample.pos);  // an exact stop: the next block waits for in-position
    out_.state = MotionState::moving;
    return;
  }
  switch (head.kind) {
    case ItemKind::path: {
      if (input.feed_hold && active_ && !stopping_ && !held_ && !block_stopped_) {
        start_stop(1.0);
      }
      if (!input.feed_hold && held_) {
        held_ = false;
        if (active_ && !plan_run(0.0, 0.0, true)) {
          held_ = true;
        }
      }
      if (block_stopped_ && resume) {
        block_stopped_ = false;
        if (active_ && !plan_run(0.0, 0.0, true)) {
          block_stopped_ = true;
        }
      }
      if (input.feed_hold && !active_) {
        write_rest(out_.sample.pos);
        out_.state = MotionState::held;
        return;
      }
      if (block_stopped_ && !active_) {
        write_rest(out_.sample.pos);
        out_.state = MotionState::block_stop;
        return;
      }
      step_path(dt);
      break;
    }
    case ItemKind::dwell:
      step_dwell(dt);
      break;
    case ItemKind::rapid_axes:
      step_rapid_axes(dt);
      break;
    case ItemKind::thread:
      step_thread();
      break;
    case ItemKind::oscillation:
      step_oscillation_item();
      break;
  }
}

}  // namespace mcnc::motion
