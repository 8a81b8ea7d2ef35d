// The spindle-synchronised parts of the planner: threads that follow the spindle's position,
// feed per revolution, constant surface speed, dwell in revolutions.
#include "channel/motion/motion_planner.hpp"

#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mcnc::motion {
namespace {

using testing::check_limits;
using testing::line_to;
using testing::rapid_to;
using testing::run;
using testing::test_machine;

constexpr double kRpm = 600.0;

// A spindle whose speed swings +-10 % around 600 rpm three times a second; its angle is the
// integral of that speed (closed form, so every run sees the same spindle).
struct SwingingSpindle {
  double dt = 0.001;
  [[nodiscard]] double rpm(double t) const {
    return kRpm * (1.0 + 0.1 * std::sin(2.0 * std::numbers::pi * 3.0 * t));
  }
  [[nodiscard]] double angle(double t) const {  // degrees
    const double w = 2.0 * std::numbers::pi * 3.0;
    return 6.0 * kRpm * (t + 0.1 * (1.0 - std::cos(w * t)) / w);
  }
  CycleInput operator()(std::size_t cycle) const {
    const double t = static_cast<double>(cycle + 1) * dt;
    CycleInput in;
    in.spindle_angle = angle(t);
    in.spindle_rpm = rpm(t);
    return in;
  }
};

interp::Command spindle_on(double rpm) {
  interp::Command c;
  c.op = interp::Op::spindle;
  c.spindle_direction = interp::SpindleDirection::cw;
  c.rpm = rpm;
  return c;
}

interp::Command thread_to(const AxisVector& to, double lead, double start_angle, std::uint64_t n) {
  interp::Command c;
  c.op = interp::Op::thread;
  c.to = to;
  c.lead = lead;
  c.start_angle = start_angle;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

// The thread's phase on one pass: z + lead * turns, which is constant where the lead is exact.
struct Pass {
  std::vector<double> phase;
  double angle_before = 0.0;  // spindle angle at the last cycle before the axis moved
  double angle_moving = 0.0;  // and at the first cycle it moved
};

std::vector<Pass> thread_passes(const std::vector<testing::Sample>& trace,
                                const std::vector<std::uint64_t>& thread_blocks, double lead) {
  std::vector<Pass> passes;
  for (const std::uint64_t b : thread_blocks) {
    Pass p;
    bool moving = false;
    double prev_angle = 0.0;
    for (const auto& s : trace) {
      if (s.block != b) {
        prev_angle = s.spindle_angle;
        continue;
      }
      if (!moving && (s.s.pos[1] < 0.0 || s.s.vel[1] < 0.0)) {
        moving = true;
        p.angle_before = prev_angle;
        p.angle_moving = s.spindle_angle;
      }
      prev_angle = s.spindle_angle;
      // Between the ramps: 5 mm after the start, 5 mm before the end.
      if (s.s.pos[1] < -5.0 && s.s.pos[1] > -55.0) {
        p.phase.push_back(s.s.pos[1] + lead * s.spindle_angle / 360.0);
      }
    }
    passes.push_back(p);
  }
  return passes;
}

TEST(Threading, LeadIsExactWhileTheSpindleSpeedSwingsAndEveryPassStartsAtTheSameAngle) {
  const MotionConfig c = test_machine(2);
  const double lead = 2.0;
  // Three passes of a G76-like cycle: rapid in to the depth, thread 60 mm, rapid out and back.
  std::vector<interp::Command> prog{spindle_on(kRpm)};
  std::vector<std::uint64_t> threads;
  std::uint64_t n = 1;
  for (int pass = 0; pass < 3; ++pass) {
    const double x = -0.3 * (pass + 1);
    prog.push_back(rapid_to({x, 0.0}, ++n));
    prog.push_back(thread_to({x, -60.0}, lead, 0.0, ++n));
    threads.push_back(n);
    prog.push_back(rapid_to({1.0, -60.0}, ++n));
    prog.push_back(rapid_to({1.0, 0.0}, ++n));
  }
  MotionPlanner p(c, AxisVector{1.0, 0.0});
  const SwingingSpindle spindle;
  const auto trace = run(p, prog, spindle);
  ASSERT_TRUE(p.idle());
  const auto passes = thread_passes(trace, threads, lead);
  ASSERT_EQ(passes.size(), 3U);
  const double reference = passes[0].phase.front();
  for (const Pass& pass : passes) {
    ASSERT_GT(pass.phase.size(), 100U);
    for (const double phase : pass.phase) {
      // The same helix on every pass (a whole number of leads apart), the lead exact to 1 um
      // while the speed swings.
      EXPECT_NEAR(std::remainder(phase - reference, lead), 0.0, 1e-3);
    }
    // The axis starts moving in the cycle where the spindle passes 0 degrees: a multiple of
    // 360 lies between the last angle at rest and the first angle moving.
    EXPECT_LE(std::ceil(pass.angle_before / 360.0) * 360.0, pass.angle_moving)
        << pass.angle_before << " " << pass.angle_moving;
  }
  const auto r = check_limits(trace, c, AxisVector{1.0, 0.0});
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  EXPECT_EQ(trace.back().s.pos[0], 1.0);
  EXPECT_EQ(trace.back().s.pos[1], 0.0);
}

TEST(Threading, SecondStartIsHalfALeadAway) {
  // A two-start thread: the second start begins at 180 degrees, half a lead further on.
  const MotionConfig c = test_machine(2);
  const double lead = 4.0;
  std::vector<interp::Command> prog{
      spindle_on(kRpm),          thread_to({0.0, -60.0}, lead, 0.0, 1),
      rapid_to({1.0, -60.0}, 2), rapid_to({1.0, 0.0}, 3),
      rapid_to({0.0, 0.0}, 4),   thread_to({0.0, -60.0}, lead, 180.0, 5)};
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, prog, SwingingSpindle{});
  const auto passes = thread_passes(trace, {1, 5}, lead);
  ASSERT_FALSE(passes[0].phase.empty());
  ASSERT_FALSE(passes[1].phase.empty());
  const double shift = passes[1].phase.front() - passes[0].phase.front();
  EXPECT_NEAR(std::remainder(shift - lead / 2.0, lead), 0.0, 1e-3);
}

TEST(Threading, ContinuousThreadGoesOnAtSpeedIntoTheNextBlock) {
  // G32 Z-20 F2 then G32 Z-40 (continuous): no stop at Z-20, the lead goes on exactly.
  const MotionConfig c = test_machine(2);
  interp::Command second = thread_to({0.0, -40.0}, 2.0, 0.0, 2);
  second.continuous = true;
  MotionPlanner p(c, AxisVector{});
  const auto trace =
      run(p, {spindle_on(kRpm), thread_to({0.0, -20.0}, 2.0, 0.0, 1), second}, SwingingSpindle{});
  ASSERT_TRUE(p.idle());
  double reference = 0.0;
  bool have = false;
  for (const auto& s : trace) {
    if (s.s.pos[1] < -5.0 && s.s.pos[1] > -35.0) {
      const double phase = s.s.pos[1] + 2.0 * s.spindle_angle / 360.0;
      if (!have) {
        reference = phase;
        have = true;
      }
      EXPECT_NEAR(phase, reference, 1e-3) << "z " << s.s.pos[1];
      EXPECT_GT(std::fabs(s.s.vel[1]), 15.0);  // never slows down at Z-20
    }
  }
  EXPECT_TRUE(have);
  EXPECT_EQ(trace.back().s.pos[1], -40.0);
}

TEST(Threading, ContinuousBlocksPushedWhileTheThreadRunsStillChain) {
  // A window of two blocks: each continuous block arrives after the one before has started.
  MotionConfig c = test_machine(2);
  c.lookahead_blocks = 2;
  std::vector<interp::Command> prog{spindle_on(kRpm)};
  for (int b = 1; b <= 4; ++b) {
    interp::Command t = thread_to({0.0, -20.0 * b}, 2.0, 0.0, static_cast<std::uint64_t>(b));
    t.continuous = b > 1;
    prog.push_back(t);
  }
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, prog, SwingingSpindle{});
  ASSERT_TRUE(p.idle());
  double reference = 0.0;
  bool have = false;
  for (const auto& s : trace) {
    if (s.s.pos[1] < -5.0 && s.s.pos[1] > -75.0) {
      const double phase = s.s.pos[1] + 2.0 * s.spindle_angle / 360.0;
      if (!have) {
        reference = phase;
        have = true;
      }
      EXPECT_NEAR(phase, reference, 1e-3) << "z " << s.s.pos[1];
    }
  }
  EXPECT_TRUE(have);
  EXPECT_EQ(trace.back().s.pos[1], -80.0);
}

