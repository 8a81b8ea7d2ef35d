// Polar interpolation (G12.1) through the planner: its machine lines are ordinary lines, so near
// the turning centre the rotary axis is held within its own velocity, acceleration and jerk,
// and the tool tip stays on the programmed contour.
#include "channel/interp/interpreter.hpp"
#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>

namespace mcnc::motion {
namespace {

using testing::check_limits;
using testing::run;

TEST(PolarPath, TheRotaryAxisStaysWithinItsLimitsNearTheCentre) {
  interp::InterpreterConfig ic;
  ic.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z', false},
             interp::AxisConfig{'A', false, true}};
  ic.polar_linear = 'X';
  ic.polar_rotary = 'A';
  // A line 1 mm beside the centre at F500: it asks the A axis for 477 degrees/s there.
  interp::Interpreter in(ic);
  ASSERT_FALSE(in.start("G00 X40 Z0 A0\nG12.1\nG01 A1 F500\nG01 X-40\nG13.1\nM30\n", "p.nc"));
  std::vector<interp::Command> program;
  while (auto r = in.next()) {
    const auto* c = std::get_if<interp::Command>(&*r);
    ASSERT_NE(c, nullptr);
    if (c->op == interp::Op::rapid || c->op == interp::Op::linear) {
      program.push_back(*c);
    }
  }
  ASSERT_GT(program.size(), 20u);

  MotionConfig c = testing::test_machine(3);
  c.axes[2] = AxisDynamics{60.0, 600.0, 20000.0};  // A: 60 degrees/s
  c.path_tolerance = 0.0005;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, program);
  ASSERT_FALSE(trace.empty());
  ASSERT_NE(trace.back().state, MotionState::fault);

  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.velocity, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  EXPECT_LE(r.acceleration, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  EXPECT_LE(r.jerk, 1.0 + 1e-6) << "cycle " << r.worst_jerk_cycle;
  double fastest_a = 0.0;
  double worst_tip = 0.0;
  for (const auto& s : trace) {
    fastest_a = std::max(fastest_a, std::fabs(s.s.vel[2]));
    // On the line y = 1 (x from 20 to -20), or on the way up to it along x = 20.
    const double a = s.s.pos[2] * M_PI / 180.0;
    const double x = s.s.pos[0] * std::cos(a);
    const double y = s.s.pos[0] * std::sin(a);
    if (s.block >= program[1].n && s.block < program.back().n) {
      const double on_line = std::fabs(y - 1.0) + std::max(0.0, std::fabs(x) - 20.0);
      const double on_way_up = std::fabs(x - 20.0) + std::max(0.0, y - 1.0) + std::max(0.0, -y);
      worst_tip = std::max(worst_tip, std::min(on_line, on_way_up));
    }
  }
  EXPECT_GT(fastest_a, 0.9 * 60.0);  // the limit, not the feed, set the pace there
  EXPECT_LE(worst_tip, 0.001 + 1e-9);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(trace.back().s.pos[i], program.back().to[i], 1e-9);
  }
}

}  // namespace
}  // namespace mcnc::motion
