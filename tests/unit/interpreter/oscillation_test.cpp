// G81.1 / G80.1 sine-profile oscillation (spec dafeng L2454-2505): the commands that hand the
// oscillation to the planner, the axis held while it oscillates, and the alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

// The lathe with Z enabled for oscillation (param 5700.1).
InterpreterConfig oscillating_z() {
  InterpreterConfig c = lathe();
  c.axes[kZ].oscillation = true;
  return c;
}

TEST(InterpOscillation, TheSpecsExample) {
  // L2491-2501: Z between 0 and 100 at 2000 mm/min while X feeds; G80.1 Z0 ends it at Z0.
  RunResult r = run_ok(
      "O1000\nT0001\nG00 X51 Z0\nG81.1 Z0 Q100 F2000\nG01 X50 F10\nG00 X100\nG80.1 Z0\nM30\n",
      oscillating_z());
  const auto on = r.of(Op::oscillate);
  ASSERT_EQ(on.size(), 1U);
  EXPECT_EQ(on[0].line, 4);
  EXPECT_EQ(on[0].oscillating, static_cast<int>(kZ));
  EXPECT_EQ(on[0].axis, 'Z');
  EXPECT_DOUBLE_EQ(on[0].top, 0.0);
  EXPECT_DOUBLE_EQ(on[0].bottom, 100.0);
  EXPECT_DOUBLE_EQ(on[0].feed, 2000.0);
  EXPECT_DOUBLE_EQ(on[0].to[kX], 25.5);  // where the axes stand
  // The moves in between keep Z where G81.1 found it; F2000 is not their feed.
  const auto lines = r.of(Op::linear);
  ASSERT_EQ(lines.size(), 1U);
  EXPECT_DOUBLE_EQ(lines[0].feed, 10.0);
  EXPECT_DOUBLE_EQ(lines[0].to[kZ], 0.0);
  const auto off = r.of(Op::oscillate_end);
  ASSERT_EQ(off.size(), 1U);
  EXPECT_EQ(off[0].line, 7);
  EXPECT_EQ(off[0].oscillating, static_cast<int>(kZ));
  EXPECT_DOUBLE_EQ(off[0].to[kZ], 0.0);
  EXPECT_DOUBLE_EQ(off[0].to[kX], 50.0);
}

TEST(InterpOscillation, PointsAreMachinePositionsAndTheModalFeedStays) {
  // A work offset of Z+10 (G50 Z-10 where the tool stands at machine 0): the dead points move
  // with it. Q may be negative: the bottom below the top. G80.1 Z5 ends at another point.
  RunResult r =
      run_ok("G98 G01 X20 F150\nG50 X20 Z-10\nG81.1 Z-2 Q-6 F600\nG01 X10\nG80.1 Z5\nG01 Z0\nM30\n",
             oscillating_z());
  const auto on = r.of(Op::oscillate);
  ASSERT_EQ(on.size(), 1U);
  EXPECT_DOUBLE_EQ(on[0].top, 8.0);
  EXPECT_DOUBLE_EQ(on[0].bottom, 2.0);
  const auto lines = r.of(Op::linear);
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_DOUBLE_EQ(lines[1].feed, 150.0);  // G81.1's F600 changed nothing
  EXPECT_DOUBLE_EQ(lines[1].to[kZ], 0.0);
  const auto off = r.of(Op::oscillate_end);
  ASSERT_EQ(off.size(), 1U);
  EXPECT_DOUBLE_EQ(off[0].to[kZ], 15.0);
  // The program goes on from there.
  EXPECT_DOUBLE_EQ(lines[2].to[kZ], 10.0);
}

TEST(InterpOscillation, ADiameterAxisTakesItsValuesAsDiameters) {
  InterpreterConfig c = lathe();
  c.axes[kX].oscillation = true;
  RunResult r = run_ok("G81.1 X40 Q-10 F500\nG01 Z-5 F100\nG80.1 X50\nM30\n", c);
  const auto on = r.of(Op::oscillate);
  ASSERT_EQ(on.size(), 1U);
  EXPECT_DOUBLE_EQ(on[0].top, 20.0);
  EXPECT_DOUBLE_EQ(on[0].bottom, 15.0);
  EXPECT_DOUBLE_EQ(r.of(Op::oscillate_end)[0].to[kX], 25.0);
}

