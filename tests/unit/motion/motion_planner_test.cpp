#include "channel/motion/motion_planner.hpp"

#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mcnc::motion {
namespace {

using testing::arc_to;
using testing::check_limits;
using testing::line_to;
using testing::rapid_to;
using testing::run;
using testing::test_machine;

TEST(MotionPlanner, LongLineTakesTheSCurveTime) {
  // 100 mm at 6000 mm/min = 100 mm/s with a = 1000, j = 50000: the acceleration reaches its
  // limit (v >= a^2/j = 20), so T = D/v + v/a + a/j = 1 + 0.1 + 0.02 = 1.12 s.
  const MotionConfig c = test_machine();
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, {line_to({100.0, 0.0, 0.0}, 6000.0, 1)});
  ASSERT_FALSE(trace.empty());
  EXPECT_EQ(trace.back().s.pos[0], 100.0);
  std::size_t moving = 0;
  for (const auto& s : trace) {
    moving += s.state == MotionState::moving ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(trace.size()) * c.cycle_s, 1.12, 0.0015);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.velocity, 1.0 + 1e-9);
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
}

TEST(MotionPlanner, ShortLineTakesTheJerkOnlyTime) {
  // 0.1 mm: too short to reach the acceleration limit (peak v = (D^2 j / 4)^(1/3) = 5 mm/s,
  // below a^2/j = 20), four jerk phases of sqrt(v/j) = 10 ms: T = 40 ms.
  const MotionConfig c = test_machine();
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, {line_to({0.1, 0.0, 0.0}, 6000.0, 1)});
  double vmax = 0.0;
  for (const auto& s : trace) {
    vmax = std::max(vmax, s.v);
  }
  EXPECT_NEAR(vmax, 5.0, 0.01);
  // Sample k is the state at (k + 1) cycles: the 40th is the first on the end point.
  ASSERT_EQ(trace.size(), 40U);
  EXPECT_LT(trace[38].s.pos[0], 0.1);
  EXPECT_EQ(trace[39].s.pos[0], 0.1);
}

TEST(MotionPlanner, CircleOfShortSegmentsKeepsItsSpeed) {
  MotionConfig c = test_machine();
  MotionPlanner p(c, AxisVector{10.0, 0.0, 0.0});
  std::vector<interp::Command> prog;
  const int n = 1000;  // 0.0628 mm segments on R10
  for (int i = 1; i <= n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    prog.push_back(line_to({10.0 * std::cos(t), 10.0 * std::sin(t), 0.0}, 3000.0, i));
  }
  const auto trace = run(p, prog);
  const auto r = check_limits(trace, c, AxisVector{10.0, 0.0, 0.0});
  // 3000 mm/min = 50 mm/s, well under what R10 allows (sqrt(0.8 a r) = 89 mm/s): the chords
  // blend into the circle and the whole middle of it runs at the programmed feed.
  for (std::size_t k = trace.size() / 4; k < 3 * trace.size() / 4; ++k) {
    EXPECT_NEAR(trace[k].v, 50.0, 1e-9) << k;
  }
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  EXPECT_NEAR(trace.back().s.pos[0], 10.0, 1e-9);
  EXPECT_NEAR(trace.back().s.pos[1], 0.0, 1e-9);
}

}  // namespace
}  // namespace mcnc::motion
