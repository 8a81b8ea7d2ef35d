// Arcs: G02/G03 with I/K and R, planes, helical turns, full circles and the arc alarms
// (spec dafeng §2.2 G02/G03 and helical, GSK D2-9).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

Command only_arc(const RunResult& r) {
  auto arcs = r.of(Op::arc);
  EXPECT_EQ(arcs.size(), 1u);
  return arcs.empty() ? Command{} : arcs[0];
}

TEST(InterpArcs, IkAndRGiveTheSameQuarterArc) {
  for (const char* block : {"G02 X58 Z30 I20 K0 F30", "G02 U40 W-20 I20 K0 F30",
                            "G02 X58 Z30 R20 F30", "G02 U40 W-20 R20. F30"}) {
    RunResult r = run_ok(std::string("G00 X18 Z50\n") + block + "\nM30\n");
    const Command a = only_arc(r);
    EXPECT_EQ(a.direction, ArcDirection::cw) << block;
    EXPECT_EQ(a.plane, Plane::zx) << block;
    EXPECT_NEAR(a.to[0], 29, 1e-9) << block;
    EXPECT_NEAR(a.to[1], 30, 1e-9) << block;
    // centre_axes name the plane axes; the centre is (X 29, Z 50) physical.
    double cx = a.center_axes[0] == 0 ? a.center[0] : a.center[1];
    double cz = a.center_axes[0] == 1 ? a.center[0] : a.center[1];
    EXPECT_NEAR(cx, 29, 1e-9) << block;
    EXPECT_NEAR(cz, 50, 1e-9) << block;
    EXPECT_EQ(a.turns, 0);
    EXPECT_NEAR(a.feed, 30, 1e-9);
  }
}

TEST(InterpArcs, NegativeRChoosesTheLongArc) {
  InterpreterConfig c = lathe();
  c.axes[0].diameter = false;
  const double h = std::sqrt(75.0);
  RunResult shortr = run_ok("G02 X0 Z-10 R10 F100\nM30\n", c);
  RunResult longr = run_ok("G02 X0 Z-10 R-10 F100\nM30\n", c);
  const Command s = only_arc(shortr);
  const Command l = only_arc(longr);
  auto cx = [](const Command& a) { return a.center_axes[0] == 0 ? a.center[0] : a.center[1]; };
  auto cz = [](const Command& a) { return a.center_axes[0] == 1 ? a.center[0] : a.center[1]; };
  EXPECT_NEAR(cx(s), h, 1e-9);
  EXPECT_NEAR(cz(s), -5, 1e-9);
  EXPECT_NEAR(cx(l), -h, 1e-9);
  EXPECT_NEAR(cz(l), -5, 1e-9);
}

TEST(InterpArcs, G03ReversesTheCentreForR) {
  InterpreterConfig c = lathe();
  c.axes[0].diameter = false;
  RunResult r = run_ok("G03 X0 Z-10 R10 F100\nM30\n", c);
  const Command a = only_arc(r);
  EXPECT_EQ(a.direction, ArcDirection::ccw);
  double cx = a.center_axes[0] == 0 ? a.center[0] : a.center[1];
  EXPECT_NEAR(cx, -std::sqrt(75.0), 1e-9);
}

TEST(InterpArcs, FullCircleWithIk) {
  RunResult r = run_ok("G00 X20 Z0\nG02 I5 K0 F100\nM30\n");
  const Command a = only_arc(r);
  EXPECT_NEAR(a.to[0], 10, 1e-9);
  EXPECT_NEAR(a.to[1], 0, 1e-9);
  double cx = a.center_axes[0] == 0 ? a.center[0] : a.center[1];
  EXPECT_NEAR(cx, 15, 1e-9);  // I is a radius value
  EXPECT_EQ(a.turns, 0);
}

TEST(InterpArcs, FullCircleWithRIsAnAlarm) {
  run_alarm("G00 X20 Z0\nG02 X20 Z0 R5 F100\nM30\n", alarm::kArcFullCircleWithR, 2);
}

TEST(InterpArcs, RTooSmallIsAnAlarm) {
  InterpreterConfig c = lathe();
  c.axes[0].diameter = false;
  run_alarm("G00 X0\nG02 X0 Z-10 R4 F100\nM30\n", alarm::kArcGeometry, 2, -1, c);
}