TEST(InterpOscillation, APositionTakenOverKeepsTheOscillatingAxisWhereG811FoundIt) {
  // The channel hands the interpreter where its axes stand (after G141, M18, G31): Z is then
  // anywhere in its stroke, and the blocks after still keep it where G81.1 found it.
  Interpreter in(oscillating_z());
  ASSERT_FALSE(in.start("G00 X20 Z1\nG81.1 Z1 Q5 F600\nG01 X30 F100\nG80.1 Z1\nM30\n", "T.nc"));
  std::vector<Command> got;
  while (auto r = in.next()) {
    ASSERT_TRUE(std::holds_alternative<Command>(*r)) << std::get<ProgramAlarm>(*r).text;
    got.push_back(std::get<Command>(*r));
    if (got.back().op == Op::oscillate) {
      in.set_machine_position(AxisVector{10.0, 3.7});
    }
    if (got.back().op == Op::end) {
      break;
    }
  }
  ASSERT_EQ(got.size(), 5U);
  EXPECT_EQ(got[2].op, Op::linear);
  EXPECT_DOUBLE_EQ(got[2].to[kZ], 1.0);
  EXPECT_DOUBLE_EQ(got[2].to[kX], 15.0);
}

TEST(InterpOscillation, Alarms) {
  const ExpectedAlarm cases[] = {
      // The oscillating axis belongs to the oscillation until G80.1.
      {"G81.1 Z0 Q10 F100\nG01 Z5 F100\nM30\n", alarm::kOscillation, 2},
      {"G81.1 Z0 Q10 F100\nG01 W5 F100\nM30\n", alarm::kOscillation, 2},
      {"G81.1 Z0 Q10 F100\nG81.1 Z0 Q10 F100\nM30\n", alarm::kOscillation, 2},
      {"G80.1 Z0\nM30\n", alarm::kOscillation, 1},
      // The program does not end with the axis oscillating.
      {"G81.1 Z0 Q10 F100\nM30\n", alarm::kOscillation, 2},
      {"G81.1 Z0 Q10 F100\nM02\n", alarm::kOscillation, 2},
      // Words.
      {"G81.1 Z0 F100\nM30\n", alarm::kCycleWordMissing, 1},
      {"G81.1 Q10 F100\nM30\n", alarm::kCycleWordMissing, 1},
      {"G81.1 Z0 Q10\nM30\n", alarm::kFeedMissing, 1},
      {"G81.1 Z0 Q0 F100\nM30\n", alarm::kBadWordValue, 1},
      {"G81.1 Z0 Q10 F0\nM30\n", alarm::kBadWordValue, 1},
      {"G81.1 W0 Q10 F100\nM30\n", alarm::kWordNotAllowed, 1},
      {"G81.1 Z0 X10 Q10 F100\nM30\n", alarm::kWordNotAllowed, 1},
      {"G81.1 Z0 Q10 F100 P2\nM30\n", alarm::kWordNotAllowed, 1},
      {"G81.1 Z0 Q10 F100\nG80.1\nM30\n", alarm::kCycleWordMissing, 2},
      {"G81.1 Z0 Q10 F100\nG80.1 Z0 Q5\nM30\n", alarm::kWordNotAllowed, 2},
      {"G81.1 Z0 Q10 F100\nG80.1 X0\nM30\n", alarm::kOscillation, 2},
      {"G04 G81.1 Z0 Q10 F100\nM30\n", alarm::kGroupConflict, 1},
      {"G68.1 Z0 X0 R30\nG81.1 Z0 Q10 F100\nM30\n", alarm::kFrameRestriction, 2},
      // G22: the strokes and G80.1's end stay out of the forbidden area (Z 30..50 here).
      {"G22 X100 Z50 I-100 K30\nG81.1 Z0 Q40 F100\nM30\n", alarm::kStrokeLimit, 2},
      {"G22 X100 Z50 I-100 K30\nG81.1 Z0 Q20 F100\nG80.1 Z45\nM30\n", alarm::kStrokeLimit, 3},
      // It stays in this channel while it oscillates.
      {"G81.1 Z0 Q10 F100\nG140 Z1\nM30\n", alarm::kOscillation, 2},
  };
  expect_alarms(cases, oscillating_z());
  // An axis that param 5700.1 does not enable.
  run_alarm("G81.1 X0 Q10 F100\nM30\n", alarm::kOscillation, 1, -1, oscillating_z());
  run_alarm("G81.1 Z0 Q10 F100\nM30\n", alarm::kOscillation, 1);
  run_ok("G22 X100 Z50 I-100 K30\nG81.1 Z0 Q20 F100\nG80.1 Z25\nM30\n", oscillating_z());
  // The blocks before the bad move run; the move never leaves.
  RunResult r = run("G00 X10\nG81.1 Z0 Q10 F100\nG01 Z5 F100\nM30\n", oscillating_z());
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.of(Op::oscillate).size(), 1U);
  EXPECT_TRUE(r.of(Op::linear).empty());
}

}  // namespace
}  // namespace mcnc::interp::test
