#pragma once
// The channel's look-ahead planner and interpolator: canonical commands in (push), one
// position/velocity/acceleration setpoint per axis per cycle out (step). Pure and
// deterministic: no clock, no thread, no allocation after construction, no exceptions.
//
// Look-ahead: every pushed block becomes path segments (lines, arcs, helices, and the blend
// arcs of G64 corners) grouped into runs of segments with like limits. A backward pass gives
// each run the highest speed at which it may start and still stop at the end of the window; the
// interpolator plans one jerk-limited profile per run from the speed it really has (the forward
// pass), and replans the run under way when the window grows, the override changes or a feed
// hold comes. docs/motion.md gives the rules and the reasons.
#include "channel/interp/command.hpp"
#include "channel/motion/axis_oscillation.hpp"
#include "channel/motion/path_limits.hpp"
#include "channel/motion/path_segment.hpp"
#include "channel/motion/speed_transition.hpp"
#include "channel/motion/thread_follower.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace mcnc::motion {

// One cycle's setpoint of every axis of the channel.
struct MotionSample {
  AxisVector pos{};
  AxisVector vel{};
  AxisVector acc{};  // feed-forward
};

struct MotionConfig {
  std::size_t axis_count = 0;
  // Per axis: velocity = the highest feed rate, acceleration, jerk (units/s, /s^2, /s^3).
  std::array<AxisDynamics, interp::kMaxChannelAxes> axes{};
  std::array<double, interp::kMaxChannelAxes> rapid_rate{};  // units/s
  double cycle_s = 0.001;
  std::size_t lookahead_blocks = 200;
  double path_tolerance = 0.01;    // G64: how far a blended corner may leave the corner point
  bool jerk_limited = true;        // false: trapezoidal feed profiles
  bool rapid_interpolated = true;  // G00 on a straight line; false: each axis at its own rate
  double curve_acceleration_share = 0.8;  // on arcs: the curve's share of the acceleration
  double reset_deceleration_scale = 1.0;  // reset: the axes' acceleration and jerk times this
  double thread_speed_margin = 0.1;       // thread ramps stay in limits up to this speed rise
  int css_axis = -1;                      // G96: the axis whose distance from the centre counts
  double css_centre = 0.0;                // its position on the spindle's axis
  double spindle_max_rpm = 0.0;           // machine maximum for G96 (0: none)
};

// What a cycle gets from outside: the reference spindle's measured angle (degrees, counted on,
// not wrapped) and speed, the operator panel's overrides and feed hold.
struct CycleInput {
  double spindle_angle = 0.0;
  double spindle_rpm = 0.0;
  double feed_override = 1.0;     // 0..2
  double rapid_override = 1.0;    // 0..1
  double spindle_override = 1.0;  // the commanded speed's factor, before the G96 limits
  bool feed_hold = false;
  // Every axis is inside its in-position width: after an exact stop the next block waits for it
  // (the channel checks the drives' feedback).
  bool in_position = true;
};

enum class PushResult : std::uint8_t {
  accepted,
  full,          // the look-ahead window is full: push again later
  bad_feed,      // a feed move without a feed > 0
  bad_target,    // a coordinate that is not a finite number, a degenerate arc
  not_a_motion,  // an op the planner does not run (the channel handles it)
};

enum class MotionState : std::uint8_t {
  idle,  // nothing queued, at rest
  moving,
  stopping,    // feed hold or reset decelerating
  held,        // feed hold: at rest on the path
  block_stop,  // single block: at rest at a block's end, waiting for resume()
  dwelling,
  waiting_spindle,  // a thread waiting for its start angle
  fault,
};

enum class MotionFault : std::uint8_t {
  none,
  thread_too_fast,  // lead x spindle speed above the axes' limits
  unplannable,      // limits that leave no profile (a machine-file error)
};

struct MotionOutput {
  MotionSample sample;
  MotionState state = MotionState::idle;
  MotionFault fault = MotionFault::none;
  std::uint64_t block = 0;  // Command::n of the block under way (0: none yet)
  int line = 0;
  std::uint64_t completed_block = 0;  // the last block whose end was passed
  double path_velocity = 0.0;
  double spindle_rpm = 0.0;   // commanded speed (G96 computed from the current position)
  int spindle_direction = 0;  // +1 M03 (clockwise), -1 M04, 0 stopped (M05, M19)
  bool css = false;
  // Bit i: axis i oscillates (G81.1) and its setpoint is the oscillation's, not the path's.
  std::uint32_t oscillating = 0;
};

class MotionPlanner {
 public:
  MotionPlanner(const MotionConfig& config, const AxisVector& start);

  // Queues a rapid, linear, arc, thread, dwell or oscillation (G81.1 / G80.1: it starts when
  // the blocks before it ended, then runs beside the path until its G80.1 ended it at its end
  // position; the path keeps the axis where it stood); a spindle command sets the speed the
  // following blocks command (G96 included). Never moves anything by itself. The backward pass
  // over what was queued runs once, at the next step() or update_lookahead().
  PushResult push(const interp::Command& command) noexcept;

