// The 7-phase S-curve of one block (channel/motion/jerk_limited_profile.hpp): closed-form
// timing goldens, and seeded random profiles that never exceed a limit and end exactly.
#include "channel/motion/jerk_limited_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::motion::test {
namespace {

// One long line from rest to rest: T = D/v + v/a + a/j when v >= a^2/j and the line is long
// enough to cruise.
TEST(JerkLimitedProfile, LongLineTimeFormula) {
  const JerkLimits l{50.0, 500.0, 10000.0};
  JerkLimitedProfile p;
  ASSERT_EQ(JerkLimitedProfile::plan(100.0, 0.0, 0.0, l, p), ProfileResult::ok);
  EXPECT_NEAR(p.duration(), 100.0 / 50.0 + 50.0 / 500.0 + 500.0 / 10000.0, 1e-12);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 50.0);
  const ProfileSample mid = p.at(p.duration() / 2.0);
  EXPECT_NEAR(mid.s, 50.0, 1e-9);
  EXPECT_NEAR(mid.v, 50.0, 1e-9);
}

// A short line reaches neither the acceleration nor the velocity limit: four jerk phases,
// peak vp = (D sqrt(j) / 2)^(2/3), T = 4 sqrt(vp / j).
TEST(JerkLimitedProfile, ShortLineOnlyJerkPhases) {
  const JerkLimits l{50.0, 500.0, 10000.0};
  JerkLimitedProfile p;
  const double d = 0.01;
  ASSERT_EQ(JerkLimitedProfile::plan(d, 0.0, 0.0, l, p), ProfileResult::ok);
  const double vp = std::pow(d * std::sqrt(l.jerk) / 2.0, 2.0 / 3.0);
  EXPECT_NEAR(p.peak_velocity(), vp, 1e-9);
  EXPECT_NEAR(p.duration(), 4.0 * std::sqrt(vp / l.jerk), 1e-9);
  EXPECT_NEAR(p.cruise_time(), 0.0, 1e-12);
}

TEST(JerkLimitedProfile, SpeedChangeFormulas) {
  const JerkLimits l{100.0, 400.0, 8000.0};
  // 0 -> 100: 100 >= a^2/j = 20, so a constant phase: T = dv/a + a/j.
  EXPECT_NEAR(speed_change_time(0, 100, l), 100.0 / 400.0 + 400.0 / 8000.0, 1e-12);
  EXPECT_NEAR(speed_change_distance(0, 100, l), 50.0 * 0.3, 1e-12);
  // 10 -> 20: below a^2/j: T = 2 sqrt(dv/j).
  EXPECT_NEAR(speed_change_time(20, 10, l), 2.0 * std::sqrt(10.0 / 8000.0), 1e-12);
}

TEST(JerkLimitedProfile, EndVelocityAndUnreachable) {
  const JerkLimits l{100.0, 400.0, 8000.0};
  JerkLimitedProfile p;
  ASSERT_EQ(JerkLimitedProfile::plan(30.0, 20.0, 60.0, l, p), ProfileResult::ok);
  const ProfileSample end = p.at(p.duration());
  EXPECT_DOUBLE_EQ(end.s, 30.0);
  EXPECT_DOUBLE_EQ(end.v, 60.0);
  // From 100 to 0 needs 100/2 * (100/400 + 400/8000) = 15 mm.
  EXPECT_EQ(JerkLimitedProfile::plan(14.9, 100.0, 0.0, l, p), ProfileResult::unreachable);
  EXPECT_EQ(JerkLimitedProfile::plan(15.0, 100.0, 0.0, l, p), ProfileResult::ok);
  EXPECT_EQ(JerkLimitedProfile::plan(1.0, 0.0, 0.0, JerkLimits{0.0, 1.0, 1.0}, p),
            ProfileResult::bad_limits);
  EXPECT_EQ(JerkLimitedProfile::plan(1.0, 0.0, 120.0, l, p), ProfileResult::bad_limits);
}

