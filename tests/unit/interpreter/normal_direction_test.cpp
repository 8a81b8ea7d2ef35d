// G40.1 / G41.1 / G42.1 normal direction control (spec dafeng L3799-3906): the rotation the
// control inserts before a move in another direction, the axis turning with an arc, the
// shortest turn, G40.1 holding the angle, and the alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

// X (diameter), Z and the rotary axis A of param 5550.
InterpreterConfig with_normal_axis() {
  InterpreterConfig c = lathe();
  c.axes.push_back(AxisConfig{'A', false, true});
  c.normal_axis = 'A';
  c.normal_feed = 7200;
  return c;
}

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr std::size_t kA = 2;

// The spec's example (L3894-3904): G41.1 turns A to 90 degrees before the move along +Z. Before
// the move along +X it turns to 180 (the normal on the left of +X, +X lying at +90 degrees in
// G18); the spec says 0 there (decision 60).
TEST(InterpNormalDirection, RotationsAreInsertedBeforeTheMoves) {
  RunResult r = run_ok("G00 X0 Z0\nG41.1\nG01 Z10 F300\nG01 X10 F300\nG40.1\nG01 Z20\nM30\n",
                       with_normal_axis());
  const auto lines = r.of(Op::linear);
  ASSERT_EQ(lines.size(), 5u);
  // The inserted rotation: A alone, at param 5551's speed.
  EXPECT_NEAR(lines[0].to[kA], 90, 1e-9);
  EXPECT_NEAR(lines[0].to[kZ], 0, 1e-12);
  EXPECT_NEAR(lines[0].feed, 7200, 1e-12);
  EXPECT_EQ(lines[0].line, 3);
  EXPECT_NEAR(lines[1].to[kZ], 10, 1e-12);
  EXPECT_NEAR(lines[1].to[kA], 90, 1e-9);
  EXPECT_NEAR(lines[1].feed, 300, 1e-12);
  EXPECT_NEAR(lines[2].to[kA], 180, 1e-9);
  EXPECT_NEAR(lines[3].to[kX], 5, 1e-12);
  EXPECT_NEAR(lines[3].to[kA], 180, 1e-9);
  // G40.1: the angle stays.
  EXPECT_NEAR(lines[4].to[kZ], 20, 1e-12);
  EXPECT_NEAR(lines[4].to[kA], 180, 1e-9);
}

TEST(InterpNormalDirection, RightSideAndTheShortestTurn) {
  // G42.1 along +Z: -90. Then along +X (+90 degrees): 0, a turn of +90 from -90.
  RunResult r = run_ok("G42.1\nG01 Z10 F300\nG01 X10\nG01 Z0\nM30\n", with_normal_axis());
  const auto lines = r.of(Op::linear);
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_NEAR(lines[0].to[kA], -90, 1e-9);
  EXPECT_NEAR(lines[2].to[kA], 0, 1e-9);
  // Along -Z (180 degrees): the normal on the right is 90, reached from 0 by +90.
  EXPECT_NEAR(lines[4].to[kA], 90, 1e-9);
}

TEST(InterpNormalDirection, TheAxisTurnsWithAnArc) {
  // A quarter circle from Z10 X0 to Z20 X20 (diameter) about Z10 X20, counter-clockwise as
  // G18 is seen: it starts along +Z (normal on the left: 90) and ends along +X, the axis at 180
  // after the arc's quarter turn.
  RunResult r = run_ok("G00 X0 Z10\nG41.1\nG03 X20 Z20 R10 F300\nM30\n", with_normal_axis());
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_NEAR(arcs[0].to[kA], 180, 1e-9);
  const auto lines = r.of(Op::linear);
  ASSERT_EQ(lines.size(), 1u);  // the rotation to the arc's start normal
  EXPECT_NEAR(lines[0].to[kA], 90, 1e-9);
}

// The inserted rotation turns the normal axis alone, from wherever the machine stands: after
// polar interpolation (whose moves were on the polar plane) as after any move.
TEST(InterpNormalDirection, TheInsertedRotationMovesTheNormalAxisOnly) {
  InterpreterConfig c = with_normal_axis();
  c.axes.push_back(AxisConfig{'C', false, true});
  c.polar_linear = 'X';
  c.polar_rotary = 'C';
  RunResult r = run_ok(
      "G00 X40 Z0 C0\nG12.1\nG01 X20 F100\nG01 C10\nG13.1\nG41.1\nG01 Z-10 F300\n"
      "G01 X60\nM30\n",
      c);
  AxisVector last{};
  int rotations = 0;
  for (const Command& m : r.commands) {
    if (!m.moves()) {
      continue;
    }
    if (m.op == Op::linear && m.feed == 7200) {
      ++rotations;
      for (std::size_t i = 0; i < 4; ++i) {
        if (i != kA) {
          EXPECT_NEAR(m.to[i], last[i], 1e-9) << "axis " << i << " line " << m.line;
        }
      }
    }
    last = m.to;
  }
  EXPECT_EQ(rotations, 2);
}

TEST(InterpNormalDirection, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G41.1 X10\nM30\n", alarm::kMustBeAlone, 1},
      // The rotary axis belongs to the control while the mode is on.
      {"G41.1\nG01 Z10 A30 F100\nM30\n", alarm::kWordNotAllowed, 2},
      // Not with tool-nose compensation yet.
      {"G41 G01 X10 F100\nG41.1\nM30\n", alarm::kNotInThisVersion, 2},
      {"G41.1\nG41 G01 X10 F100\nM30\n", alarm::kNotInThisVersion, 2},
      {"G41.1\nG01 Z10 ,C1 F100\nG01 X20\nM30\n", alarm::kNotInThisVersion, 2},
  };
  expect_alarms(cases, with_normal_axis());
  // Without the axis of param 5550.
  run_alarm("G41.1\nM30\n", alarm::kNoPlaneAxis, 1);
  run_ok("G40.1\nG01 Z10 F100\nM30\n");
}

}  // namespace
}  // namespace mcnc::interp::test