  const MotionOutput& step(const CycleInput& input) noexcept;
  // The backward pass over the blocks queued since the last one (step() runs it first).
  void update_lookahead() noexcept {
    if (backward_pending_) {
      backward_pass(false);
    }
  }

  // Whether the end of the window holds down a speed that the next step() may plan with: the
  // end speed of the run under way (or of the first one) or of the run after it. Only then can
  // more blocks change what the next cycle does; otherwise the channel may leave them for later
  // cycles. Runs the pending backward pass.
  [[nodiscard]] bool window_end_binds() noexcept;

  // Single block: stop at the end of every block (from the next block end that can be reached
  // within the limits), and go on at resume().
  void set_single_block(bool on) noexcept;
  void resume() noexcept { resume_requested_ = true; }
  // Stops with the reset deceleration and forgets the queue; an oscillation decelerates at its
  // axis's acceleration times the reset scale. Done when at_rest().
  void reset() noexcept { reset_requested_ = true; }
  // Forgets everything at once and stands at `at` (the axes' position when a program starts,
  // or after an emergency stop, where the drives stopped on their own). keep_oscillations: an
  // axis that oscillates goes on (the program goes on from a position taken over in its run).
  void restart(const AxisVector& at, bool keep_oscillations = false) noexcept;

  // Nothing queued and the path at rest (an axis may still oscillate beside it).
  [[nodiscard]] bool idle() const noexcept { return out_.state == MotionState::idle; }
  // Idle and no axis oscillates.
  [[nodiscard]] bool at_rest() const noexcept { return idle() && out_.oscillating == 0; }
  [[nodiscard]] bool accepts() const noexcept;
  [[nodiscard]] std::size_t queued_blocks() const noexcept { return item_count_; }
  [[nodiscard]] std::size_t window_blocks() const noexcept { return config_.lookahead_blocks; }
  [[nodiscard]] const AxisVector& queue_end() const noexcept { return tail_pos_; }
  [[nodiscard]] const MotionOutput& output() const noexcept { return out_; }

 private:
  enum class Feed : std::uint8_t { per_min, per_rev, rapid };
  enum class ItemKind : std::uint8_t { path, rapid_axes, dwell, thread, oscillation };

  struct SpindleCommand {
    bool css = false;
    int direction = 0;  // +1, -1, 0
    double rpm = 0.0;
    double surface = 0.0;
    double max_rpm = 0.0;
  };

  struct Segment {
    PathSegment geometry;
    std::uint64_t block = 0;
    int line = 0;
    bool block_end = false;  // a block's end point (where single block stops)
    bool exact_stop = false;
    double full_length = 0.0;  // a line's length before corner blends trimmed it
    Feed feed_kind = Feed::per_min;
    double programmed = 0.0;  // mm/s (per_min), mm/rev (per_rev); rapid: unused
    double v_geometry = 0.0;  // the axes' and the curve's velocity limit
    JerkLimits limits{};      // tangential acceleration and jerk (velocity unused)
    double end_cap = 0.0;     // the velocity limit of the junction at its end
    SpindleCommand spindle;
  };

  struct Item {
    ItemKind kind = ItemKind::path;
    std::size_t first = 0;  // ring index of the first segment
    std::size_t count = 0;
    double length = 0.0;
    Feed feed_kind = Feed::per_min;
    double programmed = 0.0;
    double v_geometry = 0.0;
    JerkLimits limits{};
    double start_cap = 0.0;  // junction cap at its start (0: starts from rest)
    double vb = 0.0;         // backward pass: the highest speed at its start
    bool frozen = false;     // under way: no more segments join it
    // dwell
    double dwell = 0.0;
    bool in_revs = false;
    // rapid_axes
    AxisVector from{};
    AxisVector to{};
    // thread
    double lead = 0.0;
    double lead_change = 0.0;
    double start_angle = 0.0;
    double thread_rpm = 0.0;
    bool continuous = false;
    bool ramp_out = true;
    // oscillation: G81.1 starts axis `axis` between top and bottom at `programmed` units/s;
    // ending (G80.1) ends it at `to`.
    std::size_t axis = 0;
    double top = 0.0;
    double bottom = 0.0;
    bool ending = false;
    std::uint64_t block = 0;
    int line = 0;
    SpindleCommand spindle;
  };

  // One 1-D feed piece along the run under way: a release of the acceleration then a profile.
  struct Piece {
    JerkPhases prefix;
    JerkLimitedProfile profile;
    bool stop_only = false;  // a hold or reset stop: only the prefix, may cross runs
    double origin = 0.0;     // run-local s where the piece starts
    double target = 0.0;     // run-local s where it ends (not for stop_only)
    [[nodiscard]] double duration() const noexcept {
      return prefix.duration() + (stop_only ? 0.0 : profile.duration());
    }
    [[nodiscard]] ProfileSample at(double t) const noexcept;
  };

