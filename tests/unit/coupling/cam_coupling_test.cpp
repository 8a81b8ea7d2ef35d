// G51.8 / G50.8 electronic cam (spec dafeng §2.6.7-2.6.10, L3013-3230): the lift per master
// angle from a table, an ellipse or an eccentric circle, and the offset the slave's node adds,
// which reaches the lift and leaves it within the axis's velocity and acceleration.
#include "axisnode/coupling/cam_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.001;
constexpr double kVel = 50.0;
constexpr double kAcc = 500.0;

CamProfile table(std::size_t n, double start, double (*f)(double)) {
  CamProfile p;
  p.points = n;
  p.start = start;
  for (std::size_t i = 0; i < n; ++i) {
    p.lift[i] = f(360.0 * static_cast<double>(i) / static_cast<double>(n));
  }
  return p;
}

double bump(double deg) {
  return 0.5 * (1.0 - std::cos(deg * std::numbers::pi / 180.0));
}

TEST(CamLift, TablePointsDivideOneTurnFromTheStartAngle) {
  CamProfile p;
  p.points = 4;
  p.lift = {0.0, 1.0, 3.0, 2.0};
  p.start = 30.0;
  EXPECT_DOUBLE_EQ(cam_lift(p, 30.0), 0.0);
  EXPECT_DOUBLE_EQ(cam_lift(p, 120.0), 1.0);
  EXPECT_DOUBLE_EQ(cam_lift(p, 210.0), 3.0);
  EXPECT_DOUBLE_EQ(cam_lift(p, 300.0), 2.0);
  EXPECT_DOUBLE_EQ(cam_lift(p, 165.0), 2.0);         // half-way from 1 to 3
  EXPECT_DOUBLE_EQ(cam_lift(p, 345.0), 1.0);         // the last point joins the first
  EXPECT_DOUBLE_EQ(cam_lift(p, 30.0 + 720.0), 0.0);  // whole turns
  EXPECT_DOUBLE_EQ(cam_lift(p, 30.0 - 270.0), 1.0);  // negative angles
}

