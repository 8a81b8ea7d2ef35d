// G51.4 (spec dafeng §3.2): the slave copies its master's increments, moves with the master in
// the same cycle although it learns the master's position a cycle late, and after every move has
// moved by exactly what the master moved.
#include "axisnode/coupling/axis_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.001;

// A smooth move of `length` in `cycles` (acceleration continuous, as the planner's S-curve).
std::vector<double> smooth_move(double from, double length, int cycles) {
  std::vector<double> p;
  for (int n = 0; n <= cycles; ++n) {
    const double u = static_cast<double>(n) / cycles;
    p.push_back(from +
                length * (u - std::sin(2.0 * std::numbers::pi * u) / (2.0 * std::numbers::pi)));
  }
  return p;
}

TEST(AxisCoupling, CopiesIncrementsNotPositions) {
  AxisCoupling c(kDt);
  EXPECT_FALSE(c.active());
  c.couple(1);
  EXPECT_TRUE(c.active());
  EXPECT_EQ(c.master(), 1U);
  // Master at 100, slave at -7: the slave stays at -7 plus what the master moves.
  const std::vector<double> master = smooth_move(100.0, 10.0, 2000);
  double slave = -7.0;
  double worst = 0.0;
  for (std::size_t n = 1; n < master.size(); ++n) {
    slave = c.step(master[n - 1], slave).pos;  // the master's position of the last cycle in
    worst = std::max(worst, std::fabs((slave + 7.0) - (master[n] - 100.0)));
  }
  for (int n = 0; n < 5; ++n) {
    slave = c.step(master.back(), slave).pos;  // the master stands
  }
  EXPECT_NEAR(slave, 3.0, 1e-12);
  // With the same cycle's master: off by at most the acceleration times a cycle squared
  // (peak 2 pi x 10 mm / 2 s^2 here, about 16 mm/s^2).
  EXPECT_LT(worst, 2e-5);
}

TEST(AxisCoupling, ConstantSpeedIsExactFromTheSecondCycle) {
  AxisCoupling c(kDt);
  c.couple(3);
  double slave = 0.0;
  const double speed = 50.0;  // mm/s
  AxisTarget t;
  for (int n = 0; n < 100; ++n) {
    t = c.step(speed * kDt * n, slave);  // the master's position at cycle n, known at n + 1
    slave = t.pos;
    if (n >= 1) {
      EXPECT_NEAR(slave, speed * kDt * (n + 1), 1e-9) << n;
    }
  }
  EXPECT_NEAR(t.vel, speed, 1e-6);
}

TEST(AxisCoupling, ResumesWithoutAJumpAfterItDidNotFollow) {
  AxisCoupling c(kDt);
  c.couple(1);
  double slave = 5.0;
  slave = c.step(0.0, slave).pos;
  slave = c.step(1.0, slave).pos;  // moves with the master: 5 + 1 + 1 (extrapolated)
  EXPECT_NEAR(slave, 7.0, 1e-12);
  // The slave's drive stops (an E-stop) while the master goes on to 20: where the slave
  // stands is where it resumes from, with no catch-up jump.
  c.rebase();
  const double stopped = 6.5;
  slave = c.step(20.0, stopped).pos;
  EXPECT_NEAR(slave, stopped, 1e-12);
  slave = c.step(21.0, slave).pos;
  EXPECT_NEAR(slave, stopped + 2.0, 1e-12);
  c.decouple();
  EXPECT_FALSE(c.active());
  EXPECT_EQ(c.master(), 0U);
}

// Seeded random moves, rests and speeds: at every rest the slave has moved by what the master
// moved since the coupling, to the last bit the arithmetic leaves.
TEST(AxisCoupling, RandomMovesAddUpExactly) {
  std::mt19937 rng(514);
  std::uniform_real_distribution<double> length(-50.0, 50.0);
  std::uniform_int_distribution<int> duration(1, 800);
  AxisCoupling c(kDt);
  c.couple(2);
  double master = 12.5;
  double slave = -3.25;
  const double master0 = master;
  const double slave0 = slave;
  for (int move = 0; move < 200; ++move) {
    const std::vector<double> m = smooth_move(master, length(rng), duration(rng));
    for (double p : m) {
      slave = c.step(p, slave).pos;
    }
    master = m.back();
    slave = c.step(master, slave).pos;
    slave = c.step(master, slave).pos;
    ASSERT_NEAR(slave - slave0, master - master0, 1e-9) << "after move " << move;
  }
}

}  // namespace
}  // namespace mcnc::coupling
