// G51.4 (spec dafeng §3.2): the slave copies its master's increments from where both stood
// when it was coupled, moves with the master in the same cycle although it learns the master's
// position a cycle late, and after every move has moved by exactly what the master moved.
#include "axisnode/coupling/axis_coupling.hpp"
#include "axisnode/coupling/master_history.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.001;
constexpr std::uint32_t kX = 1;

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

// The slave node's loop in lockstep: the master's sample of the last cycle in, the slave's
// position of this cycle out.
struct Follower {
  Follower() : history(masters, 1 << 12), coupling(kDt) {}
  std::array<std::uint32_t, 1> masters{kX};
  MasterHistory history;
  AxisCoupling coupling;
  double slave = 0.0;
  std::uint64_t cycle = 0;
  bool slave_operating = true;
  // The master's commanded position at `cycle` (published for the next cycle), then the
  // slave's cycle.
  double run(double master_now, bool master_operating = true) {
    history.put(kX, cycle, master_now, master_operating);
    ++cycle;
    if (!coupling.active()) {
      return slave;
    }
    const MasterHistory::Sample m = history.estimate(kX, cycle, true);
    if (m.lookup == MasterHistory::Lookup::found && m.operating && slave_operating) {
      slave = coupling.step(m.cmd, slave).pos;
    } else {
      coupling.rebase();
    }
    return slave;
  }
};

TEST(AxisCoupling, CopiesIncrementsNotPositionsInTheSameCycle) {
  Follower f;
  f.coupling.couple(kX);
  EXPECT_TRUE(f.coupling.active());
  EXPECT_EQ(f.coupling.master(), kX);
  f.slave = -7.0;  // master at 100, slave at -7: the slave stays at -7 plus what X moves
  const std::vector<double> master = smooth_move(100.0, 10.0, 2000);
  f.run(100.0);
  f.run(100.0);
  double worst = 0.0;
  for (std::size_t n = 0; n + 1 < master.size(); ++n) {
    const double slave = f.run(master[n]);  // the slave's position at the master's next cycle
    worst = std::max(worst, std::fabs((slave + 7.0) - (master[n + 1] - 100.0)));
  }
  for (int n = 0; n < 3; ++n) {
    f.run(master.back());
  }
  EXPECT_NEAR(f.slave, 3.0, 1e-12);
  // Off the master by at most its acceleration times a cycle squared (peak 2 pi x 10 mm / 2 s^2
  // here, about 16 mm/s^2).
  EXPECT_LT(worst, 2e-5);
}

TEST(AxisCoupling, CouplingToAMovingMasterTakesItsSpeedWithoutACatchUpStep) {
  Follower f;
  constexpr double kStep = 0.05;  // the master moves 50 mm/s
  for (int n = 0; n < 10; ++n) {
    f.run(kStep * n);
  }
  f.coupling.couple(kX);
  std::vector<double> slave;
  for (int n = 10; n < 20; ++n) {
    slave.push_back(f.run(kStep * n));
  }
  EXPECT_DOUBLE_EQ(slave[0], 0.0);  // where it stood
  for (std::size_t n = 1; n < slave.size(); ++n) {
    EXPECT_NEAR(slave[n] - slave[n - 1], kStep, 1e-12) << n;  // never two steps at once
  }
}

TEST(AxisCoupling, AMasterOutOfOperationIsNotFollowedAndTheSlaveResumesWithoutAJump) {
  Follower f;
  f.coupling.couple(kX);
  f.slave = 5.0;
  f.run(0.0);
  f.run(0.0);
  EXPECT_NEAR(f.run(1.0), 7.0, 1e-12);  // with the master, which is at 2 by now
  EXPECT_NEAR(f.run(2.0), 8.0, 1e-12);
  EXPECT_NEAR(f.run(2.0), 7.0, 1e-12);  // the master stands at 2: the slave at 5 + 2
  // The master homes: its position jumps to 250 while it is out of operation.
  EXPECT_NEAR(f.run(250.0, false), 7.0, 1e-12);
  EXPECT_NEAR(f.run(250.0, false), 7.0, 1e-12);
  EXPECT_NEAR(f.run(250.0), 7.0, 1e-12);  // in operation again: where both stand
  EXPECT_NEAR(f.run(251.0), 9.0, 1e-12);
  EXPECT_NEAR(f.run(251.0), 8.0, 1e-12);  // the homing's 248 never reached the slave
  // The slave's drive stops (an E-stop) while the master goes on: it resumes from where it
  // stands.
  f.slave_operating = false;
  f.run(255.0);
  f.run(260.0);
  f.slave = 6.5;
  f.slave_operating = true;
  EXPECT_NEAR(f.run(261.0), 6.5, 1e-12);
  EXPECT_NEAR(f.run(262.0), 7.5, 1e-12);
  EXPECT_NEAR(f.run(263.0), 8.5, 1e-12);
  f.coupling.decouple();
  EXPECT_FALSE(f.coupling.active());
  EXPECT_EQ(f.coupling.master(), 0U);
}

// Seeded random moves and rests: at every rest the slave has moved by what the master moved
// since the coupling, to the last bit the arithmetic leaves.
TEST(AxisCoupling, RandomMovesAddUpExactly) {
  std::mt19937 rng(514);
  std::uniform_real_distribution<double> length(-50.0, 50.0);
  std::uniform_int_distribution<int> duration(1, 800);
  Follower f;
  f.coupling.couple(kX);
  double master = 12.5;
  f.slave = -3.25;
  f.run(master);
  f.run(master);
  const double master0 = master;
  const double slave0 = f.slave;
  for (int move = 0; move < 200; ++move) {
    const std::vector<double> m = smooth_move(master, length(rng), duration(rng));
    for (double p : m) {
      f.run(p);
    }
    master = m.back();
    f.run(master);
    f.run(master);
    ASSERT_NEAR(f.slave - slave0, master - master0, 1e-9) << "after move " << move;
  }
}

}  // namespace
}  // namespace mcnc::coupling
