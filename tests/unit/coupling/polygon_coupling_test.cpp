// G51.2 / G50.2 polygon turning (spec dafeng §2.6.6, L2847-2939): the polygon axis turns Q/P
// times the master spindle, stands at its zero while the master stands at R, and G50.2 brings it
// to rest within its acceleration.
#include "axisnode/coupling/spindle_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.002;
constexpr double kAcc = 3600.0;

SpindleCoupling coupling() {
  return SpindleCoupling(SpindleCouplingSetup{kDt, kAcc, 0.05, 1.0});
}

TEST(PolygonCoupling, TheSlaveStandsAtItsZeroWhileTheMasterStandsAtR) {
  SpindleCoupling c = coupling();
  c.couple(polygon_command(1, 2, 30.0), 123.0, 0.0);
  SlaveTarget t;
  for (int n = 0; n < 2000 && !t.locked; ++n) {
    t = c.step(30.0, 0.0);
  }
  ASSERT_TRUE(t.locked);
  t = c.step(30.0, 0.0);  // the cycle it locks in is within 0.05 deg; exact from the next
  EXPECT_NEAR(wrap_degrees(t.pos), 0.0, 1e-9);
  // The master a quarter turn on: the slave half a turn (Q/P = 2).
  t = c.step(120.0, 0.0);
  EXPECT_NEAR(std::fabs(wrap_degrees(t.pos)), 180.0, 1e-9);
}

TEST(PolygonCoupling, SeededRatiosFollowTheMasterAtQOverPFromTheStartAngle) {
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    std::mt19937 rng(seed);
    const int p = std::uniform_int_distribution<int>(1, 6)(rng);
    int q = std::uniform_int_distribution<int>(-8, 7)(rng);
    q = q >= 0 ? q + 1 : q;  // never 0
    const double r = std::uniform_real_distribution<double>(0.0, 360.0)(rng);
    const double ratio = static_cast<double>(q) / p;
    // The master's speed such that the slave needs at most 2400 deg/s.
    const double master_vel =
        std::uniform_real_distribution<double>(-2400.0, 2400.0)(rng) / std::fabs(ratio);
    const double master_start = std::uniform_real_distribution<double>(-720.0, 720.0)(rng);
    SpindleCoupling c = coupling();
    c.couple(polygon_command(p, q, r), std::uniform_real_distribution<double>(-360.0, 360.0)(rng),
             0.0);
    int locked_at = -1;
    double last_vel = 0.0;
    for (int n = 0; n < 4000; ++n) {
      const double master = master_start + master_vel * kDt * n;
      const SlaveTarget t = c.step(master, master_vel);
      if (locked_at < 0) {
        EXPECT_LE(std::fabs(t.vel - last_vel) / kDt, kAcc + 1e-6) << "seed " << seed;
      }
      last_vel = t.vel;
      if (t.locked && locked_at < 0) {
        locked_at = n;
      }
      if (locked_at >= 0 && n > locked_at) {  // exact from the cycle after it locks
        ASSERT_NEAR(wrap_degrees((master - r) * ratio - t.pos), 0.0, 1e-6)
            << "seed " << seed << " P" << p << " Q" << q << " R" << r << " cycle " << n;
        ASSERT_NEAR(t.vel, master_vel * ratio, 1e-9) << "seed " << seed;
      }
    }
    EXPECT_GE(locked_at, 0) << "seed " << seed << " P" << p << " Q" << q;
  }
}

TEST(PolygonCoupling, ReleaseDeceleratesWithinTheLimitToRestThenEnds) {
  SpindleCoupling c = coupling();
  c.couple(polygon_command(1, 2, 0.0), 0.0, 0.0);
  const double master_vel = 3000.0;  // 500 rpm: the slave at 1000 rpm (spec L2953-2969)
  SlaveTarget t;
  int n = 0;
  for (; n < 4000 && !t.locked; ++n) {
    t = c.step(master_vel * kDt * n, master_vel);
  }
  ASSERT_TRUE(t.locked);
  t = c.step(master_vel * kDt * n, master_vel);
  ++n;
  EXPECT_NEAR(t.vel, 6000.0, 1e-9);
  c.release();
  EXPECT_TRUE(c.releasing());
  double last_pos = t.pos;
  double last_vel = t.vel;
  int cycles = 0;
  while (c.active() && cycles < 4000) {
    t = c.step(master_vel * kDt * (n + cycles), master_vel);  // the master turns on
    EXPECT_LE(std::fabs(t.vel - last_vel), kAcc * kDt + 1e-9);
    EXPECT_NEAR(t.pos - last_pos, t.vel * kDt, 1e-9);
    EXPECT_FALSE(t.locked);
    last_pos = t.pos;
    last_vel = t.vel;
    ++cycles;
  }
  EXPECT_FALSE(c.active());
  EXPECT_EQ(t.vel, 0.0);
  EXPECT_NEAR(cycles * kDt, 6000.0 / kAcc, 2 * kDt);  // 1.67 s at 3600 deg/s^2
  // Released, the coupling no longer moves it.
  const SlaveTarget after = c.step(0.0, master_vel);
  EXPECT_EQ(after.pos, last_pos);
  EXPECT_EQ(after.vel, 0.0);
}

TEST(PolygonCoupling, ANewCouplingDuringTheReleaseFollowsAgain) {
  SpindleCoupling c = coupling();
  c.couple(polygon_command(1, 1, 0.0), 0.0, 0.0);
  for (int n = 0; n < 500; ++n) {
    (void)c.step(600.0 * kDt * n, 600.0);
  }
  c.release();
  (void)c.step(0.0, 600.0);
  c.couple(polygon_command(1, 1, 0.0), 0.0, 0.0);
  EXPECT_FALSE(c.releasing());
  EXPECT_TRUE(c.active());
}

}  // namespace
}  // namespace mcnc::coupling
