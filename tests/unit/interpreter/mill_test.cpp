// The mill dialect (gsk Part B, seed 003): its table and groups, the Part C conflicts read as
// the mill reads them, G43/G44/G49 with H, G41/G42 with D, the hole cycles, G27/G29/G60. The
// examples of B.5 are conformance cases (tests/conformance/gsk-D3-*-mill-*).
#include "channel/interp/dialect.hpp"
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

InterpreterConfig mill() {
  InterpreterConfig c;
  select_dialect(c, Dialect::fanuc_mill);
  return c;
}

TEST(MillDialect, NamesAndWhatTheDialectSets) {
  EXPECT_EQ(dialect_named("fanuc-mill"), Dialect::fanuc_mill);
  EXPECT_EQ(dialect_named("gsk"), Dialect::gsk);
  EXPECT_EQ(dialect_named("fanuc-lathe"), Dialect::dafeng);  // ARCHITECTURE.md's name
  EXPECT_FALSE(dialect_named("fanuc").has_value());
  EXPECT_EQ(dialect_name(Dialect::fanuc_mill), "fanuc-mill");
  const InterpreterConfig c = mill();
  EXPECT_EQ(c.system, GCodeSystem::b);
  ASSERT_EQ(c.axes.size(), 3u);
  EXPECT_EQ(c.axes[1].name, 'Y');
  EXPECT_FALSE(c.axes[0].diameter);
  EXPECT_EQ(c.macro.local_last, 33);
  EXPECT_TRUE(c.macro.round_to_integer);
}

// Part C: the codes that conflict mean what the mill means; the lathe's own codes are not G
// codes of the mill (B.2 rule 4).
TEST(MillDialect, LatheCodesAreNotInTheTable) {
  const ExpectedAlarm cases[] = {
      {"G00 X10\nG50 X0\nM30\n", alarm::kUnsupportedG, 2, 1},  // the lathe's coordinate set
      {"G71 U1 R1\nM30\n", alarm::kUnsupportedG, 1, 1},        // a turning cycle
      {"G96 S100\nM30\n", alarm::kUnsupportedG, 1, 1},         // not in seed 003
      {"G32 Z-10 F1\nM30\n", alarm::kUnsupportedG, 1, 1},      // threading
      {"G12.1\nM30\n", alarm::kUnsupportedG, 1, 1},            // polar interpolation
      {"G00 X0 U1\nM30\n", alarm::kWordNotAllowed, 1, 8},      // U is no incremental X
      {"G88 X0 Y0 Z-5 R2 F100\nM30\n", alarm::kNotInThisVersion, 1},
  };
  expect_alarms(cases, mill());
}

TEST(MillDialect, G92SetsTheCoordinatesAndG98G99AreReturnLevels) {
  RunResult r = run_ok(
      "G00 X10 Y10 Z50\nG92 X0 Y0 Z0\nG00 X5\nG99 G81 X0 Y0 Z-45 R-40 F100\nG98 X5\nM30\n", mill());
  const auto rapids = r.of(Op::rapid);
  ASSERT_GE(rapids.size(), 2u);
  EXPECT_AT(rapids[1], 15, 10, 50);  // G92: X5 is machine 15
  // G99: back to R (machine 10); G98: back to the initial level (machine 50).
  const auto hole1 = r.at_line(4);
  ASSERT_FALSE(hole1.empty());
  EXPECT_AT(hole1.back(), 10, 10, 10);
  const auto hole2 = r.at_line(5);
  ASSERT_FALSE(hole2.empty());
  EXPECT_AT(hole2.back(), 15, 10, 50);
}

TEST(MillDialect, GroupsAreTheMillsAndTheLastCodeOfAGroupWins) {
  // #4009 the hole cycle (group 09), #4002 the plane (group 02), as FANUC 0i-M numbers them.
  RunResult r = run_ok(
      "G00 Z10\nG81 X0 Y0 Z-5 R2 F100\n#100=#4009\nG80 G19 G18\n#101=#4002\n"
      "IF [#100 NE 81] #3000=1\nIF [#101 NE 18] #3000=2\nM30\n",
      mill());
  EXPECT_EQ(r.of(Op::linear).size(), 1u);
}

