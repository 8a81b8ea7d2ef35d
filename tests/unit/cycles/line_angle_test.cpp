// Angle programming (channel/interp/path/line_angle.hpp): the dafeng ,A examples, the gsk
// D2-13 alarm table, the 1-degree tolerance, angles beyond +-360 and random lines.
#include "channel/interp/path/line_angle.hpp"

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::path::test {
namespace {

// G00 X40 Z150 (a = Z, b = X / 2).
constexpr Point2 kStart{150, 20};

// dafeng §2.4 L488: G01 X120 F500 ,A135 (and G01 U80 ,A135): 40 up in X radius at 135 degrees
// is 40 back in Z, so the end is X120 Z110.
TEST(LineAngleGolden, DafengOneCoordinateAndAngle) {
  Point2 end;
  ASSERT_EQ(line_end_from_angle(kStart, 135, KnownAxis::b, 60, end), std::nullopt);
  EXPECT_NEAR(end.a, 110, 1e-12);
  EXPECT_EQ(end.b, 60);
}

// The same line from its Z: G01 Z110 ,A135 ends at X120.
TEST(LineAngleGolden, DafengKnownZGivesX) {
  Point2 end;
  ASSERT_EQ(line_end_from_angle(kStart, 135, KnownAxis::a, 110, end), std::nullopt);
  EXPECT_EQ(end.a, 110);
  EXPECT_NEAR(end.b, 60, 1e-12);
}

// dafeng §2.4 L489-490: G01 ,A135 F500; G01 X50 Z80 ,A-120. The first line is a + b = 170;
// the second passes (80, 25) with slope tan(-120) = sqrt(3): the corner is at
// a = 80 + 32.5 (sqrt3 - 1), b = 25 + 32.5 (3 - sqrt3), i.e. X132.417 Z103.792.
TEST(LineAngleGolden, DafengTwoBlockIntersection) {
  Point2 corner;
  ASSERT_EQ(angle_lines_corner(kStart, 135, {80, 25}, -120, corner), std::nullopt);
  const double root3 = std::sqrt(3.0);
  EXPECT_NEAR(corner.a, 80 + 32.5 * (root3 - 1), 1e-12);
  EXPECT_NEAR(corner.b, 25 + 32.5 * (3 - root3), 1e-12);
  EXPECT_NEAR(2 * corner.b, 132.417, 5e-4);
  EXPECT_NEAR(corner.a, 103.792, 5e-4);
}

struct GskAlarmCase {
  const char* block;
  KnownAxis known;
  double value;
  double q;  // Q in 0.001 degree
};

// gsk D2-13 (L1394-1404): X known with Q within 1 degree of 0/180, Z known within 1 degree of
// 90/270 -> alarm.
class GskAngleAlarm : public ::testing::TestWithParam<GskAlarmCase> {};

TEST_P(GskAngleAlarm, Alarm1148) {
  const GskAlarmCase& c = GetParam();
  Point2 end{7, 7};
  const PathResult e = line_end_from_angle({0, 0}, c.q / 1000, c.known, c.value, end);
  ASSERT_TRUE(e.has_value()) << c.block;
  EXPECT_EQ(e->alarm, alarm::kAngleProgramming);
  EXPECT_EQ(end.a, 7);
  EXPECT_EQ(end.b, 7);
}

INSTANTIATE_TEST_SUITE_P(
    D2_13, GskAngleAlarm,
    ::testing::Values(GskAlarmCase{"G01 X50 Q0", KnownAxis::b, 25, 0},
                      GskAlarmCase{"G01 X50 Q180500", KnownAxis::b, 25, 180500},
                      GskAlarmCase{"G01 Z-20 Q90000", KnownAxis::a, -20, 90000},
                      GskAlarmCase{"G01 Z-20 Q269200", KnownAxis::a, -20, 269200},
                      GskAlarmCase{"G01 X50 Q359001", KnownAxis::b, 25, 359001},
                      GskAlarmCase{"G01 X50 Q-180999", KnownAxis::b, 25, -180999},
                      GskAlarmCase{"G01 Z-20 Q-90500", KnownAxis::a, -20, -90500},
                      GskAlarmCase{"G01 Z-20 Q450000", KnownAxis::a, -20, 450000}));

TEST(LineAngleAlarm, TextNamesTheAngleAndTheCoordinate) {
  Point2 end;
  const PathResult e = line_end_from_angle({0, 0}, 180.5, KnownAxis::b, 25, end);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->text,
            "a line at 180.500 degrees runs within 1 degree of the first axis: it has no end "
            "point at second-axis coordinate 25.000");
  EXPECT_EQ(e->source, -1);
}

// Exactly 1 degree off the axis is accepted (gsk: "within +-1 degree" alarms).
TEST(LineAngleTolerance, OneDegreeOffTheAxisIsAccepted) {
  Point2 end;
  ASSERT_EQ(line_end_from_angle({0, 0}, 1.0, KnownAxis::b, 1, end), std::nullopt);
  EXPECT_NEAR(end.a, 1 / std::tan(kPi / 180), 1e-9);
  ASSERT_EQ(line_end_from_angle({0, 0}, 181.0, KnownAxis::b, 1, end), std::nullopt);
  EXPECT_NEAR(end.a, 1 / std::tan(kPi / 180), 1e-9);
  ASSERT_EQ(line_end_from_angle({0, 0}, 91.0, KnownAxis::a, -1, end), std::nullopt);
  EXPECT_NEAR(end.b, 1 / std::tan(kPi / 180), 1e-9);
  EXPECT_TRUE(line_end_from_angle({0, 0}, 0.999, KnownAxis::b, 1, end).has_value());
  EXPECT_TRUE(line_end_from_angle({0, 0}, 89.001, KnownAxis::a, 1, end).has_value());
}

// The angle fixes a line: the known coordinate decides the sense, so 135 and -45 agree.
TEST(LineAngleSense, OppositeAnglesGiveTheSameEnd) {
  for (double degrees : {-45.0, 315.0, 135.0 + 360.0, 135.0 - 720.0, 495.0, -225.0}) {
    Point2 end;
    ASSERT_EQ(line_end_from_angle(kStart, degrees, KnownAxis::b, 60, end), std::nullopt) << degrees;
    EXPECT_NEAR(end.a, 110, 1e-9) << degrees;
  }
}

TEST(LineAngleModulo, NormalisedIntoZeroTo360) {
  EXPECT_EQ(normalized_degrees(0), 0);
  EXPECT_EQ(normalized_degrees(360), 0);
  EXPECT_EQ(normalized_degrees(-360), 0);
  EXPECT_EQ(normalized_degrees(-120), 240);
  EXPECT_EQ(normalized_degrees(495), 135);
  EXPECT_EQ(normalized_degrees(-600), 120);
  EXPECT_EQ(normalized_degrees(180.5), 180.5);
}

// gsk A.6.11 rule 5: two lines less than 1 degree apart -> alarm 1148, corner unchanged.
TEST(LineAngleAlarm, TwoBlocksNearlyParallel) {
  for (double second : {135.0, 135.5, 134.001, -45.0, 315.9, 495.0}) {
    Point2 corner{7, 7};
    const PathResult e = angle_lines_corner(kStart, 135, {80, 25}, second, corner);
    ASSERT_TRUE(e.has_value()) << second;
    EXPECT_EQ(e->alarm, alarm::kAngleProgramming);
    EXPECT_EQ(corner.a, 7);
  }
  Point2 corner;
  const PathResult e = angle_lines_corner(kStart, 135, {80, 25}, -44.5, corner);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->text,
            "lines at 135.000 and -44.500 degrees are less than 1 degree apart: no "
            "intersection");
  EXPECT_EQ(angle_lines_corner(kStart, 135, {80, 25}, 136, corner), std::nullopt);
}

