// G05 / G05.1, the arc through three points (gsk A.6.4; Dafeng's appendix L8086): the centre
// and the sense the middle point gives, the mode, and the alarms of rules 2, 3 and 5.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

// The centre of arc `a` as (X, Z) physical on the lathe (X is axis 0, Z axis 1).
std::array<double, 2> center_xz(const Command& a) {
  const double x = a.center_axes[0] == 0 ? a.center[0] : a.center[1];
  const double z = a.center_axes[0] == 1 ? a.center[0] : a.center[1];
  return {x, z};
}

// Start X18 Z50 (radius 9), middle X26 Z38 (radius 13), end X58 Z30: on the circle about
// X29 (radius) Z50 of radius 20, clockwise in the ZX plane as G02 I20 K0 cuts it.
TEST(InterpThreePointArc, RelativeMiddlePointGivesTheG02Arc) {
  for (const InterpreterConfig& c : {lathe(), gsk()}) {
    RunResult r = run_ok("G00 X18 Z50\nG05 X58 Z30 I4 K-12 F30\nM30\n", c);
    const auto arcs = r.of(Op::arc);
    ASSERT_EQ(arcs.size(), 1u);
    EXPECT_EQ(arcs[0].direction, ArcDirection::cw);
    EXPECT_EQ(arcs[0].plane, Plane::zx);
    EXPECT_NEAR(center_xz(arcs[0])[0], 29, 1e-9);
    EXPECT_NEAR(center_xz(arcs[0])[1], 50, 1e-9);
    EXPECT_NEAR(arcs[0].to[0], 29, 1e-9);
    EXPECT_NEAR(arcs[0].to[1], 30, 1e-9);
    EXPECT_NEAR(arcs[0].feed, 30, 1e-9);
  }
}

TEST(InterpThreePointArc, AbsoluteMiddlePointIsGsksG051InXsDiameter) {
  RunResult r = run_ok("G00 X18 Z50\nG05.1 X58 Z30 I26 K38 F30\nM30\n", gsk());
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].direction, ArcDirection::cw);
  EXPECT_NEAR(center_xz(arcs[0])[0], 29, 1e-9);
  EXPECT_NEAR(center_xz(arcs[0])[1], 50, 1e-9);
  // Dafeng's appendix has no G05.1.
  run_alarm("G00 X18 Z50\nG05.1 X58 Z30 I26 K38 F30\nM30\n", alarm::kUnsupportedG, 2);
}

TEST(InterpThreePointArc, TheModeStaysAndTheMiddlePointTurnsTheSense) {
  // Back from X58 Z30 through the same middle point: counter-clockwise; then the long way
  // round through a middle point beyond the end (X58 Z70 lies on the circle too).
  RunResult r = run_ok(
      "G00 X18 Z50\nG05 X58 Z30 I4 K-12 F30\nX18 Z50 I-16 K8\nX58 Z30 I20 K20\nM30\n", gsk());
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 3u);
  EXPECT_EQ(arcs[0].direction, ArcDirection::cw);
  EXPECT_EQ(arcs[1].direction, ArcDirection::ccw);
  EXPECT_EQ(arcs[2].direction, ArcDirection::ccw);
  for (const Command& a : arcs) {
    EXPECT_NEAR(center_xz(a)[0], 29, 1e-9);
    EXPECT_NEAR(center_xz(a)[1], 50, 1e-9);
  }
}

TEST(InterpThreePointArc, AnOmittedWordKeepsTheStartsCoordinate) {
  // Start X20 Z50 and end X20 Z30: K-10 alone leaves the middle point on X20, the three on one
  // line; with I10 (a radius) it is X40 Z40, and the arc is the half circle about X10 Z40
  // (radius values), counter-clockwise as the ZX plane is seen.
  run_alarm("G00 X20 Z50\nG05 X20 Z30 K-10 F30\nM30\n", alarm::kArcGeometry, 2);
  RunResult r = run_ok("G00 X20 Z50\nG05 X20 Z30 I10 K-10 F30\nM30\n");
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_NEAR(center_xz(arcs[0])[0], 10, 1e-9);
  EXPECT_NEAR(center_xz(arcs[0])[1], 40, 1e-9);
  EXPECT_EQ(arcs[0].direction, ArcDirection::ccw);
}

TEST(InterpThreePointArc, AlarmsOfTheRules) {
  const ExpectedAlarm cases[] = {
      // Rule 3: I and K both omitted.
      {"G00 X18 Z50\nG05 X58 Z30 F30\nM30\n", alarm::kArcGeometry, 2},
      // Rule 2: collinear points.
      {"G00 X0 Z0\nG05 X20 Z-10 I5 K-5 F30\nM30\n", alarm::kArcGeometry, 2},
      // Rule 5: no full circle.
      {"G00 X18 Z50\nG05 X18 Z50 I4 K-12 F30\nM30\n", alarm::kArcGeometry, 2},
      // No feed.
      {"G00 X18 Z50\nG05 X58 Z30 I4 K-12\nM30\n", alarm::kFeedMissing, 2},
  };
  expect_alarms(cases);
  expect_alarms(cases, gsk());
}

}  // namespace
}  // namespace mcnc::interp::test
