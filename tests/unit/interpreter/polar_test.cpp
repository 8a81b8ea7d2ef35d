// G12.1 / G13.1 polar interpolation (spec dafeng L711-849) in the interpreter: the moves of the
// polar plane leave as machine lines of the linear and rotary axes, at the tangential feed.
#include "channel/interp/dialect.hpp"
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr std::size_t kA = 2;

InterpreterConfig polar_lathe() {
  InterpreterConfig c;
  c.axes = {AxisConfig{'X', true}, AxisConfig{'Z', false}, AxisConfig{'A', false, true}};
  c.polar_linear = 'X';
  c.polar_rotary = 'A';
  return c;
}

// The spec's contour (L804-849) without its nose compensation.
const char* const kSquare =
    "G00 X120 A30 Z0\nG12.1\nG01 A0 X40 F500\nG01 A10\nG03 X20 A20 R10\nG01 X-40\nG01 A-10\n"
    "G03 X-20 A-20 I10 J0\nG01 X40\nG01 A0\nG01 X120\nG13.1\nG00 A0\nM30\n";

// The plane point of a machine position: radius X, angle A from where the virtual axis is 0.
std::array<double, 2> plane_point(const AxisVector& to, double zero_degrees) {
  const double a = (to[kA] - zero_degrees) * M_PI / 180.0;
  return {to[kX] * std::cos(a), to[kX] * std::sin(a)};
}

// The last machine line of each block (line, plane point) ends on its point.
using PlaneEnd = std::pair<int, std::array<double, 2>>;
void expect_ends(const RunResult& r, const std::vector<PlaneEnd>& ends, double zero_degrees) {
  for (const auto& [line, want] : ends) {
    const std::vector<Command> moves = r.at_line(line);
    ASSERT_FALSE(moves.empty()) << line;
    const std::array<double, 2> p = plane_point(moves.back().to, zero_degrees);
    EXPECT_NEAR(p[0], want[0], 1e-9) << line;
    EXPECT_NEAR(p[1], want[1], 1e-9) << line;
  }
}

TEST(InterpPolar, EveryBlockEndsOnItsProgrammedPoint) {
  RunResult r = run_ok(kSquare, polar_lathe());
  // The virtual axis starts at 0 where A stands (A30), X40 is the radius 20.
  expect_ends(r,
              {{3, {20, 0}},
               {4, {20, 10}},
               {5, {10, 20}},
               {6, {-20, 20}},
               {7, {-20, -10}},
               {8, {-10, -20}},
               {9, {20, -20}},
               {10, {20, 0}},
               {11, {60, 0}}},
              30.0);
  for (int line = 3; line <= 11; ++line) {
    for (const Command& m : r.at_line(line)) {
      EXPECT_EQ(m.op, Op::linear);
      EXPECT_NEAR(m.to[kZ], 0.0, 1e-12);
    }
  }
  EXPECT_GT(r.at_line(5).size(), 10u);                    // the arc needs many machine lines
  EXPECT_NEAR(r.at_line(11).back().to[kA], 390.0, 1e-9);  // once around from A30
  // G13.1 gives A back as an angle.
  EXPECT_AT(r.of(Op::rapid).back(), 60, 0, 0);
}

// F is the speed along the contour: the machine lines take as long as the contour at F.
TEST(InterpPolar, TheFeedIsTheTangentialSpeed) {
  RunResult r = run_ok(kSquare, polar_lathe());
  const double minutes = minutes_at_feed(r, r.of(Op::rapid).front().to, 3);
  // 40 from X120 to X40, the square's sides and rounded corners, 40 back out.
  const double contour = 40 + 10 + M_PI * 5 + 30 + 30 + M_PI * 5 + 30 + 20 + 40;
  EXPECT_NEAR(minutes, contour / 500.0, 1e-9);
}

// The spec's example with its G42 (L804-849), a cutter of radius 2: the compensation works in
// the polar plane, so the tool's centre runs 2 outside the square.
TEST(InterpPolar, CompensationWorksInThePolarPlane) {
  RunResult r = run_ok(
      "T0101\nG00 X120 A0 Z0\nG12.1\nG42 G01 A0 X40 F500\nG01 A10\nG03 X20 A20 R10\n"
      "G01 X-40\nG01 A-10\nG03 X-20 A-20 I10 J0\nG01 X40\nG01 A0\nG40 X120\nG13.1\nM30\n",
      with_nose_radius(polar_lathe(), 2.0));
  expect_ends(r,
              {{5, {22, 10}},
               {6, {10, 22}},
               {7, {-22, 20}},
               {8, {-22, -10}},
               {9, {-10, -22}},
               {10, {22, -20}},
               {11, {22, 0}},
               {12, {60, 0}}},
              0.0);
}

TEST(InterpPolar, ModalGroup21ReadsIt) {
  run_ok(
      "IF[#4021 NE 13.1] #3000=1 (off)\nG12.1\nIF[#4021 NE 12.1] #3000=2 (on)\nG13.1\n"
      "IF[#4021 NE 13.1] #3000=3 (off)\nM30\n",
      polar_lathe());
}

