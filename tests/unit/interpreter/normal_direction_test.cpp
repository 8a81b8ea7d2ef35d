// G40.1 / G41.1 / G42.1 normal direction control (spec dafeng L3799-3906): the rotation the
// control inserts before a move in another direction, the axis turning with an arc, the
// shortest turn, G40.1 holding the angle, and the alarms.
#include "channel/interp/dialect.hpp"
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

// The travel direction (degrees, G18: 0 along +Z) where move `c` from `from` starts or ends.
double direction(const Command& c, const AxisVector& from, bool at_end) {
  constexpr double kDegrees = 180.0 / M_PI;
  if (c.op == Op::arc) {
    const AxisVector& p = at_end ? c.to : from;
    const double ra = p[kZ] - c.center[0];
    const double rb = p[kX] - c.center[1];
    return (c.direction == ArcDirection::ccw ? std::atan2(ra, -rb) : std::atan2(-ra, rb)) *
           kDegrees;
  }
  return std::atan2(c.to[kX] - from[kX], c.to[kZ] - from[kZ]) * kDegrees;
}

// Every cutting move of lines `first`-`last` that travels in the plane starts and ends with A at
// its direction + `side` degrees; returns how many were checked.
int expect_normal(const RunResult& r, int first, int last, double side) {
  AxisVector at{};
  int checked = 0;
  for (const Command& c : r.commands) {
    if (!c.moves()) {
      continue;
    }
    const double travel = std::hypot(c.to[kZ] - at[kZ], c.to[kX] - at[kX]);
    if (c.line >= first && c.line <= last && (c.op == Op::linear || c.op == Op::arc) &&
        travel > 1e-9) {
      EXPECT_NEAR(std::remainder(at[kA] - direction(c, at, false) - side, 360.0), 0, 1e-9)
          << "start, line " << c.line;
      EXPECT_NEAR(std::remainder(c.to[kA] - direction(c, at, true) - side, 360.0), 0, 1e-9)
          << "end, line " << c.line;
      ++checked;
    }
    at = c.to;
  }
  return checked;
}

// L3880: with tool-nose compensation the axis follows the offset path. G42 with a nose of 1
// round an outside corner (a corner arc: the axis turns with it, no turn of its own) and an
// inside one (a turn at the offset lines' intersection). G40.1 leaves A where the last move of
// the control leaves it, which the G40 move, still in the look-ahead then, carries.
TEST(InterpNormalDirection, WithNoseCompensationTheAxisFollowsTheOffsetPath) {
  RunResult r = run_ok(
      "T0101\nG00 X20 Z30\nG41.1\nG42 G01 Z20 F300\nG01 Z10\nG01 X0\nG01 Z0\nG40.1\n"
      "G40 G00 X40 Z40\nM30\n",
      with_nose_radius(with_normal_axis(), 1.0));
  // Lines 4-7 under the control: every move normal on the left of travel.
  EXPECT_EQ(expect_normal(r, 4, 7, 90.0), 5);  // 4 lines and the corner arc
  ASSERT_EQ(r.of(Op::arc).size(), 1u);
  const Command corner = r.of(Op::arc)[0];
  EXPECT_NEAR(corner.center[0], 10, 1e-9);  // about the programmed corner Z10 X10 (radius)
  EXPECT_NEAR(corner.center[1], 10, 1e-9);
  // The inside corner at Z0 X0 (programmed): the offset -X line (Z9) meets the -Z line (X1).
  const auto line7 = r.at_line(7);
  ASSERT_GE(line7.size(), 2u);
  EXPECT_EQ(line7[0].feed, 7200);
  EXPECT_NEAR(line7[0].to[kZ], 9, 1e-9);
  EXPECT_NEAR(line7[0].to[kX], 1, 1e-9);
  // G40.1 and the G40 move: A stays at the left normal of -Z (270 or -90).
  const auto line9 = r.at_line(9);
  ASSERT_EQ(line9.size(), 1u);
  EXPECT_NEAR(std::remainder(line9[0].to[kA] - 270.0, 360.0), 0, 1e-9);
  EXPECT_NEAR(line9[0].to[kA], line7.back().to[kA], 1e-12);
}