  // queue
  Segment& seg(std::size_t i) noexcept { return segments_[i % segments_.size()]; }
  const Segment& seg(std::size_t i) const noexcept { return segments_[i % segments_.size()]; }
  Item& item(std::size_t i) noexcept { return items_[i % items_.size()]; }
  const Item& item(std::size_t i) const noexcept { return items_[i % items_.size()]; }
  PushResult push_path(const interp::Command& c, Feed feed_kind) noexcept;
  PushResult push_thread(const interp::Command& c) noexcept;
  PushResult push_dwell(const interp::Command& c) noexcept;
  PushResult push_rapid_axes(const interp::Command& c) noexcept;
  PushResult push_oscillation(const interp::Command& c) noexcept;
  void set_segment_limits(Segment& s) const noexcept;
  double junction_cap(Segment& prev, Segment& next, bool prev_open) const noexcept;
  bool try_blend(std::size_t prev_index, Segment& next) noexcept;
  void append_segment(const Segment& s, double cap) noexcept;
  Item& new_item(ItemKind kind) noexcept;
  [[nodiscard]] double factor(Feed kind) const noexcept;
  [[nodiscard]] double cap_of(const Item& it) const noexcept;
  [[nodiscard]] double end_target(std::size_t index) const noexcept;
  void touch(std::size_t index) noexcept;
  void backward_pass(bool all) noexcept;

  // interpolation
  void step_items(const CycleInput& input) noexcept;
  void step_path(double dt) noexcept;
  void step_oscillation_item() noexcept;
  // The oscillating axes' setpoints over the path's.
  void step_oscillations(double dt) noexcept;
  void step_rapid_axes(double dt) noexcept;
  bool plan_rapid_axes(const Item& it) noexcept;
  void step_dwell(double dt) noexcept;
  void step_thread() noexcept;
  void finish_item() noexcept;
  bool plan_run(double v, double a, bool may_end_faster) noexcept;
  void start_stop(double scale) noexcept;
  void write_path_sample(const ProfileSample& p) noexcept;
  void write_rest(const AxisVector& pos) noexcept;
  void maybe_replan() noexcept;
  [[nodiscard]] double next_block_end(double from) const noexcept;
  [[nodiscard]] double spindle_rpm_at(const SpindleCommand& s,
                                      const AxisVector& pos) const noexcept;

  MotionConfig config_;
  JerkLimits curve_share_{};
  std::vector<Segment> segments_;
  std::vector<Item> items_;
  std::size_t seg_head_ = 0;  // first segment still queued
  std::size_t seg_tail_ = 0;  // one past the last
  std::size_t item_head_ = 0;
  std::size_t item_count_ = 0;
  AxisVector tail_pos_{};
  SpindleCommand spindle_{};
  bool single_block_ = false;
  bool resume_requested_ = false;
  bool replan_needed_ = false;
  static constexpr std::size_t kNoneChanged = ~std::size_t{0};
  std::size_t first_changed_ = kNoneChanged;  // the first run changed since the backward pass
  bool backward_pending_ = false;
  bool reset_requested_ = false;

  // interpolator state
  CycleInput in_{};
  double feed_factor_ = 1.0;  // the factors the backward pass used
  double rapid_factor_ = 1.0;
  double rev_factor_ = 0.0;
  bool active_ = false;  // the head item has started
  Piece piece_{};
  double t_ = 0.0;  // time in the piece
  double s_ = 0.0;  // run-local position
  double v_ = 0.0;
  double a_ = 0.0;
  double planned_end_v_ = 0.0;  // end velocity the current piece was planned for
  std::size_t cur_seg_ = 0;     // ring index of the segment under way
  double seg_base_ = 0.0;       // run-local s at its start
  bool stopping_ = false;
  bool held_ = false;
  bool block_stopped_ = false;
  bool resetting_ = false;
  double dwell_left_ = 0.0;
  double dwell_angle_ = 0.0;
  double dwell_last_angle_ = 0.0;
  double stop_scale_ = 1.0;  // the limits' scale of the stop under way (reset: its own)
  // rapid_axes
  std::array<JerkLimitedProfile, interp::kMaxChannelAxes> axis_profiles_{};
  std::array<double, interp::kMaxChannelAxes> axis_sign_{};
  AxisVector axis_start_{};  // where each axis's profile starts
  std::array<JerkPhases, interp::kMaxChannelAxes> axis_stops_{};
  bool rapid_stopping_ = false;
  // thread
  ThreadFollower thread_;
  ThreadGeometry thread_geometry_{};  // what thread_ was planned with
  double thread_rev_per_s_ = 0.0;
  JerkLimits thread_limits_{};
  bool thread_drop_ramp_out_ = false;  // a continuous block came after this thread started
  bool thread_started_ = false;
  double thread_angle0_ = 0.0;
  double thread_dir_ = 1.0;
  double thread_next_angle0_ = 0.0;
  bool thread_chain_ = false;
  double prev_angle_ = 0.0;
  std::array<AxisOscillation, interp::kMaxChannelAxes> oscillations_{};
  MotionOutput out_{};
};

}  // namespace mcnc::motion