TEST(JerkLimitedProfile, StartAboveTheLimitSlowsDownFirst) {
  // An override lowered under way: from 150 down to the limit 100, cruise, then to 0. Slowing
  // 150 -> 100 takes 50/400 + 400/8000 = 0.175 s over 125 * 0.175 = 21.875 mm.
  const JerkLimits l{100.0, 400.0, 8000.0};
  JerkLimitedProfile p;
  ASSERT_EQ(JerkLimitedProfile::plan(100.0, 150.0, 0.0, l, p), ProfileResult::ok);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 100.0);
  EXPECT_NEAR(p.at(0.175).v, 100.0, 1e-9);
  EXPECT_NEAR(p.at(0.175).s, 21.875, 1e-9);
  for (double t = 0.0; t < 0.175; t += 0.005) {
    EXPECT_LE(p.at(t + 0.005).v, p.at(t).v + 1e-12);  // only slows down
  }
  EXPECT_DOUBLE_EQ(p.at(p.duration()).s, 100.0);
  // Slowing to the limit and stopping needs 21.875 + 15 mm; with less room the plateau is
  // lower, down to one straight stop from 150: 75 * (150/400 + 400/8000) = 31.875 mm.
  ASSERT_EQ(JerkLimitedProfile::plan(36.9, 150.0, 0.0, l, p), ProfileResult::ok);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 100.0);
  ASSERT_EQ(JerkLimitedProfile::plan(33.0, 150.0, 0.0, l, p), ProfileResult::ok);
  EXPECT_LT(p.peak_velocity(), 100.0);
  for (double t = 0.0; t < p.duration(); t += 0.005) {
    EXPECT_LE(p.at(t + 0.005).v, p.at(t).v + 1e-12);  // only slows down
  }
  EXPECT_DOUBLE_EQ(p.at(p.duration()).s, 33.0);
  EXPECT_EQ(JerkLimitedProfile::plan(31.8, 150.0, 0.0, l, p), ProfileResult::unreachable);
  EXPECT_EQ(JerkLimitedProfile::plan(31.9, 150.0, 0.0, l, p), ProfileResult::ok);
}

// Random blocks sampled every 50 us: velocity, acceleration and jerk within their limits, the
// distance never goes back, the end is exact.
TEST(JerkLimitedProfile, RandomProfilesKeepTheLimits) {
  std::mt19937 rng(5);
  auto uni = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  int planned = 0;
  for (int n = 0; n < 500; ++n) {
    const JerkLimits l{uni(1, 200), uni(10, 5000), uni(100, 1e5)};
    const double d = uni(0, 1) < 0.3 ? uni(0, 0.05) : uni(0, 200);
    const double v0 = uni(0, l.velocity);
    const double v1 = uni(0, l.velocity);
    JerkLimitedProfile p;
    const ProfileResult r = JerkLimitedProfile::plan(d, v0, v1, l, p);
    if (r == ProfileResult::unreachable) {
      EXPECT_GT(std::max(speed_change_distance(v0, v1, l), 0.0), d * (1.0 - 1e-9)) << n;
      continue;
    }
    ASSERT_EQ(r, ProfileResult::ok) << n;
    ++planned;
    const double dt = 5e-5;
    ProfileSample prev = p.at(0.0);
    EXPECT_DOUBLE_EQ(prev.v, v0);
    for (double t = dt; t < p.duration() + dt; t += dt) {
      const ProfileSample s = p.at(t);
      EXPECT_LE(s.v, l.velocity * (1 + 1e-9) + 1e-9) << n;
      EXPECT_GE(s.v, -1e-9) << n;
      EXPECT_LE(std::fabs(s.a), l.acceleration * (1 + 1e-9) + 1e-9) << n;
      if (t < p.duration()) {
        EXPECT_LE(std::fabs(s.a - prev.a), l.jerk * dt * (1 + 1e-6) + 1e-9) << n << " t " << t;
      }
      EXPECT_GE(s.s, prev.s - 1e-12) << n;
      prev = s;
    }
    const ProfileSample end = p.at(p.duration());
    EXPECT_EQ(end.s, d) << n;
    EXPECT_EQ(end.v, v1) << n;
    // Continuity into the exact end: the last interior sample is close to it.
    const ProfileSample before = p.at(p.duration() * (1 - 1e-12));
    EXPECT_NEAR(before.s, d, 1e-6 * std::max(1.0, d)) << n;
    EXPECT_NEAR(before.v, v1, 1e-6 * std::max(1.0, l.velocity)) << n;
  }
  EXPECT_GT(planned, 300);
}

}  // namespace
}  // namespace mcnc::motion::test