TEST(LineAngleProperty, EndsLieOnTheLineAtTheKnownCoordinate) {
  std::mt19937 rng(1148);
  std::uniform_real_distribution<double> coord(-200, 200);
  std::uniform_real_distribution<double> angle(-720, 720);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const Point2 start{coord(rng), coord(rng)};
    const double degrees = angle(rng);
    const KnownAxis known = i % 2 == 0 ? KnownAxis::a : KnownAxis::b;
    const double value = coord(rng);
    const double rad = degrees * kPi / 180;
    const Point2 dir{std::cos(rad), std::sin(rad)};
    const double off_axis = known == KnownAxis::b ? std::fabs(dir.b) : std::fabs(dir.a);
    Point2 end;
    const PathResult e = line_end_from_angle(start, degrees, known, value, end);
    if (off_axis < std::sin(kPi / 180) - 1e-9) {
      EXPECT_TRUE(e.has_value()) << i;
      continue;
    }
    ASSERT_EQ(e, std::nullopt) << i;
    ++checked;
    EXPECT_EQ(known == KnownAxis::a ? end.a : end.b, value);
    EXPECT_NEAR(cross(dir, end - start), 0, 1e-9 * std::max(1.0, length(end - start))) << i;
  }
  EXPECT_GT(checked, 380);
}

TEST(LineAngleProperty, CornerLiesOnBothLines) {
  std::mt19937 rng(4811);
  std::uniform_real_distribution<double> coord(-200, 200);
  std::uniform_real_distribution<double> angle(-360, 360);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const Point2 start{coord(rng), coord(rng)};
    const Point2 end{coord(rng), coord(rng)};
    const double first = angle(rng);
    const double second = angle(rng);
    const Point2 d1{std::cos(first * kPi / 180), std::sin(first * kPi / 180)};
    const Point2 d2{std::cos(second * kPi / 180), std::sin(second * kPi / 180)};
    Point2 corner;
    const PathResult e = angle_lines_corner(start, first, end, second, corner);
    if (std::fabs(cross(d1, d2)) < std::sin(kPi / 180) - 1e-9) {
      EXPECT_TRUE(e.has_value()) << i;
      continue;
    }
    ASSERT_EQ(e, std::nullopt) << i;
    ++checked;
    const double scale = std::max(1.0, length(corner - start) + length(corner - end));
    EXPECT_NEAR(cross(d1, corner - start), 0, 1e-9 * scale) << i;
    EXPECT_NEAR(cross(d2, corner - end), 0, 1e-9 * scale) << i;
  }
  EXPECT_GT(checked, 380);
}

}  // namespace
}  // namespace mcnc::interp::path::test