TEST(Threading, WaitsForATurningSpindleAndRefusesALeadTooFastForTheAxes) {
  const MotionConfig c = test_machine(2);
  {
    MotionPlanner p(c, AxisVector{});
    ASSERT_EQ(p.push(thread_to({0.0, -10.0}, 2.0, 0.0, 1)), PushResult::accepted);
    for (int i = 0; i < 50; ++i) {
      const MotionOutput& o = p.step(CycleInput{});  // spindle stopped
      EXPECT_EQ(o.state, MotionState::waiting_spindle);
      EXPECT_EQ(o.sample.pos[1], 0.0);
    }
  }
  {
    // 30 mm/rev at 600 rpm = 300 mm/s on an axis of 200 mm/s: a fault, no motion.
    MotionPlanner p(c, AxisVector{});
    p.push(spindle_on(kRpm));
    p.push(thread_to({0.0, -100.0}, 30.0, 0.0, 1));
    CycleInput in;
    in.spindle_rpm = kRpm;
    const MotionOutput& o = p.step(in);
    EXPECT_EQ(o.state, MotionState::fault);
    EXPECT_EQ(o.fault, MotionFault::thread_too_fast);
    EXPECT_EQ(o.sample.pos[1], 0.0);
  }
}

TEST(FeedPerRevolution, FollowsTheActualSpindleSpeed) {
  const MotionConfig c = test_machine(2);
  interp::Command cut = line_to({0.0, -50.0}, 0.2, 1);  // G99 F0.2: 0.2 mm/rev
  cut.feed_mode = interp::FeedMode::per_rev;
  MotionPlanner p(c, AxisVector{});
  // 600 rpm for 3 s, then 300 rpm: 2 mm/s, then 1 mm/s.
  const auto input = [](std::size_t cycle) {
    CycleInput in;
    in.spindle_rpm = cycle < 3000 ? 600.0 : 300.0;
    return in;
  };
  const auto trace = run(p, {cut}, input);
  EXPECT_NEAR(trace[2500].v, 2.0, 0.02);
  EXPECT_NEAR(trace[4000].v, 1.0, 0.01);
  EXPECT_EQ(trace.back().s.pos[1], -50.0);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
}