TEST(InterpPolar, MisuseIsAnAlarm) {
  const ExpectedAlarm cases[] = {
      {"G00 X40\nG12.1 X10\nM30\n", alarm::kMustBeAlone, 2},
      {"G00 X40\nG12.1 G01\nM30\n", alarm::kMustBeAlone, 2},
      {"G00 X40\nG42 G01 X40 F100\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG00 X20\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nX20\nM30\n", alarm::kInterpolationModeRestriction, 3},  // G00 still modal
      {"G00 X40\nG12.1\nT0202\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG50 X0\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG18\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG68.1 X0 Z0 R10\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG12.1\nG42 G01 X20 F100\nG13.1\nM30\n", alarm::kInterpolationModeRestriction,
       4},  // G13.1 under G42
      {"G00 X40\nG68.1 X0 Z0 R10\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X-40\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 2},
  };
  expect_alarms(cases, polar_lathe());
  // Without the polar axes in the parameters.
  run_alarm("G00 X40\nG12.1\nM30\n", alarm::kInterpolationModeRestriction, 2);
}

// G16 (format 2, spec L711-849 detail 5): in G12.1 the linear axis gives the radius (X a
// diameter) and the rotary axis the angle in degrees from where G12.1 found it; the moves stay
// lines and arcs of the polar plane. Incremental words add to the radius and the angle as
// programmed, so a negative radius and whole turns keep their meaning.
TEST(InterpPolar, PolarCoordinatesUnderG16) {
  RunResult r = run_ok(
      "G00 X120 A30 Z0\nG16\nG12.1\nG01 X40 A0 F500\nA60\nA120\nX-40 A-45\nU-10\n"
      "G03 X40 A270 R25\nG01 UA-90\nG15\nG01 X10 A5\nG16\nUA30\nG13.1\nG15\nM30\n",
      polar_lathe());
  const auto at = [](double radius, double degrees) {
    const double a = degrees * M_PI / 180.0;
    return std::array<double, 2>{radius * std::cos(a), radius * std::sin(a)};
  };
  expect_ends(r,
              {{4, at(20, 0)},
               {5, at(20, 60)},
               {6, at(20, 120)},
               {7, at(-20, -45)},  // the opposite side
               {8, at(-25, -45)},  // U-10: the radius 5 more negative
               {9, at(20, 270)},
               {10, at(20, 180)},                      // H-90 from the programmed 270
               {12, {5.0, 5.0}},                       // G15: the plane's coordinates again
               {14, at(std::hypot(5.0, 5.0), 75.0)}},  // G16 again: from where the tool is
              30.0);
  // Between the points the tool moves on straight lines of the polar plane (not on circles of
  // its radius): the line from (20, 0) to the angle 60 passes the centre at 10 * sqrt(3).
  double nearest = 1e9;
  for (const Command& m : r.at_line(5)) {
    const std::array<double, 2> p = plane_point(m.to, 30.0);
    nearest = std::min(nearest, std::hypot(p[0], p[1]));
  }
  EXPECT_NEAR(nearest, 10.0 * std::sqrt(3.0), 1e-3);
  // The arc of line 9 keeps its radius R25 about a centre of the polar plane.
  const std::array<double, 2> from = at(-25, -45);
  const std::array<double, 2> to = at(20, 270);
  for (const Command& m : r.at_line(9)) {
    const std::array<double, 2> p = plane_point(m.to, 30.0);
    EXPECT_LE(std::hypot(p[0] - from[0], p[1] - from[1]), 50.0 + 1e-9);
    EXPECT_LE(std::hypot(p[0] - to[0], p[1] - to[1]), 50.0 + 1e-9);
  }
}

TEST(InterpPolar, ModalGroup18ReadsG15AndG16) {
  run_ok(
      "IF[#4018 NE 15] #3000=1 (off)\nG16\nIF[#4018 NE 16] #3000=2 (on)\nG01\nG12.1\nG15\n"
      "IF[#4018 NE 15] #3000=3 (off)\nG13.1\nM30\n",
      polar_lathe());
}

TEST(InterpPolar, G16MisuseIsAnAlarm) {
  const ExpectedAlarm cases[] = {
      // Polar coordinates only where G12.1 gives them a plane.
      {"G00 X40\nG16\nG01 X20 F100\nM30\n", alarm::kInterpolationModeRestriction, 3},
      {"G00 X40\nG16\nG12.1\nG13.1\nG00 X60\nM30\n", alarm::kInterpolationModeRestriction, 5},
      {"G00 X40\nG01 F100\nG12.1\nG16\nX40 A30 ,A45\nM30\n", alarm::kInterpolationModeRestriction,
       5},
      // An arc by its centre: I/J in polar coordinates would be ambiguous.
      {"G00 X40\nG01 F100\nG12.1\nG16\nG03 X20 A90 I-10 J0\nM30\n",
       alarm::kInterpolationModeRestriction, 5},
  };
  expect_alarms(cases, polar_lathe());
}

// GSK (gsk A.6.8): G16 and G15 stand alone in their block; the Dafeng spec does not ask it.
TEST(InterpPolar, GskG16StandsAlone) {
  InterpreterConfig gsk = polar_lathe();
  select_dialect(gsk, Dialect::gsk);
  run_alarm("G00 X40\nG01 F100\nG12.1\nG16 X20 A90\nM30\n", alarm::kMustBeAlone, 4, -1, gsk);
  run_ok("G00 X40\nG01 F100\nG12.1\nG16 X20 A90\nG15\nG13.1\nM30\n", polar_lathe());
}

}  // namespace
}  // namespace mcnc::interp::test
