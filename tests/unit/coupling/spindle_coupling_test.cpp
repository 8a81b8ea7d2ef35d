// G114.1 (spec dafeng §2.6.13): the slave catches up within its acceleration and then follows
// the master in phase, also with a ratio, a reversed direction and a phase offset.
#include "axisnode/coupling/spindle_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.002;

struct CatchUp {
  double max_acc = 0.0;  // the largest acceleration the slave used
  int lock_cycle = -1;
  double worst_after_lock = 0.0;  // phase error once locked
};

// The master turns at `rpm` from `master_start`; the slave starts at rest at `slave_start`.
CatchUp run(SpindleCouplingCommand cmd, double rpm, double master_start, double slave_start,
            int cycles = 3000) {
  SpindleCoupling c(SpindleCouplingSetup{kDt, 3600.0, 0.05, 1.0});
  c.couple(cmd, slave_start, 0.0);
  CatchUp r;
  double last_vel = 0.0;
  const double ratio = static_cast<double>(cmd.q) / cmd.p;
  for (int n = 0; n < cycles; ++n) {
    const double master = master_start + rpm * 6.0 * kDt * n;
    const SlaveTarget t = c.step(master, rpm * 6.0);
    r.max_acc = std::max(r.max_acc, std::fabs(t.vel - last_vel) / kDt);
    last_vel = t.vel;
    if (t.locked && r.lock_cycle < 0) {
      r.lock_cycle = n;
    }
    if (r.lock_cycle >= 0 && n > r.lock_cycle) {
      r.worst_after_lock =
          std::max(r.worst_after_lock, std::fabs(wrap_degrees(master * ratio + cmd.r - t.pos)));
    }
  }
  return r;
}

TEST(SpindleCoupling, ASlaveAtRestCatchesAMasterAt500RpmAndStaysInPhase) {
  const CatchUp r = run({1, 1, 0.0}, 500.0, 90.0, 180.0);
  ASSERT_GE(r.lock_cycle, 0);
  EXPECT_LT(r.lock_cycle * kDt, 3.0);   // 3000 deg/s at 3600 deg/s^2, then the phase
  EXPECT_LE(r.max_acc, 3600.0 + 1e-6);  // never beyond its limit until locked
  EXPECT_LT(r.worst_after_lock, 1e-9);  // then exactly in phase
}

TEST(SpindleCoupling, StaticSyncAlignsTheSlaveToTheMasterPlusR) {
  const CatchUp r = run({1, 1, 90.0}, 0.0, 90.0, 180.0);  // spec: master at 90, slave aligns to +R
  ASSERT_GE(r.lock_cycle, 0);
  EXPECT_LT(r.worst_after_lock, 1e-9);
}

TEST(SpindleCoupling, RatioAndReversedDirection) {
  const CatchUp r = run({2, -1, 45.0}, 300.0, 10.0, 0.0);  // half speed, opposite direction
  ASSERT_GE(r.lock_cycle, 0);
  EXPECT_LT(r.worst_after_lock, 1e-9);
}

TEST(SpindleCoupling, DecoupledItHoldsWhereItWas) {
  SpindleCoupling c(SpindleCouplingSetup{kDt, 3600.0, 0.05, 1.0});
  c.couple({1, 1, 0.0}, 0.0, 0.0);
  EXPECT_TRUE(c.active());
  c.decouple();
  EXPECT_FALSE(c.active());
  EXPECT_FALSE(c.locked());
}

}  // namespace
}  // namespace mcnc::coupling
