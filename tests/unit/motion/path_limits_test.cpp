// Per-axis limits projected on a move, and the blend-tolerance corner velocity
// (channel/motion/path_limits.hpp).
#include "channel/motion/path_limits.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

namespace mcnc::motion::test {
namespace {

using interp::AxisVector;

AxisVector vec(double x, double z) {
  AxisVector v{};
  v[0] = x;
  v[1] = z;
  return v;
}

TEST(PathLimits, OneAxisMoveTakesThatAxisLimits) {
  const std::array<AxisDynamics, 2> axes{AxisDynamics{100, 1000, 1e4}, AxisDynamics{50, 500, 5e3}};
  const JerkLimits x = line_limits(vec(-3, 0), axes, 0.0);
  EXPECT_DOUBLE_EQ(x.velocity, 100);
  EXPECT_DOUBLE_EQ(x.acceleration, 1000);
  EXPECT_DOUBLE_EQ(x.jerk, 1e4);
  const JerkLimits z = line_limits(vec(0, 7), axes, 30.0);
  EXPECT_DOUBLE_EQ(z.velocity, 30);  // the feed caps it
  EXPECT_DOUBLE_EQ(z.acceleration, 500);
}

TEST(PathLimits, DiagonalMoveIsLimitedByEachAxisShare) {
  const std::array<AxisDynamics, 2> axes{AxisDynamics{100, 1000, 1e4}, AxisDynamics{50, 500, 5e3}};
  // 45 degrees: each axis moves 1/sqrt(2) of the path; Z is the slower one.
  const JerkLimits l = line_limits(vec(1, 1), axes, 0.0);
  EXPECT_NEAR(l.velocity, 50 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(l.acceleration, 500 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(l.jerk, 5e3 * std::sqrt(2.0), 1e-6);
}

TEST(PathLimits, RandomDirectionsNeverOverloadAnAxis) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> pos(1, 1000);
  for (int n = 0; n < 1000; ++n) {
    std::array<AxisDynamics, 4> axes{};
    AxisVector d{};
    for (std::size_t i = 0; i < 4; ++i) {
      axes[i] = AxisDynamics{pos(rng), pos(rng) * 10, pos(rng) * 100};
      d[i] = u(rng);
    }
    const JerkLimits l = line_limits(d, axes, 0.0);
    double length = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      length += d[i] * d[i];
    }
    length = std::sqrt(length);
    bool tight = false;  // some axis is exactly at its limit
    for (std::size_t i = 0; i < 4; ++i) {
      const double share = std::fabs(d[i]) / length;
      EXPECT_LE(l.velocity * share, axes[i].velocity * (1 + 1e-12)) << n;
      EXPECT_LE(l.acceleration * share, axes[i].acceleration * (1 + 1e-12)) << n;
      EXPECT_LE(l.jerk * share, axes[i].jerk * (1 + 1e-12)) << n;
      tight = tight || std::fabs(l.velocity * share - axes[i].velocity) < 1e-9 * axes[i].velocity;
    }
    EXPECT_TRUE(tight) << n;
  }
}

}  // namespace
}  // namespace mcnc::motion::test
