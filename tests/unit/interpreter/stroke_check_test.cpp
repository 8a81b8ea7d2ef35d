// G22 / G23, the stored stroke check 2 (spec dafeng L2393-2435, gsk A.6.17): the forbidden area
// stops a move before it leaves the interpreter, with the limits from the block (formats ① and
// ②) or the parameters, inside or outside forbidden; and the alarms of bad G22 blocks.
#include "channel/interp/dialect.hpp"
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

// X 20..100 (diameters: 10..50 mm) and Z -50..50 forbidden.
constexpr const char* kZone = "G22 X100 Z50 I20 K-50\n";

TEST(InterpStrokeCheck, AMoveIntoTheAreaIsAnAlarmBeforeItLeaves) {
  RunResult r = run_alarm(std::string(kZone) + "G00 X0 Z60\nG01 X60 F100\nG01 Z40\nM30\n",
                          alarm::kStrokeLimit, 4);
  ASSERT_EQ(r.commands.size(), 2u);  // the moves before it only
  EXPECT_NE(r.alarm->text.find("X 20.000..100.000"), std::string::npos) << r.alarm->text;
}

TEST(InterpStrokeCheck, AMoveThroughTheAreaIsAnAlarmItsEndsOutside) {
  run_alarm(std::string(kZone) + "G00 X0 Z0\nG00 X120\nM30\n", alarm::kStrokeLimit, 3);
  // The same move above the area in Z is free.
  run_ok(std::string(kZone) + "G00 X0 Z60\nG00 X120\nG00 Z100\nM30\n");
}

TEST(InterpStrokeCheck, AnArcThatBulgesIntoTheAreaIsAnAlarm) {
  // Half circles from X0 Z55 to X80 Z55 (both ends above the area, Z > 50): G03 passes Z 75,
  // clear; G02 passes Z 35 at X 40 (20 mm), inside.
  run_alarm(
      std::string(kZone) + "G00 X0 Z55\nG03 X80 Z55 R20 F100\nG00 X0\nG02 X80 Z55 R20 F100\nM30\n",
      alarm::kStrokeLimit, 5);
}

TEST(InterpStrokeCheck, G23AllowsTheAreaAndG22AloneTakesTheParameters) {
  run_ok(std::string(kZone) + "G23\nG00 X0 Z0\nG00 X120\nM30\n");
  InterpreterConfig c = lathe();
  c.axes[0].stroke_minus = 10;  // physical: X20 as a diameter
  c.axes[0].stroke_plus = 50;
  run_alarm("G22\nG00 X120\nM30\n", alarm::kStrokeLimit, 2, -1, c);
  run_ok("G22\nG00 Z-200\nG23\nG00 X120\nM30\n", c);
}

TEST(InterpStrokeCheck, FormatTwoSetsOneSideOfOneAxis) {
  // Z above 20 forbidden (P2 = the - limit; no + limit): X moves anywhere below.
  const std::string zone = "G22 Z20 P2\n";
  run_ok(zone + "G00 X300 Z10\nG00 X0\nG00 Z20\nM30\n");
  run_alarm(zone + "G00 Z30\nM30\n", alarm::kStrokeLimit, 2);
  // With the + limit Z 40 of another G22 the area ends there: above it is free.
  InterpreterConfig c = lathe();
  c.axes[1].start = 60;
  run_ok("G22 Z40 P1\n" + zone + "G00 Z100\nG00 X0\nM30\n", c);
  run_alarm("G22 Z40 P1\n" + zone + "G00 Z39\nM30\n", alarm::kStrokeLimit, 3, -1, c);
}

TEST(InterpStrokeCheck, OutsideForbiddenMakesTheLimitsTravelLimits) {
  InterpreterConfig c = lathe();
  c.stroke_inside_forbidden = false;
  run_ok("G22 X100 Z50 I0 K-50\nG00 X80 Z-40\nG00 X0 Z50\nM30\n", c);
  run_alarm("G22 X100 Z50 I0 K-50\nG00 X80 Z-40\nG00 Z-60\nM30\n", alarm::kStrokeLimit, 3, -1, c);
}

TEST(InterpStrokeCheck, TheModeReadsAs4009) {
  run_ok("IF[#4009 NE 23] #3000=1(G23 at power-on)\n" + std::string(kZone) +
         "IF[#4009 NE 22] #3000=2(G22)\nG23\nIF[#4009 NE 23] #3000=3(G23)\nM30\n");
}

TEST(InterpStrokeCheck, Alarms) {
  const ExpectedAlarm cases[] = {
      // The tool stands in the area.
      {"G00 X40 Z0\nG22 X100 Z50 I20 K-50\nM30\n", alarm::kStrokeLimit, 2},
      // - limit not below the + limit.
      {"G22 X20 Z50 I100 K-50\nM30\n", alarm::kBadWordValue, 1},
      // Machine positions are absolute.
      {"G22 U100 Z50\nM30\n", alarm::kWordNotAllowed, 1},
      {"G22 X100 P3\nM30\n", alarm::kBadWordValue, 1},
      {"G22 P1\nM30\n", alarm::kBadWordValue, 1},
      // Format ② takes no I/J/K; a channel without Y has no J.
      {"G00 X120\nG22 X100 P1 I20\nM30\n", alarm::kWordNotAllowed, 2},
      {"G00 X120\nG22 X100 J20\nM30\n", alarm::kWordNotAllowed, 2},
      // Without words and without parameters.
      {"G22\nM30\n", alarm::kBadWordValue, 1},
      // Another code wanting the axis words.
      {"G22 G04 X100\nM30\n", alarm::kGroupConflict, 1},
  };
  expect_alarms(cases);
  InterpreterConfig mill;
  select_dialect(mill, Dialect::fanuc_mill);
  run_alarm("G22 X100 Y100 Z50 I0 J0 K0\nM30\n", alarm::kUnsupportedG, 1, -1, mill);
}

}  // namespace
}  // namespace mcnc::interp::test