TEST(MillDialect, LengthCompensationAlongZ) {
  InterpreterConfig c = mill();
  c.tool_geometry[3].z = 120.0;
  c.tool_wear[3].z = 0.25;
  RunResult r = run_ok("G00 X0 Y0 Z0\nG43 H3 Z10\nG44 Z10\nG49 Z10\nG43 H3 X1 Y1\nZ0\nM30\n", c);
  const auto rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 6u);
  EXPECT_AT(rapids[1], 0, 0, 130.25);
  EXPECT_AT(rapids[2], 0, 0, 10 - 120.25);
  EXPECT_AT(rapids[3], 0, 0, 10);
  EXPECT_AT(rapids[4], 1, 1, 10);  // no Z: nothing moves along Z yet
  EXPECT_AT(rapids[5], 1, 1, 120.25);
  run_alarm("G43 H65 Z10\nM30\n", alarm::kBadWordValue, 1, 5, mill());
  run_alarm("G41 D-1 X0\nM30\n", alarm::kBadWordValue, 1, 5, mill());
}

// G41 with D: a square programmed clockwise keeps the cutter's centre D's radius outside every
// side (FANUC cutter compensation C; the lathe's nose compensation with tip 0).
TEST(MillDialect, CutterCompensationWithD) {
  InterpreterConfig c = mill();
  c.tool_geometry[2].radius = 4.0;
  c.tool_geometry[2].tip = 3;  // the lathe's tip number: the mill compensates the centre
  RunResult r = run_ok(
      "G00 X-20 Y-20 Z0\nG41 D2 G01 X0 Y0 F100\nY50\nX50\nY0\nX0\nG40 G00 X-20 Y-20\nM30\n", c);
  std::vector<Command> moves;
  for (const Command& m : r.commands) {
    if ((m.op == Op::linear || m.op == Op::arc) && m.line >= 3 && m.line <= 6) {
      moves.push_back(m);
    }
  }
  ASSERT_GE(moves.size(), 4u);
  // The side Y50 (line 3) is cut at X-4, the side X50 (line 4) at Y54.
  EXPECT_NEAR(moves.front().to[0], -4.0, 1e-9);
  bool top = false;
  for (const Command& m : moves) {
    top = top || (m.line == 4 && m.op == Op::linear && std::fabs(m.to[1] - 54.0) < 1e-9);
  }
  EXPECT_TRUE(top);
  ASSERT_FALSE(r.at_line(7).empty());
  EXPECT_AT(r.at_line(7).back(), -20, -20, 0);
}

TEST(MillDialect, HoleCyclesDrillAlongTheNormalOfThePlane) {
  // G19: the drilling axis is X; R and the bottom are X positions.
  RunResult r = run_ok("G00 X50 Y0 Z0\nG19 G81 Y5 Z5 X-10 R2 F100\nM30\n", mill());
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 1u);
  EXPECT_AT(feeds[0], -10, 5, 5);
  ASSERT_GE(r.commands.size(), 2u);
  EXPECT_AT(r.commands[r.commands.size() - 2], 50, 5, 5);  // G98: back to X50
}

// The drilling axis is the plane's normal: a channel without it cannot drill in that plane.
TEST(MillDialect, HoleCycleNeedsTheNormalAxis) {
  InterpreterConfig xy = mill();
  xy.axes.pop_back();  // X and Y only
  run_alarm("G00 X0 Y0\nG81 X5 Y5 R2 F100\nM30\n", alarm::kNoPlaneAxis, 2, -1, xy);
  InterpreterConfig xz = mill();
  xz.axes.erase(xz.axes.begin() + 1);  // X and Z: G18 drills along the missing Y
  run_alarm("G00 X0 Z0\nG18 G81 X5 Z5 R2 F100\nM30\n", alarm::kNoPlaneAxis, 2, -1, xz);
}

TEST(MillDialect, IncrementalHoleCycle) {
  // G91: R from the initial level, Z from R (FANUC); K3 holes 10 apart.
  RunResult r = run_ok("G00 X0 Y0 Z20\nG91 G99 G83 X10 Z-15 R-18 Q5. K3 F100\nM30\n", mill());
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 9u);  // 3 holes x 3 pecks (5, 5, 5 below R)
  EXPECT_AT(feeds[2], 10, 0, -13);
  EXPECT_AT(feeds[8], 30, 0, -13);
  ASSERT_GE(r.commands.size(), 2u);
  EXPECT_AT(r.commands[r.commands.size() - 2], 30, 0, 2);  // G99: at R
}

