// G07.1 cylindrical interpolation (spec dafeng L612-710) in the interpreter: the rotary axis in
// degrees on the unrolled cylinder, lines as lines, arcs as chords, F along the surface.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kZ = 1;
constexpr std::size_t kC = 2;

InterpreterConfig cylinder_lathe() {
  InterpreterConfig c;
  c.axes = {AxisConfig{'X', true}, AxisConfig{'Z', false}, AxisConfig{'C', false, true}};
  return c;
}

// The length around the cylinder of radius 60 of `degrees`.
double around(double degrees) {
  return degrees * M_PI * 60.0 / 180.0;
}

const char* const kSlot =
    "G00 X120 Z100 C0\nG19\nG07.1 C60\nG01 Z120 F300\nG01 C30\nG02 Z90 C60 R30\nG07.1 C0\n"
    "G00 C0\nM30\n";

TEST(InterpCylindrical, LinesStayLinesAndArcsBecomeChordsOnTheCircle) {
  RunResult r = run_ok(kSlot, cylinder_lathe());
  ASSERT_EQ(r.at_line(5).size(), 1u);
  EXPECT_AT(r.at_line(5)[0], 60, 120, 30);  // C30 are degrees on the machine
  const std::vector<Command> chords = r.at_line(6);
  ASSERT_GT(chords.size(), 10u);
  EXPECT_AT(chords.back(), 60, 90, 60);
  // Every chord end on the circle of radius 30 through (C30, Z120) and (C60, Z90), unrolled:
  // its centre is on the side that makes the arc clockwise in the (C, Z) plane of G19.
  const double ds = around(30.0);
  const double d = std::hypot(ds, 30.0);
  const double h = std::sqrt(30.0 * 30.0 - d * d / 4.0);
  const double cs = around(30.0) + ds / 2.0 - h * (-(-30.0) / d);
  const double cz = 120.0 - 30.0 / 2.0 - h * (ds / d);
  for (const Command& c : chords) {
    EXPECT_NEAR(std::hypot(around(c.to[kC]) - cs, c.to[kZ] - cz), 30.0, 1e-9);
  }
  EXPECT_AT(r.of(Op::rapid).back(), 60, 90, 0);  // G07.1 C0: C back in degrees
}

// F is the speed on the surface: the machine lines take as long as the programmed contour at F
// (Z20, C30 around the cylinder, the arc of R30).
TEST(InterpCylindrical, TheFeedIsTheSpeedOnTheSurface) {
  RunResult r = run_ok(kSlot, cylinder_lathe());
  const double minutes = minutes_at_feed(r, r.of(Op::rapid).front().to, 3);
  const double chord = std::hypot(around(30.0), 30.0);
  const double contour = 20.0 + around(30.0) + 30.0 * 2.0 * std::asin(chord / 60.0);
  EXPECT_NEAR(minutes, contour / 300.0, 1e-9);
}

// G42 works on the unrolled surface: a cutter of radius 2 along +C runs 2 below the line, and
// down -Z 2 before C30 (the inside corner: lengths around the cylinder, 2 mm of C60).
TEST(InterpCylindrical, CompensationWorksOnTheUnrolledSurface) {
  RunResult r = run_ok(
      "T0101\nG00 X120 Z100 C0\nG19\nG07.1 C60\nG42 G01 Z120 F300\nG01 C30\nG01 Z100\n"
      "G40 C40\nG07.1 C0\nM30\n",
      with_nose_radius(cylinder_lathe(), 2.0));
  ASSERT_EQ(r.at_line(6).size(), 1u);
  EXPECT_AT(r.at_line(6)[0], 60, 118, 30 - 2.0 * 180.0 / (M_PI * 60.0));
  EXPECT_AT(r.at_line(7).back(), 60, 100, 30 - 2.0 * 180.0 / (M_PI * 60.0));
}

TEST(InterpCylindrical, MisuseIsAnAlarm) {
  const ExpectedAlarm cases[] = {
      {"G19\nG07.1 C60 Z10\nM30\n", alarm::kMustBeAlone, 2, 11},
      {"G19\nG07.1\nM30\n", alarm::kCycleWordMissing, 2},
      {"G19\nG07.1 C-60\nM30\n", alarm::kBadWordValue, 2},
      {"G19\nG42 G01 Z10 F100\nG07.1 C60\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G68.1 X0 Z0 R10\nG07.1 C60\nM30\n", alarm::kInterpolationModeRestriction, 2},
      {"G07.1 C60\nM30\n", alarm::kInterpolationModeRestriction, 1},  // G18: no C in the plane
      {"G19\nG07.1 C60\nG00 Z10\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G19\nG07.1 C60\nG41 G01 Z10 F100\nG07.1 C0\nM30\n", alarm::kInterpolationModeRestriction,
       4},  // G07.1 C0 under G41
      {"G19\nG07.1 C60\nG07.1 C50\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G19\nG07.1 C60\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G19\nG07.1 C60\nG16\nM30\n", alarm::kInterpolationModeRestriction, 3},  // G12.1's only
      {"G19\nG52 H10\nG07.1 C60\nM30\n", alarm::kInterpolationModeRestriction, 3},
  };
  expect_alarms(cases, cylinder_lathe());
  run_ok("G19\nG107 C60\nG01 Z10 F100\nG107 C0\nM30\n", cylinder_lathe());  // G107 is G07.1
}

}  // namespace
}  // namespace mcnc::interp::test
