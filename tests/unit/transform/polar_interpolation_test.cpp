// Polar interpolation (channel/interp/transform/polar_interpolation.hpp): the tool tip stays on
// the programmed contour within 1 um between the machine points, also across the centre.
#include "channel/interp/transform/polar_interpolation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::transform {
namespace {

constexpr double kTolerance = 0.001;  // 1 um

using P = std::array<double, 2>;

double distance_to_piece(const PlanePiece& piece, const P& p) {
  if (piece.arc) {
    const double r = std::hypot(piece.from[0] - piece.centre[0], piece.from[1] - piece.centre[1]);
    return std::fabs(std::hypot(p[0] - piece.centre[0], p[1] - piece.centre[1]) - r);
  }
  const double dx = piece.to[0] - piece.from[0];
  const double dy = piece.to[1] - piece.from[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p[0] - piece.from[0]) * dx + (p[1] - piece.from[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (piece.from[0] + t * dx), p[1] - (piece.from[1] + t * dy));
}

// The largest distance of the tip from the piece while the machine moves straight (radius and
// angle linear) between the steps, sampled 64 times a step; and the steps' angle at the end.
double worst_deviation(const PolarInterpolation& polar, const PlanePiece& piece,
                       double from_degrees, double& end_degrees, std::size_t& count) {
  std::vector<PolarStep> steps;
  EXPECT_TRUE(polar.steps(piece, from_degrees, kTolerance, steps));
  count = steps.size();
  PolarPoint at{std::hypot(piece.from[0], piece.from[1]), from_degrees};
  double worst = 0.0;
  double covered = 0.0;
  for (const PolarStep& s : steps) {
    for (int k = 1; k <= 64; ++k) {
      const double f = k / 64.0;
      const PolarPoint m{at.radius + f * (s.machine.radius - at.radius),
                         at.degrees + f * (s.machine.degrees - at.degrees)};
      worst = std::max(worst, distance_to_piece(piece, polar.to_plane(m)));
    }
    covered += s.plane_length;
    at = s.machine;
  }
  EXPECT_NEAR(covered, piece.length(), 1e-9);
  const P end = polar.to_plane(at);
  EXPECT_NEAR(end[0], piece.to[0], 1e-9);
  EXPECT_NEAR(end[1], piece.to[1], 1e-9);
  end_degrees = at.degrees;
  return worst;
}

TEST(PolarInterpolation, MachinePointsRoundTripAndTurnContinuously) {
  const PolarInterpolation polar(30.0);
  std::mt19937_64 rng(121);
  std::uniform_real_distribution<double> coordinate(-200.0, 200.0);
  std::uniform_real_distribution<double> turn(-2000.0, 2000.0);
  for (int i = 0; i < 1000; ++i) {
    const P p{coordinate(rng), coordinate(rng)};
    const double near = turn(rng);
    const PolarPoint m = polar.to_machine(p, near);
    EXPECT_LE(std::fabs(m.degrees - near), 180.0 + 1e-9);
    const P back = polar.to_plane(m);
    EXPECT_NEAR(back[0], p[0], 1e-9);
    EXPECT_NEAR(back[1], p[1], 1e-9);
  }
  // The virtual axis at 0 on the positive linear axis is the zero angle.
  EXPECT_NEAR(polar.to_machine({20.0, 0.0}, 0.0).degrees, 30.0, 1e-12);
  EXPECT_NEAR(polar.to_machine({0.0, 20.0}, 0.0).degrees, 120.0, 1e-12);
}

// Spec dafeng L804-849 (without the nose compensation): a square of side 40 (X as a diameter
// gives x = X/2) with rounded corners, around the centre.
TEST(PolarInterpolation, SpecContourStaysWithinOneMicron) {
  const PolarInterpolation polar(0.0);
  const PlanePiece pieces[] = {
      {{20, 0}, {20, 10}},
      {{20, 10}, {10, 20}, true, {10, 10}, true},
      {{10, 20}, {-20, 20}},
      {{-20, 20}, {-20, -10}},
      {{-20, -10}, {-10, -20}, true, {-10, -10}, true},
      {{-10, -20}, {20, -20}},
      {{20, -20}, {20, 0}},
  };
  double degrees = 0.0;
  for (const PlanePiece& piece : pieces) {
    std::size_t count = 0;
    const double start = degrees;
    EXPECT_LE(worst_deviation(polar, piece, start, degrees, count), kTolerance);
    EXPECT_GT(count, 1u);
  }
  EXPECT_NEAR(degrees, 360.0, 1e-9);  // once around, counter-clockwise
}

TEST(PolarInterpolation, ALineThroughTheCentreTurnsHalfARevolutionThere) {
  const PolarInterpolation polar(0.0);
  const PlanePiece piece{{20, 5}, {-20, -5}};
  double degrees = 0.0;
  std::size_t count = 0;
  const double start = std::atan2(5.0, 20.0) * 180.0 / M_PI;
  EXPECT_LE(worst_deviation(polar, piece, start, degrees, count), kTolerance);
  EXPECT_NEAR(std::fabs(degrees - start), 180.0, 1e-9);
  EXPECT_LT(count, 5000u);
}

TEST(PolarInterpolation, RandomLinesAndArcsStayWithinOneMicron) {
  const PolarInterpolation polar(-45.0);
  std::mt19937_64 rng(1212);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  std::bernoulli_distribution coin(0.5);
  for (int i = 0; i < 100; ++i) {
    PlanePiece piece{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    if (coin(rng)) {
      // An arc about the middle of the chord moved sideways; the end put on the circle.
      piece.arc = true;
      piece.ccw = coin(rng);
      piece.centre = {0.5 * (piece.from[0] + piece.to[0]) + coordinate(rng) / 5,
                      0.5 * (piece.from[1] + piece.to[1]) + coordinate(rng) / 5};
      const double r = std::hypot(piece.from[0] - piece.centre[0], piece.from[1] - piece.centre[1]);
      const double a = std::atan2(piece.to[1] - piece.centre[1], piece.to[0] - piece.centre[0]);
      piece.to = {piece.centre[0] + r * std::cos(a), piece.centre[1] + r * std::sin(a)};
    }
    double degrees = 0.0;
    std::size_t count = 0;
    const double start = polar.to_machine(piece.from, 0.0).degrees;
    EXPECT_LE(worst_deviation(polar, piece, start, degrees, count), kTolerance) << i;
  }
}

}  // namespace
}  // namespace mcnc::interp::transform