// The offsets as FANUC 0i-M's memory C numbers them: #11001+ H geometry, #10001+ H wear,
// #13001+ D geometry, #12001+ D wear.
TEST(MillDialect, OffsetsAsSystemVariables) {
  InterpreterConfig c = mill();
  c.tool_geometry[2].z = 80.0;
  RunResult r = run_ok(
      "IF [#11002 NE 80] #3000=1\n#10002=-0.5\n#13002=6\n#12002=0.1\n"
      "G43 H2 Z0\nIF [#12002 NE 0.1] #3000=2\nM30\n",
      c);
  ASSERT_EQ(r.of(Op::rapid).size(), 1u);
  EXPECT_AT(r.of(Op::rapid)[0], 0, 0, 79.5);
  RunResult d =
      run_ok("#13001=6\n#12001=-1\nG00 X-20 Y0\nG41 D1 G01 X0 F100\nY50\nG40 X-20\nM30\n", mill());
  ASSERT_FALSE(d.at_line(5).empty());
  EXPECT_NEAR(d.at_line(5).front().to[0], -5.0, 1e-9);  // radius 6 worn by 1
}

// K0 keeps the block's data and makes no hole; the next positioning block drills with it.
TEST(MillDialect, K0StoresTheHoleData) {
  RunResult r = run_ok("G00 Z10\nG81 Z-5 R2 F100 K0\nX5\nM30\n", mill());
  EXPECT_TRUE(r.at_line(2).empty());
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 1u);
  EXPECT_AT(feeds[0], 5, 0, -5);
}

TEST(MillDialect, TappingNeedsTheSpindleSpeed) {
  run_alarm("G00 Z10\nG84 X0 Y0 Z-10 R2 F100\nM30\n", alarm::kThreadLead, 2, -1, mill());
  RunResult r = run_ok("G00 Z10 S400 M03\nG84 X0 Y0 Z-10 R2 F500\nM30\n", mill());
  const auto taps = r.of(Op::thread);
  ASSERT_EQ(taps.size(), 2u);
  EXPECT_DOUBLE_EQ(taps[0].lead, 1.25);  // F/S
}

// G84 with Q: peck tapping, each peck backing off tap_retract (high-speed, the default) inside
// the thread; no rapid inside the tapped hole.
TEST(MillDialect, PeckTapping) {
  RunResult r = run_ok("G00 Z10 S500 M03\nG84 X0 Y0 Z-10 R2 Q5. F500\nM30\n", mill());
  std::vector<double> ends;
  for (const Command& c : r.at_line(2)) {
    if (c.op == Op::thread) {
      ends.push_back(c.to[2]);
    }
    if (c.op == Op::rapid) {
      EXPECT_GE(c.to[2], 2.0 - 1e-9) << "a rapid inside the thread";
    }
  }
  // In to -3, back 0.5, in to -8, back 0.5, in to -10, out to R.
  const std::vector<double> want{-3, -2.5, -8, -7.5, -10, 2};
  ASSERT_EQ(ends.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(ends[i], want[i], 1e-9) << i;
  }
}

TEST(MillDialect, ReferenceCheckAndReturn) {
  InterpreterConfig c = mill();
  c.axes[0].reference[0] = 100.0;
  c.axes[1].reference[0] = 200.0;
  run_alarm("G00 X0 Y0\nG27 X99\nM30\n", alarm::kReferencePoint, 2, -1, c);
  run_alarm("G00 X0 Y0\nG28 X5\nG29 X1 Y1\nM30\n", alarm::kReferencePoint, 3, -1, c);
  RunResult r = run_ok("G00 X0 Y0\nG28 X5 Y6\nG29 X1 Y2\nG27 X100\nM30\n", c);
  const auto back = r.at_line(3);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_AT(back[0], 5, 6);
  EXPECT_AT(back[1], 1, 2);
  ASSERT_FALSE(r.at_line(4).empty());
  EXPECT_AT(r.at_line(4).back(), 100, 2);
}

TEST(MillDialect, SingleDirectionPositioning) {
  InterpreterConfig c = mill();
  c.axes[0].approach = 2.0;
  RunResult r = run_ok("G00 X10 Y0\nG60 X5 Y3\nM30\n", c);
  const auto moves = r.at_line(2);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_AT(moves[0], 3, 3);  // below X5 first: the last move goes in +X
  EXPECT_AT(moves[1], 5, 3);
}

// The lathe dialects keep their readings of the conflicting codes.
TEST(MillDialect, TheLatheKeepsItsMeanings) {
  RunResult r = run_ok("G00 X100 Z5\nG90 X80 Z-30 F0.2\nM30\n");  // G90: turning cycle
  EXPECT_EQ(r.of(Op::linear).size(), 2u);
  run_alarm("G43 H1 Z10\nM30\n", alarm::kUnsupportedG, 1, 1);
}

}  // namespace
}  // namespace mcnc::interp::test