TEST(InterpArcs, EndPointOffTheCircleIsAnAlarmBeyondTolerance) {
  // From (X9, Z50) with centre (29, 50) the radius is 20; an end at radius 20.5 is off by 0.5.
  run_alarm("G00 X18 Z50\nG02 X58 Z29.5 I20 K0 F30\nM30\n", alarm::kArcGeometry, 2);
  // Within the tolerance (0.01 mm) it is accepted.
  RunResult r = run_ok("G00 X18 Z50\nG02 X58 Z29.995 I20 K0 F30\nM30\n");
  EXPECT_EQ(r.of(Op::arc).size(), 1u);
}

TEST(InterpArcs, ArcCheckCanBeSwitchedOff) {
  InterpreterConfig c = lathe();
  c.arc_check = false;
  RunResult r = run_ok("G00 X18 Z50\nG02 X58 Z29.5 I20 K0 F30\nM30\n", c);
  EXPECT_EQ(r.of(Op::arc).size(), 1u);
}

TEST(InterpArcs, ArcWithoutFeedIsAnAlarm) {
  run_alarm("G00 X10\nG02 X30 Z-10 R10\nM30\n", alarm::kFeedMissing, 2);
}

TEST(InterpArcs, HelicalExtraTurns) {
  InterpreterConfig c = lathe_xyz();
  RunResult r = run_ok("G00 X100 Y0 Z0\nG17\nG03 X100 Y0 Z-10 I-50 J0 F500 L3\nM30\n", c);
  const Command a = only_arc(r);
  EXPECT_EQ(a.plane, Plane::xy);
  EXPECT_EQ(a.turns, 2);  // a full circle plus 2 extra turns = 3 turns
  EXPECT_NEAR(a.to[2], -10, 1e-9);
  EXPECT_NEAR(a.center[0], 0, 1e-9);
  EXPECT_NEAR(a.center[1], 0, 1e-9);
}

TEST(InterpArcs, HelicalLOnAPartialArc) {
  InterpreterConfig c = lathe_xyz();
  c.axes[0].diameter = false;
  RunResult r = run_ok("G17\nG00 X10 Y0 Z0\nG03 X0 Y10 Z-5 R10 F100 L2\nM30\n", c);
  const Command a = only_arc(r);
  EXPECT_EQ(a.turns, 1);
}

TEST(InterpArcs, HelicalLMustBeWhole) {
  InterpreterConfig c = lathe_xyz();
  run_alarm("G17\nG03 X0 Y0 Z-1 I-5 F100 L1.5\nM30\n", alarm::kBadWordValue, 2, -1, c);
}

TEST(InterpArcs, G19PlaneUsesJK) {
  InterpreterConfig c = lathe_xyz();
  RunResult r = run_ok("G19\nG02 Y10 Z10 J0 K10 F100\nM30\n", c);
  const Command a = only_arc(r);
  EXPECT_EQ(a.plane, Plane::yz);
}

TEST(InterpArcs, G17WithoutYAxisIsAnAlarm) {
  RunResult r = run("G17\nG02 X10 Y10 R5 F100\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_TRUE(r.alarm->number == alarm::kNoPlaneAxis || r.alarm->number == alarm::kUnknownAddress)
      << r.alarm->number;
}

TEST(InterpArcs, G02IsModal) {
  InterpreterConfig c = lathe();
  c.axes[0].diameter = false;
  RunResult r = run_ok("G02 X0 Z-10 R5 F100\nX0 Z-20 R5\nM30\n", c);
  EXPECT_EQ(r.of(Op::arc).size(), 2u);
}

TEST(InterpArcs, GskRWithoutEndPointIsNoMotion) {
  // GSK D2-9: `G02 R5` with no end point is a 0-degree arc: no motion, no alarm.
  RunResult r = run("G00 X10\nG02 R5 F100\nG00 X20\nM30\n", gsk());
  EXPECT_FALSE(r.alarm.has_value()) << (r.alarm ? r.alarm->text : "");
  EXPECT_EQ(r.of(Op::arc).size(), 0u);
}

}  // namespace
}  // namespace mcnc::interp::test