// After G40.1 the program knows where A stands once the control's moves left the look-ahead:
// programming A then moves it from there; before, it is an alarm (the angle is not known yet).
TEST(InterpNormalDirection, TheAxisAfterG401) {
  const InterpreterConfig c = with_nose_radius(with_normal_axis(), 1.0);
  RunResult r = run_ok(
      "T0101\nG00 X20 Z30\nG41.1\nG42 G01 Z20 F300\nG01 X0\nG40.1\nG40 G00 X40 Z40\n"
      "G00 A0\nM30\n",
      c);
  const auto line8 = r.at_line(8);
  ASSERT_EQ(line8.size(), 1u);
  EXPECT_NEAR(line8[0].to[kA], 0, 1e-12);
  run_alarm(
      "T0101\nG00 X20 Z30\nG41.1\nG42 G01 Z20 F300\nG01 X0\nG40.1\nG00 A0\nG40 G00 X40\nM30\n",
      alarm::kWordNotAllowed, 7, -1, c);
  // Without compensation nothing waits: A may be programmed right after G40.1.
  RunResult plain = run_ok("G41.1\nG01 Z10 F300\nG40.1\nG00 A45\nM30\n", with_normal_axis());
  EXPECT_NEAR(plain.at_line(4)[0].to[kA], 45, 1e-12);
}

// Corners (,C ,R) under the control: the chamfer is a move of its own with a turn before it and
// after it; the round corner is an arc the axis turns with.
TEST(InterpNormalDirection, CornersTurnTheAxis) {
  RunResult r =
      run_ok("G00 X0 Z0\nG41.1\nG01 Z10 ,C2 F300\nG01 X20 ,R3\nG01 Z20\nM30\n", with_normal_axis());
  EXPECT_EQ(expect_normal(r, 3, 5, 90.0), 5);  // three lines, the chamfer and the round
  int turns = 0;
  for (const Command& m : r.commands) {
    turns += m.op == Op::linear && m.feed == 7200 ? 1 : 0;
  }
  EXPECT_EQ(turns, 3);  // the start, into the chamfer, out of it; none at the round
}

// G41 -> G42 under the control, and G42.1 on the offset path of an arc.
TEST(InterpNormalDirection, ChangesOfSideOnTheOffsetPath) {
  RunResult r = run_ok(
      "T0101\nG00 X0 Z0\nG42.1\nG41 G01 Z10 F300\nG03 X20 Z20 R10\nG42 G01 Z30\n"
      "G01 X0\nG40 G01 Z40\nM30\n",
      with_nose_radius(with_normal_axis(), 0.5));
  EXPECT_EQ(expect_normal(r, 4, 7, -90.0), 4);  // two start-ups, the arc, the last line
}

TEST(InterpNormalDirection, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G41.1 X10\nM30\n", alarm::kMustBeAlone, 1},
      // The rotary axis belongs to the control while the mode is on.
      {"G41.1\nG01 Z10 A30 F100\nM30\n", alarm::kWordNotAllowed, 2},
      {"G41.1\nG00 A0\nM30\n", alarm::kWordNotAllowed, 2},
  };
  expect_alarms(cases, with_normal_axis());
  // Without the axis of param 5550.
  run_alarm("G41.1\nM30\n", alarm::kNoPlaneAxis, 1);
  run_ok("G40.1\nG01 Z10 F100\nM30\n");
}

// The mill (FANUC 0i-MF): G41.1 with cutter compensation G41 D in G17, C the axis. A square
// programmed clockwise, the cutter on the left (outside): corner arcs at every corner, C turned
// by -90 with each.
TEST(InterpNormalDirection, TheMillWithCutterCompensation) {
  InterpreterConfig c;
  select_dialect(c, Dialect::fanuc_mill);
  c.axes.push_back(AxisConfig{'C', false, true});
  c.normal_axis = 'C';
  c.tool_geometry[2].radius = 5.0;
  RunResult r = run_ok(
      "G00 X-20 Y-20 Z0\nG41.1\nG41 D2 G01 X0 Y0 F100\nY50\nX50\nY0\nX0\nG40 G00 X-20 "
      "Y-20\nG40.1\nM30\n",
      c);
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 3u);
  // Up +Y (90 degrees in G17): the left normal 180; round the corner clockwise to +X: 90; to -Y:
  // 0; to -X: -90.
  EXPECT_NEAR(std::remainder(arcs[0].to[3] - 90.0, 360.0), 0, 1e-9);
  EXPECT_NEAR(arcs[1].to[3] - arcs[0].to[3], -90, 1e-9);
  EXPECT_NEAR(arcs[2].to[3] - arcs[1].to[3], -90, 1e-9);
}

}  // namespace
}  // namespace mcnc::interp::test
