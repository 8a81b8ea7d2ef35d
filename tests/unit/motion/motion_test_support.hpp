#pragma once
// Shared by the motion planner tests: a machine, command builders, a run loop that records the
// cycle samples, and the limit checks on those samples.
#include "channel/motion/motion_planner.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace mcnc::motion::testing {

inline MotionConfig test_machine(std::size_t axes = 3) {
  MotionConfig c;
  c.axis_count = axes;
  for (std::size_t i = 0; i < axes; ++i) {
    c.axes[i] = AxisDynamics{200.0, 1000.0, 50000.0};
    c.rapid_rate[i] = 400.0;
  }
  c.cycle_s = 0.001;
  c.lookahead_blocks = 200;
  c.path_tolerance = 0.01;
  return c;
}

inline interp::Command line_to(const AxisVector& to, double feed_mm_min, std::uint64_t n = 0) {
  interp::Command c;
  c.op = interp::Op::linear;
  c.to = to;
  c.feed = feed_mm_min;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

inline interp::Command rapid_to(const AxisVector& to, std::uint64_t n = 0) {
  interp::Command c;
  c.op = interp::Op::rapid;
  c.to = to;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

// An arc in the plane of axes 0 and 1 around (ca, cb).
inline interp::Command arc_to(const AxisVector& to, double ca, double cb, bool ccw, double feed,
                              std::uint64_t n = 0) {
  interp::Command c;
  c.op = interp::Op::arc;
  c.to = to;
  c.center_axes = {0, 1};
  c.center = {ca, cb};
  c.direction = ccw ? interp::ArcDirection::ccw : interp::ArcDirection::cw;
  c.feed = feed;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

struct Sample {
  MotionSample s;
  MotionState state = MotionState::idle;
  std::uint64_t block = 0;
  std::uint64_t completed = 0;
  double v = 0.0;
  double spindle_angle = 0.0;
  double spindle_rpm = 0.0;
};

using InputFn = std::function<CycleInput(std::size_t cycle)>;

// A spindle turning steadily at `rpm` (600: 3.6 degrees per 1 ms cycle), as seen at `cycle`.
inline CycleInput steady_spindle(std::size_t cycle, double rpm = 600.0, double cycle_s = 0.001) {
  CycleInput in;
  in.spindle_rpm = rpm;
  in.spindle_angle = 6.0 * rpm * cycle_s * static_cast<double>(cycle + 1);
  return in;
}

// Pushes the commands as the window takes them and steps until everything has run (or
// max_cycles). `input` gives each cycle's input; `each` sees the planner before each step.
inline std::vector<Sample> run(MotionPlanner& p, const std::vector<interp::Command>& program,
                               const InputFn& input = {}, std::size_t max_cycles = 2'000'000,
                               const std::function<void(std::size_t, MotionPlanner&)>& each = {}) {
  std::vector<Sample> out;
  std::size_t next = 0;
  for (std::size_t cycle = 0; cycle < max_cycles; ++cycle) {
    while (next < program.size() && p.push(program[next]) == PushResult::accepted) {
      ++next;
    }
    if (each) {
      each(cycle, p);
    }
    const CycleInput in = input ? input(cycle) : CycleInput{};
    const MotionOutput& o = p.step(in);
    out.push_back(Sample{o.sample, o.state, o.block, o.completed_block, o.path_velocity,
                         in.spindle_angle, in.spindle_rpm});
    if (o.state == MotionState::fault) {
      break;
    }
    if (next == program.size() && p.idle()) {
      break;
    }
  }
  return out;
}

struct LimitReport {
  double velocity = 0.0;  // the worst ratio to the limit over every axis and cycle
  double acceleration = 0.0;
  double jerk = 0.0;
  std::size_t worst_cycle = 0;
  std::size_t worst_jerk_cycle = 0;
  std::size_t worst_jerk_axis = 0;
};

// Ratios of what the samples show to each axis's limits: velocity from the position steps,
// acceleration from the velocity steps, jerk from the acceleration steps (the cycle samples are
// what the drives see).
inline LimitReport check_limits(const std::vector<Sample>& trace, const MotionConfig& c,
                                const AxisVector& start) {
  LimitReport r;
  const double dt = c.cycle_s;
  MotionSample prev;
  prev.pos = start;
  for (std::size_t k = 0; k < trace.size(); ++k) {
    const MotionSample& s = trace[k].s;
    for (std::size_t i = 0; i < c.axis_count; ++i) {
      const double v = std::fabs(s.pos[i] - prev.pos[i]) / dt;
      const double a = std::fabs(s.vel[i] - prev.vel[i]) / dt;
      const double j = std::fabs(s.acc[i] - prev.acc[i]) / dt;
      const double vmax = std::max(c.axes[i].velocity, c.rapid_rate[i]);
      const double rv = std::max(v, std::fabs(s.vel[i])) / vmax;
      const double ra = std::max(a, std::fabs(s.acc[i])) / c.axes[i].acceleration;
      const double rj = j / c.axes[i].jerk;
      if (ra > r.acceleration) {
        r.worst_cycle = k;
      }
      if (rj > r.jerk) {
        r.worst_jerk_cycle = k;
        r.worst_jerk_axis = i;
      }
      r.velocity = std::max(r.velocity, rv);
      r.acceleration = std::max(r.acceleration, ra);
      r.jerk = std::max(r.jerk, rj);
    }
    prev = s;
  }
  return r;
}

}  // namespace mcnc::motion::testing