TEST(CamLift, TheSpecExampleTableStartsAtZero) {
  // L3067-3085: #100 = 0, #101 = 0.02, #102 = 0.08 ... #459 = 0 (360 points).
  CamProfile p;
  p.points = 360;
  p.lift[1] = 0.02;
  p.lift[2] = 0.08;
  EXPECT_DOUBLE_EQ(cam_lift(p, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(cam_lift(p, 1.0), 0.02);
  EXPECT_NEAR(cam_lift(p, 1.5), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(cam_lift(p, 359.5), 0.0);
}

TEST(CamLift, EllipseAndEccentricCircleAreZeroAtTheStartAngle) {
  CamProfile e;
  e.shape = CamShape::ellipse;
  e.a = 10.0;
  e.b = 8.0;
  EXPECT_NEAR(cam_lift(e, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(cam_lift(e, 90.0), -2.0, 1e-12);  // the minor semi-axis
  EXPECT_NEAR(cam_lift(e, 180.0), 0.0, 1e-12);
  CamProfile c;
  c.shape = CamShape::eccentric;
  c.a = 5.0;  // D10
  c.b = 2.0;  // P2
  c.start = 90.0;
  EXPECT_NEAR(cam_lift(c, 90.0), 0.0, 1e-12);
  EXPECT_NEAR(cam_lift(c, 270.0), -4.0, 1e-12);  // twice the eccentricity nearer
  // Seeded: the eccentric circle's points are D/2 from its centre.
  std::mt19937 rng(7);
  for (int n = 0; n < 200; ++n) {
    const double deg = std::uniform_real_distribution<double>(0.0, 360.0)(rng);
    const double r = cam_lift(c, deg) + 7.0;
    const double th = (deg - 90.0) * std::numbers::pi / 180.0;
    EXPECT_NEAR(std::hypot(r * std::cos(th) - 2.0, r * std::sin(th)), 5.0, 1e-9) << deg;
  }
}

TEST(CamLift, ProfilesThatCannotBeACamAreRefusedWithTheirReason) {
  CamProfile p;
  EXPECT_NE(cam_profile_error(p), nullptr);  // no points
  p.points = 10;
  EXPECT_EQ(cam_profile_error(p), nullptr);
  p.start = 361.0;
  EXPECT_NE(cam_profile_error(p), nullptr);
  p.start = 0.0;
  p.lift[3] = std::nan("");
  EXPECT_NE(cam_profile_error(p), nullptr);
  CamProfile e;
  e.shape = CamShape::ellipse;
  e.a = 10.0;
  EXPECT_NE(cam_profile_error(e), nullptr);  // b = 0
  CamProfile c;
  c.shape = CamShape::eccentric;
  c.a = 5.0;
  c.b = 5.0;
  EXPECT_NE(cam_profile_error(c), nullptr);  // the spindle's axis on the circle
  c.b = 4.999;
  EXPECT_EQ(cam_profile_error(c), nullptr);
}

// Seeded cams at seeded master speeds: the offset never moves faster or accelerates harder than
// the axis may, reaches the lift, then is the lift at every master angle; G50.8 takes it back
// to 0 the same way and ends the cam.
TEST(CamCoupling, SeededCamsAreReachedAndLeftWithinTheLimitsThenFollowedExactly) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const std::size_t n = std::uniform_int_distribution<std::size_t>(180, 999)(rng);
    const double amp = std::uniform_real_distribution<double>(0.05, 2.0)(rng);
    const double start = std::uniform_real_distribution<double>(0.0, 360.0)(rng);
    CamProfile p = table(n, start, bump);
    for (std::size_t i = 0; i < n; ++i) {
      p.lift[i] *= amp;
    }
    // Slow enough, and points dense enough, that the lift itself (straight between points) stays
    // within the limits.
    const double rpm = std::uniform_real_distribution<double>(1.0, 30.0)(rng);
    const double master0 = std::uniform_real_distribution<double>(0.0, 360.0)(rng);
    CamCoupling c(CamCouplingSetup{kDt, kVel, kAcc});
    c.couple(p);
    double pos = 0.0;
    double vel = 0.0;
    bool locked_once = false;
    int cycles_to_lock = 0;
    for (int k = 1; k <= 6000; ++k) {
      const double master = master0 + rpm * 6.0 * kDt * k;
      const CamOffset o = c.step(master);
      const double v = (o.pos - pos) / kDt;
      ASSERT_LE(std::fabs(v), kVel + 1e-3) << seed << " cycle " << k;
      ASSERT_LE(std::fabs(v - vel), kAcc * kDt + 1e-3) << seed << " cycle " << k;
      pos = o.pos;
      vel = v;
      if (o.locked || locked_once) {
        ASSERT_TRUE(o.locked) << seed << " lost the lift at cycle " << k;
        ASSERT_NEAR(o.pos, cam_lift(p, master), 1e-12) << seed;
        cycles_to_lock = locked_once ? cycles_to_lock : k;
        locked_once = true;
      }
    }
    ASSERT_TRUE(locked_once) << seed;
    EXPECT_LT(cycles_to_lock, 1000) << seed;
    c.release();
    int k = 6001;
    for (; c.active() && k < 12000; ++k) {
      const CamOffset o = c.step(master0 + rpm * 6.0 * kDt * k);
      const double v = (o.pos - pos) / kDt;
      ASSERT_LE(std::fabs(v), kVel + 1e-3) << seed << " release cycle " << k;
      ASSERT_LE(std::fabs(v - vel), kAcc * kDt + 1e-3) << seed << " release cycle " << k;
      pos = o.pos;
      vel = v;
    }
    EXPECT_FALSE(c.active()) << seed;
    EXPECT_EQ(c.offset(), 0.0) << seed;
    EXPECT_EQ(c.step(123.0).pos, 0.0);
  }
}

TEST(CamCoupling, ALiftBeyondTheLimitsIsFollowedNoFasterThanTheAxisMay) {
  CamProfile p = table(360, 0.0, bump);
  for (double& l : p.lift) {
    l *= 10.0;
  }
  CamCoupling c(CamCouplingSetup{kDt, 5.0, 50.0});
  c.couple(p);
  double pos = 0.0;
  double vel = 0.0;
  for (int k = 1; k <= 5000; ++k) {
    const CamOffset o = c.step(600.0 * 6.0 * kDt * k);  // 600 rpm: far beyond 5 units/s
    const double v = (o.pos - pos) / kDt;
    ASSERT_LE(std::fabs(v), 5.0 + 1e-3) << k;
    ASSERT_LE(std::fabs(v - vel), 50.0 * kDt + 1e-3) << k;
    pos = o.pos;
    vel = v;
  }
}

TEST(CamCoupling, WithoutItsMasterTheOffsetStandsAndAReleaseStillEnds) {
  CamProfile p = table(8, 0.0, bump);
  CamCoupling c(CamCouplingSetup{kDt, kVel, kAcc});
  c.couple(p);
  CamOffset o;
  for (int k = 0; k < 500; ++k) {
    o = c.step(180.0);
  }
  ASSERT_TRUE(o.locked);
  EXPECT_NEAR(o.pos, 1.0, 1e-12);
  o = c.step_without_master();
  EXPECT_EQ(o.pos, 1.0);
  EXPECT_EQ(o.vel, 0.0);
  c.release();
  for (int k = 0; k < 1000 && c.active(); ++k) {
    o = c.step_without_master();
  }
  EXPECT_FALSE(c.active());
  EXPECT_EQ(c.offset(), 0.0);
}

}  // namespace
}  // namespace mcnc::coupling