TEST(ConstantSurfaceSpeed, SpindleSpeedFollowsXAndStopsAtTheG50Clamp) {
  MotionConfig c = test_machine(2);
  c.css_axis = 0;  // X, radius
  interp::Command css;
  css.op = interp::Op::spindle;
  css.spindle_direction = interp::SpindleDirection::cw;
  css.css = true;
  css.surface = 100.0;   // m/min
  css.max_rpm = 1500.0;  // G50 S1500
  MotionPlanner p(c, AxisVector{50.0, 0.0});
  const auto trace = run(p, {css, line_to({5.0, 0.0}, 600.0, 1)});
  // At X50: 100000 / (2 pi 50) = 318.3 rpm; at X5 it would be 3183: clamped to 1500.
  EXPECT_NEAR(p.output().spindle_rpm, 1500.0, 1e-9);
  bool seen = false;
  for (const auto& s : trace) {
    if (std::fabs(s.s.pos[0] - 20.0) < 0.01) {
      seen = true;
    }
  }
  EXPECT_TRUE(seen);
  MotionPlanner q(c, AxisVector{50.0, 0.0});
  q.push(css);
  q.push(line_to({20.0, 0.0}, 600.0, 1));
  const MotionOutput& first = q.step(CycleInput{});
  EXPECT_NEAR(first.spindle_rpm, 100000.0 / (2.0 * std::numbers::pi * first.sample.pos[0]), 1e-6);
  EXPECT_TRUE(first.css);
}

TEST(Dwell, SecondsAndRevolutions) {
  const MotionConfig c = test_machine(2);
  interp::Command seconds;
  seconds.op = interp::Op::dwell;
  seconds.seconds = 0.5;
  seconds.n = 1;
  interp::Command revs;
  revs.op = interp::Op::dwell;
  revs.seconds = 2.0;
  revs.in_revs = true;
  revs.n = 2;
  MotionPlanner p(c, AxisVector{});
  // 600 rpm = 3.6 degrees per 1 ms cycle: two revolutions take 200 cycles.
  const auto input = [](std::size_t cycle) {
    CycleInput in = testing::steady_spindle(cycle);
    return in;
  };
  const auto trace = run(p, {seconds, revs}, input);
  std::size_t dwell_s = 0;
  std::size_t dwell_r = 0;
  for (const auto& s : trace) {
    if (s.state == MotionState::dwelling) {
      (s.block == 1 ? dwell_s : dwell_r) += 1;
    }
  }
  EXPECT_EQ(dwell_s, 499U);  // the 500th cycle ends the dwell
  EXPECT_NEAR(static_cast<double>(dwell_r), 200.0, 1.0);
}

}  // namespace
}  // namespace mcnc::motion
