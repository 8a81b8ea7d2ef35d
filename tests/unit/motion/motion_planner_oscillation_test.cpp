// The planner running a G81.1 oscillation beside the path (spec dafeng L2454-2505): the axis
// strokes between its dead points while the other axes' blocks run, G80.1 ends it at its end
// position before the blocks after it, and a reset stops it.
#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mcnc::motion {
namespace {

using testing::line_to;
using testing::test_machine;

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

interp::Command oscillate(std::size_t axis, double top, double bottom, double feed,
                          const AxisVector& at, std::uint64_t n) {
  interp::Command c;
  c.op = interp::Op::oscillate;
  c.oscillating = static_cast<int>(axis);
  c.top = top;
  c.bottom = bottom;
  c.feed = feed;
  c.to = at;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

interp::Command oscillate_end(std::size_t axis, const AxisVector& to, std::uint64_t n) {
  interp::Command c;
  c.op = interp::Op::oscillate_end;
  c.oscillating = static_cast<int>(axis);
  c.to = to;
  c.n = n;
  c.line = static_cast<int>(n);
  return c;
}

struct Record {
  std::vector<double> turns;  // Z where its velocity changed sign or it came to rest
  std::vector<MotionOutput> out;
};

// Steps until the planner is at rest (or `cycles`), recording Z's turning points.
Record run(MotionPlanner& p, std::size_t cycles, const CycleInput& in = CycleInput{}) {
  Record r;
  double prev_v = 0.0;
  double prev_z = p.output().sample.pos[kZ];
  for (std::size_t i = 0; i < cycles; ++i) {
    const MotionOutput& m = p.step(in);
    r.out.push_back(m);
    const double v = m.sample.vel[kZ];
    if (prev_v != 0.0 && (v == 0.0 || (v > 0.0) != (prev_v > 0.0))) {
      r.turns.push_back(std::fabs(v) < std::fabs(prev_v) ? m.sample.pos[kZ] : prev_z);
    }
    prev_v = v;
    prev_z = m.sample.pos[kZ];
    if (p.at_rest()) {
      break;
    }
  }
  return r;
}

TEST(MotionPlannerOscillation, TheAxisStrokesWhileThePathRunsAndEndsAtG801) {
  // G81.1 Z0 Q10 F1200 (20 mm/s: 0.785 s a stroke), X feeds 10 mm at 240 mm/min (2.5 s),
  // G80.1 Z0, then X back.
  MotionPlanner p(test_machine(2), AxisVector{});
  ASSERT_EQ(p.push(oscillate(kZ, 0.0, 10.0, 1200.0, AxisVector{}, 1)), PushResult::accepted);
  ASSERT_EQ(p.push(line_to(AxisVector{10.0, 0.0}, 240.0, 2)), PushResult::accepted);
  ASSERT_EQ(p.push(oscillate_end(kZ, AxisVector{10.0, 0.0}, 3)), PushResult::accepted);
  ASSERT_EQ(p.push(line_to(AxisVector{0.0, 0.0}, 600.0, 4)), PushResult::accepted);
  const Record r = run(p, 20000);
  ASSERT_TRUE(p.at_rest());
  // Z turned at 10 and 0 alternately, and stopped at 0.
  ASSERT_GE(r.turns.size(), 4U);
  for (std::size_t k = 0; k < r.turns.size(); ++k) {
    // The sample nearest a dead point: within the stroke's peak acceleration (80 mm/s^2) times
    // a cycle squared of it.
    EXPECT_NEAR(r.turns[k], k % 2 == 0 ? 10.0 : 0.0, 80.0 * 1e-6) << "turn " << k;
  }
  // While X fed, Z oscillated: at X = 5 (half way) it was somewhere between its points, and
  // the planner said so.
  bool seen_mid = false;
  std::size_t x_done = 0;
  std::size_t z_done = 0;
  std::size_t back_starts = 0;
  for (std::size_t i = 0; i < r.out.size(); ++i) {
    const MotionOutput& m = r.out[i];
    EXPECT_LE(std::fabs(m.sample.vel[kZ]), 20.0 + 1e-9);
    if (!seen_mid && m.sample.pos[kX] >= 5.0) {
      seen_mid = true;
      EXPECT_NE(m.oscillating & (1U << kZ), 0U);
    }
    if (x_done == 0 && m.completed_block >= 2) {
      x_done = i;
    }
    if (z_done == 0 && m.oscillating == 0 && i > 0 && r.out[i - 1].oscillating != 0) {
      z_done = i;
      EXPECT_DOUBLE_EQ(m.sample.pos[kZ], 0.0);
      EXPECT_EQ(m.sample.vel[kZ], 0.0);
    }
    if (back_starts == 0 && m.sample.pos[kX] < 10.0 - 1e-9 && x_done != 0) {
      back_starts = i;
    }
  }
  EXPECT_TRUE(seen_mid);
  ASSERT_GT(x_done, 0U);
  ASSERT_GT(z_done, x_done);
  // X went back only after G80.1 ended: Z at rest at 0.
  EXPECT_GT(back_starts, z_done);
  EXPECT_NEAR(r.out.back().sample.pos[kX], 0.0, 1e-9);
}

TEST(MotionPlannerOscillation, ThePlannerIsIdleWhileTheAxisStrokesOn) {
  // Blocks that do not move run beside the oscillation: the path is idle, not at rest.
  MotionPlanner p(test_machine(2), AxisVector{});
  ASSERT_EQ(p.push(oscillate(kZ, 0.0, 5.0, 600.0, AxisVector{}, 1)), PushResult::accepted);
  for (int i = 0; i < 100; ++i) {
    p.step(CycleInput{});
  }
  EXPECT_TRUE(p.idle());
  EXPECT_FALSE(p.at_rest());
  EXPECT_GT(p.output().sample.pos[kZ], 0.0);
  EXPECT_GT(p.output().sample.vel[kZ], 0.0);
  // Feed hold and the feed override leave it alone (L2484).
  CycleInput held;
  held.feed_hold = true;
  held.feed_override = 0.0;
  const double z = p.output().sample.pos[kZ];
  p.step(held);
  EXPECT_GT(p.output().sample.pos[kZ], z);
}

TEST(MotionPlannerOscillation, AResetStopsItAtTheAxissDeceleration) {
  MotionPlanner p(test_machine(2), AxisVector{});
  ASSERT_EQ(p.push(oscillate(kZ, 0.0, 50.0, 6000.0, AxisVector{}, 1)), PushResult::accepted);
  for (int i = 0; i < 300; ++i) {
    p.step(CycleInput{});
  }
  const double v = p.output().sample.vel[kZ];
  ASSERT_GT(v, 10.0);
  p.reset();
  const Record r = run(p, 5000);
  EXPECT_TRUE(p.at_rest());
  for (const MotionOutput& m : r.out) {
    EXPECT_LE(std::fabs(m.sample.acc[kZ]), 1000.0 + 1e-9);  // the axis's acceleration
    EXPECT_GE(m.sample.vel[kZ], 0.0);                       // no turn back
  }
  EXPECT_LE(r.out.size(), static_cast<std::size_t>(v / 1000.0 / 0.001) + 3);
  // A restart forgets it.
  p.restart(p.output().sample.pos);
  EXPECT_EQ(p.output().oscillating, 0U);
}

TEST(MotionPlannerOscillation, ARestartInTheRunKeepsItAndThePathsHold) {
  // A position taken over in the run (G141, M18): the stroke goes on, and the path goes on
  // from where G81.1 found Z, not from where the stroke is.
  MotionPlanner p(test_machine(2), AxisVector{});
  ASSERT_EQ(p.push(oscillate(kZ, 0.0, 5.0, 600.0, AxisVector{}, 1)), PushResult::accepted);
  for (int i = 0; i < 200; ++i) {
    p.step(CycleInput{});
  }
  const AxisVector here = p.output().sample.pos;
  ASSERT_GT(here[kZ], 0.5);
  p.restart(here, true);
  EXPECT_EQ(p.queue_end()[kZ], 0.0);
  ASSERT_EQ(p.push(line_to(AxisVector{1.0, 0.0}, 600.0, 2)), PushResult::accepted);
  const MotionOutput& m = p.step(CycleInput{});
  EXPECT_NE(m.oscillating, 0U);
  EXPECT_GT(m.sample.pos[kZ], here[kZ]);  // still on its way to 5
}

TEST(MotionPlannerOscillation, BadOscillationsAreRefused) {
  MotionPlanner p(test_machine(2), AxisVector{});
  EXPECT_EQ(p.push(oscillate(kZ, 5.0, 5.0, 600.0, AxisVector{}, 1)), PushResult::bad_target);
  EXPECT_EQ(p.push(oscillate(kZ, 0.0, 5.0, 0.0, AxisVector{}, 1)), PushResult::bad_feed);
  EXPECT_EQ(p.push(oscillate(7, 0.0, 5.0, 600.0, AxisVector{}, 1)), PushResult::bad_target);
  EXPECT_EQ(p.queued_blocks(), 0U);
}

}  // namespace
}  // namespace mcnc::motion
