// G10.9, the per-axis diameter/radius switch (spec dafeng L3959-4023): the moves after it, the
// data it leaves alone (G53, G10 L2, #5201..), the end of the program, and its alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

double x_of(const Command& c) {
  return c.to[0];
}

// The spec's example without its polar square: X50 in radius is X100 in diameter.
TEST(InterpDiameterSwitch, RadiusProgrammingMovesTheSameNumberTwiceAsFar) {
  RunResult r =
      run_ok("G00 X100 Z0\nG10.9 X0\nG00 X50\nG01 U10 F100\nG10.9 X1\nG00 X200\nU10\nM30\n");
  const auto moves = r.of(Op::rapid);
  ASSERT_EQ(moves.size(), 4u);
  EXPECT_NEAR(x_of(moves[0]), 50, 1e-9);
  EXPECT_NEAR(x_of(moves[1]), 50, 1e-9);             // X50 in radius: where X100 in diameter is
  EXPECT_NEAR(x_of(r.of(Op::linear)[0]), 60, 1e-9);  // U10 in radius: 10 mm
  EXPECT_NEAR(x_of(moves[2]), 100, 1e-9);
  EXPECT_NEAR(x_of(moves[3]), 105, 1e-9);  // U10 in diameter again: 5 mm
}

TEST(InterpDiameterSwitch, ARadiusAxisBecomesADiameter) {
  InterpreterConfig c = lathe_xyz();
  RunResult r = run_ok("G10.9 Y1\nG00 Y40\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 2u);
  EXPECT_NEAR(r.commands[0].to[1], 20, 1e-9);
}

TEST(InterpDiameterSwitch, PositionsReadInTheSwitchedUnitDataInTheParameters) {
  InterpreterConfig c = lathe();
  RunResult r = run_ok(
      "G00 X100 Z0\nG10.9 X0\nG4I0\n"
      "IF[#5001 NE 50] #3000=1(5001 in radius)\n"
      "IF[#5021 NE 100] #3000=2(5021 machine as the parameter)\n"
      "G53 X100\n"       // G53 is not switched: X100 is a diameter
      "G10 L2 P1 X20\n"  // nor are the work offsets: X20 a diameter, 10 mm
      "IF[#5221 NE 20] #3000=3(5221)\n"
      "G00 X0\n"
      "M30\n",
      c);
  const auto moves = r.of(Op::rapid);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_NEAR(x_of(moves[1]), 50, 1e-9);
  EXPECT_NEAR(x_of(moves[2]), 10, 1e-9);
}

TEST(InterpDiameterSwitch, CyclesReadTheSwitchedUnit) {
  // G90 X in radius: the cut at X 20 mm.
  RunResult r = run_ok("G00 X100 Z2\nG10.9 X0\nG90 X20 Z-10 F100\nM30\n");
  const auto cuts = r.of(Op::linear);
  ASSERT_FALSE(cuts.empty());
  EXPECT_NEAR(x_of(cuts[0]), 20, 1e-9);
}

TEST(InterpDiameterSwitch, Alarms) {
  const ExpectedAlarm cases[] = {
      // Alone in its block (L3971 rule 1).
      {"G10.9 X0 G00\nM30\n", alarm::kMustBeAlone, 1},
      {"G10.9 X0 M03\nM30\n", alarm::kMustBeAlone, 1},
      {"G10.9 X0 F100\nM30\n", alarm::kMustBeAlone, 1},
      // 0 or 1 only.
      {"G10.9 X2\nM30\n", alarm::kBadWordValue, 1},
      // An axis is needed; the incremental address is not the axis.
      {"G10.9\nM30\n", alarm::kBadWordValue, 1},
      {"G10.9 U0\nM30\n", alarm::kWordNotAllowed, 1},
  };
  expect_alarms(cases);
  InterpreterConfig c = lathe();
  c.axes.push_back(AxisConfig{'C', false, true});
  run_alarm("G10.9 C1\nM30\n", alarm::kBadWordValue, 1, -1, c);
}

}  // namespace
}  // namespace mcnc::interp::test
