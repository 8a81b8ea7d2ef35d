#include "channel/motion/trapezoid_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::motion {
namespace {

TEST(TrapezoidProfile, TrapezoidWhenTheSpeedLimitIsReached) {
  // 100 at v 10, a 20: 0.5 s up (2.5), 9.5 s cruise (95), 0.5 s down (2.5).
  const TrapezoidProfile p(100.0, 10.0, 20.0);
  EXPECT_FALSE(p.is_triangle());
  EXPECT_DOUBLE_EQ(p.accel_time(), 0.5);
  EXPECT_DOUBLE_EQ(p.cruise_time(), 9.5);
  EXPECT_DOUBLE_EQ(p.duration(), 10.5);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 10.0);

  const ProfileSample up = p.at(0.25);
  EXPECT_DOUBLE_EQ(up.s, 0.625);
  EXPECT_DOUBLE_EQ(up.v, 5.0);
  EXPECT_DOUBLE_EQ(up.a, 20.0);
  const ProfileSample cruise = p.at(5.0);
  EXPECT_DOUBLE_EQ(cruise.s, 2.5 + 45.0);
  EXPECT_DOUBLE_EQ(cruise.v, 10.0);
  EXPECT_EQ(cruise.a, 0.0);
  const ProfileSample down = p.at(10.25);
  EXPECT_DOUBLE_EQ(down.s, 100.0 - 0.625);
  EXPECT_DOUBLE_EQ(down.v, 5.0);
  EXPECT_DOUBLE_EQ(down.a, -20.0);
}

TEST(TrapezoidProfile, TriangleForShortMoves) {
  // 1 at a 4: peak sqrt(4) = 2 < 10, 0.5 s up and 0.5 s down.
  const TrapezoidProfile p(1.0, 10.0, 4.0);
  EXPECT_TRUE(p.is_triangle());
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 2.0);
  EXPECT_DOUBLE_EQ(p.duration(), 1.0);
  EXPECT_DOUBLE_EQ(p.at(0.5).s, 0.5);
  EXPECT_DOUBLE_EQ(p.at(0.75).v, 1.0);
}

TEST(TrapezoidProfile, ExactlyReachingTheLimitHasNoCruise) {
  const TrapezoidProfile p(4.0, 2.0, 1.0);  // v^2/a = 4
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 2.0);
  EXPECT_NEAR(p.cruise_time(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(p.duration(), 4.0);
}

TEST(TrapezoidProfile, EndsAndStartsAtRest) {
  const TrapezoidProfile p(7.0, 3.0, 5.0);
  const ProfileSample before = p.at(-1.0);
  EXPECT_EQ(before.s, 0.0);
  EXPECT_EQ(before.v, 0.0);
  const ProfileSample after = p.at(p.duration());
  EXPECT_EQ(after.s, 7.0);
  EXPECT_EQ(after.v, 0.0);
  EXPECT_EQ(after.a, 0.0);
  EXPECT_EQ(p.at(1e9).s, 7.0);
}

TEST(TrapezoidProfile, ZeroDistanceTakesNoTime) {
  const TrapezoidProfile p(0.0, 3.0, 5.0);
  EXPECT_EQ(p.duration(), 0.0);
  EXPECT_EQ(p.at(0.1).s, 0.0);
}

TEST(TrapezoidProfile, SamplesAreContinuousAndBounded) {
  const TrapezoidProfile p(12.3, 4.5, 6.7);
  ProfileSample prev = p.at(0.0);
  const double dt = 1e-4;
  for (double t = dt; t < p.duration() + 2 * dt; t += dt) {
    const ProfileSample s = p.at(t);
    EXPECT_LE(s.v, 4.5 * (1 + 1e-12));
    EXPECT_GE(s.v, 0.0);
    EXPECT_LE(std::fabs(s.a), 6.7);
    EXPECT_GE(s.s, prev.s);
    EXPECT_LE(s.s - prev.s, 4.5 * dt * (1 + 1e-9));
    EXPECT_LE(std::fabs(s.v - prev.v), 6.7 * dt * (1 + 1e-9));
    prev = s;
  }
  EXPECT_EQ(prev.s, 12.3);
}

}  // namespace
}  // namespace mcnc::motion
