// Cylindrical interpolation (channel/interp/transform/cylindrical_interpolation.hpp): angles
// and lengths around the cylinder, and arcs of the unrolled plane as chords within 1 um.
#include "channel/interp/transform/cylindrical_interpolation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::transform {
namespace {

TEST(CylindricalInterpolation, DegreesAreLengthsAroundTheCylinder) {
  // Spec dafeng L664-710: radius 60, so 30 degrees are a twelfth of the circumference.
  const CylindricalInterpolation c(60.0);
  EXPECT_NEAR(c.to_length(30.0), M_PI * 60.0 / 6.0, 1e-12);
  EXPECT_NEAR(c.to_length(360.0), 2.0 * M_PI * 60.0, 1e-12);
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> degrees(-5000.0, 5000.0);
  for (int i = 0; i < 1000; ++i) {
    const double d = degrees(rng);
    EXPECT_NEAR(c.to_degrees(c.to_length(d)), d, 1e-9);
  }
}

TEST(CylindricalInterpolation, LinesStayOneMove) {
  const PlanePiece line{{0, 0}, {100, -50}};
  EXPECT_EQ(CylindricalInterpolation::chord_ends(line, 0.001), std::vector<double>{1.0});
}

// Seeded random arcs: the middle of every chord (its farthest point) within 1 um of the circle.
TEST(CylindricalInterpolation, ArcChordsStayWithinOneMicron) {
  std::mt19937_64 rng(107);
  std::uniform_real_distribution<double> coordinate(-100.0, 100.0);
  std::uniform_real_distribution<double> radius(0.5, 80.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::bernoulli_distribution coin(0.5);
  for (int i = 0; i < 200; ++i) {
    PlanePiece arc;
    arc.arc = true;
    arc.ccw = coin(rng);
    arc.centre = {coordinate(rng), coordinate(rng)};
    const double r = radius(rng);
    const double a0 = angle(rng);
    const double a1 = angle(rng);
    arc.from = {arc.centre[0] + r * std::cos(a0), arc.centre[1] + r * std::sin(a0)};
    arc.to = {arc.centre[0] + r * std::cos(a1), arc.centre[1] + r * std::sin(a1)};
    const std::vector<double> ends = CylindricalInterpolation::chord_ends(arc, 0.001);
    ASSERT_FALSE(ends.empty());
    EXPECT_EQ(ends.back(), 1.0);
    double f0 = 0.0;
    for (const double f1 : ends) {
      const auto p = arc.at(f0);
      const auto q = arc.at(f1);
      const std::array<double, 2> middle{0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
      const double off = r - std::hypot(middle[0] - arc.centre[0], middle[1] - arc.centre[1]);
      EXPECT_LE(off, 0.001 + 1e-9) << i;
      EXPECT_GE(off, -1e-9) << i;
      f0 = f1;
    }
  }
}

}  // namespace
}  // namespace mcnc::interp::transform
