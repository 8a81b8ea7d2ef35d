// G81.4 / G80.4 electronic gear box (spec dafeng §2.6.11, L3231-3374): the work axis turns L/T
// times the tool spindle, plus the helical term of the axial axis's travel; with R it is brought
// into phase within one period 360 |L| / T; G80.4 stops it within the stop time where it reached.
#include "axisnode/coupling/gear_box_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace mcnc::coupling {
namespace {

constexpr double kDt = 0.001;
constexpr double kAcc = 7200.0;

GearBoxSetup setup() {
  GearBoxSetup s;
  s.cycle_s = kDt;
  s.max_acceleration = kAcc;
  s.stop_time_s = 0.4;
  return s;
}

GearBoxCommand gear(int t, int l) {
  GearBoxCommand c;
  c.teeth = t;
  c.threads = l;
  return c;
}

TEST(GearBoxCoupling, CommandErrorsNameTheWord) {
  EXPECT_EQ(gear_box_command_error(gear(1, 1)), nullptr);
  EXPECT_NE(gear_box_command_error(gear(0, 1)), nullptr);
  EXPECT_NE(gear_box_command_error(gear(10, 0)), nullptr);
  GearBoxCommand helical = gear(10, 1);
  helical.helix = 20.0;
  EXPECT_NE(gear_box_command_error(helical), nullptr);  // no module
  helical.module = -2.0;
  EXPECT_EQ(gear_box_command_error(helical), nullptr);
  helical.helix = 95.0;
  EXPECT_NE(gear_box_command_error(helical), nullptr);
  GearBoxCommand phased = gear(10, 1);
  phased.phase = true;
  phased.r = 360.0;
  EXPECT_NE(gear_box_command_error(phased), nullptr);
}

TEST(GearBoxCoupling, RatioAndHelicalTermFollowTheFormulas) {
  EXPECT_DOUBLE_EQ(gear_box_ratio(gear(40, -2), false), -0.05);
  EXPECT_DOUBLE_EQ(gear_box_ratio(gear(40, -2), true), 0.05);
  GearBoxCommand c = gear(30, 1);
  c.helix = 30.0;
  c.module = 2.0;
  // 10 mm x sin 30 / (pi x 30 x 2) x 360 = 1800 / (60 pi) degrees.
  EXPECT_NEAR(helical_angle(c, 10.0, false), 30.0 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(helical_angle(c, 10.0, true), -30.0 / std::numbers::pi, 1e-12);
  c.module = -2.0;  // Q's sign turns the term (L3349)
  EXPECT_NEAR(helical_angle(c, 10.0, false), -30.0 / std::numbers::pi, 1e-12);
  EXPECT_EQ(helical_angle(gear(30, 1), 10.0, false), 0.0);
}

TEST(GearBoxCoupling, WithoutRNothingMovesAtG814AndTheWorkFollowsFromThere) {
  GearBoxCoupling c(setup());
  c.couple(gear(20, 1), 137.0, 0.0, 42.0);
  GearBoxOffset o = c.step(137.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(o.pos, 0.0);
  EXPECT_TRUE(o.locked);
  // The tool turns a revolution slowly: the work one tooth, 18 degrees.
  for (int n = 1; n <= 1000; ++n) {
    o = c.step(137.0 + 0.36 * n, 360.0, 0.0, 0.0);
  }
  EXPECT_NEAR(o.pos, 18.0, 1e-9);
  EXPECT_NEAR(o.vel, 18.0, 1e-9);
}

TEST(GearBoxCoupling, WithRTheWorkComesIntoPhaseByTheShortestWayWithinAPeriod) {
  GearBoxCoupling c(setup());
  GearBoxCommand g = gear(10, 2);  // period 72 degrees
  g.phase = true;
  g.r = 5.0;
  // Work at 100 (setpoint, no offset), tool at 20: ratio x tool + R = 9, and 9 + 72 = 81 is the
  // nearest angle of that phase to 100, 19 degrees away.
  c.couple(g, 20.0, 0.0, 100.0);
  GearBoxOffset o;
  for (int n = 0; n < 3000 && !o.locked; ++n) {
    o = c.step(20.0, 0.0, 0.0, 0.0);
    EXPECT_LE(std::fabs(o.pos), 19.0 + 1e-9);
  }
  ASSERT_TRUE(o.locked);
  o = c.step(20.0, 0.0, 0.0, 0.0);
  EXPECT_NEAR(100.0 + o.pos, 81.0, 1e-9);
}

TEST(GearBoxCoupling, SeededGearsCatchUpWithinTheAccelerationAndThenHoldTheRatio) {
  for (std::uint32_t seed = 1; seed <= 80; ++seed) {
    std::mt19937 rng(seed);
    GearBoxCommand g = gear(std::uniform_int_distribution<int>(1, 120)(rng), 1);
    g.threads = std::uniform_int_distribution<int>(1, 4)(rng) *
                (std::uniform_int_distribution<int>(0, 1)(rng) == 0 ? -1 : 1);
    g.phase = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    g.r = std::uniform_real_distribution<double>(0.0, 359.999)(rng);
    if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) {
      g.helix = std::uniform_real_distribution<double>(-45.0, 45.0)(rng);
      g.module = std::uniform_real_distribution<double>(0.5, 5.0)(rng);
    }
    ASSERT_EQ(gear_box_command_error(g), nullptr);
    const double ratio = gear_box_ratio(g, false);
    // The tool's speed such that the work needs at most 1800 deg/s; Z feeds at up to 5 mm/s.
    const double tool_vel =
        std::uniform_real_distribution<double>(-1800.0, 1800.0)(rng) / std::fabs(ratio);
    const double z_vel =
        g.helix != 0.0 ? std::uniform_real_distribution<double>(-5.0, 5.0)(rng) : 0.0;
    const double tool0 = std::uniform_real_distribution<double>(-720.0, 720.0)(rng);
    const double setpoint = std::uniform_real_distribution<double>(-360.0, 360.0)(rng);
    GearBoxCoupling c(setup());
    c.couple(g, tool0, 0.0, setpoint);
    double last_vel = 0.0;
    bool locked = false;
    int n = 0;
    for (; n < 6000 && !locked; ++n) {
      const GearBoxOffset o = c.step(tool0 + tool_vel * kDt * n, tool_vel, z_vel * kDt * n, z_vel);
      EXPECT_LE(std::fabs(o.vel - last_vel) / kDt, kAcc * (1.0 + 1e-9)) << "seed " << seed;
      last_vel = o.vel;
      locked = o.locked;
    }
    ASSERT_TRUE(locked) << "seed " << seed;
    // The cycle it locks in is within 0.05 degree; from the next one the work axis's angle is
    // the gear's, exactly, every cycle.
    c.step(tool0 + tool_vel * kDt * n, tool_vel, z_vel * kDt * n, z_vel);
    const double base = setpoint + c.offset() - ratio * (tool0 + tool_vel * kDt * n) -
                        helical_angle(g, z_vel * kDt * n, false);
    if (g.phase) {
      // In phase: the work's angle is ratio x tool + helical + R modulo one period.
      const double period = 360.0 * std::fabs(ratio);
      const double k = (base - g.r) / period;
      EXPECT_NEAR(k, std::round(k), 1e-9 * (1.0 + std::fabs(k))) << "seed " << seed;
    }
    for (int m = n + 1; m < n + 500; ++m) {
      const GearBoxOffset o = c.step(tool0 + tool_vel * kDt * m, tool_vel, z_vel * kDt * m, z_vel);
      ASSERT_TRUE(o.locked) << "seed " << seed;
      const double want =
          base + ratio * (tool0 + tool_vel * kDt * m) + helical_angle(g, z_vel * kDt * m, false);
      EXPECT_NEAR(setpoint + o.pos, want, 1e-6) << "seed " << seed << " cycle " << m;
    }
    EXPECT_EQ(c.worst_deviation(), 0.0);
  }
}

TEST(GearBoxCoupling, G804StopsWithinTheStopTimeWhereItReachedAndTheChannelAbsorbsIt) {
  GearBoxCoupling c(setup());
  c.couple(gear(4, 1), 0.0, 0.0, 0.0);  // a quarter of the tool's speed
  GearBoxOffset o;
  int n = 0;
  for (; n < 3000; ++n) {
    o = c.step(1.2 * n, 1200.0, 0.0, 0.0);  // 1200 deg/s: the work at 300 deg/s
  }
  ASSERT_TRUE(o.locked);
  c.release();
  int cycles = 0;
  double last = o.pos;
  while (c.active() && cycles < 10000) {
    o = c.step(1.2 * (n + cycles), 1200.0, 0.0, 0.0);  // the tool turns on (L3339)
    EXPECT_GE(o.pos, last);                            // slows down, never back
    last = o.pos;
    ++cycles;
  }
  EXPECT_LE(cycles * kDt, 0.4 + kDt);  // param 5333
  EXPECT_GE(cycles * kDt, 0.4 - 2 * kDt);
  EXPECT_EQ(o.vel, 0.0);
  // Where it reached: 300 deg/s over 0.4 s of even deceleration adds about 60 degrees.
  EXPECT_NEAR(o.pos - 0.25 * 1.2 * (n - 1), 60.0, 0.5);
  ASSERT_TRUE(c.stopped_off_setpoint());
  const double reached = c.offset();
  EXPECT_EQ(c.step(9999.0, 1200.0, 0.0, 0.0).pos, reached);  // stands there, whatever the tool
  c.absorb();
  EXPECT_EQ(c.offset(), 0.0);
  EXPECT_FALSE(c.stopped_off_setpoint());
}

TEST(GearBoxCoupling, AToolSpindleFasterThanTheWorkCanFollowRaisesTheDeviationAlarm) {
  GearBoxSetup s = setup();
  s.max_deviation = 30.0;     // deg/s
  s.deviation_time_s = 0.05;  // s
  GearBoxCoupling c(s);
  c.couple(gear(1, 1), 0.0, 0.0, 0.0);
  double tool = 0.0;
  double vel = 0.0;
  int n = 0;
  for (; n < 100; ++n) {  // at rest: locked
    ASSERT_TRUE(c.step(tool, vel, 0.0, 0.0).locked);
  }
  // The tool spindle jumps up at twice the work axis's acceleration.
  for (; n < 2000 && !c.deviation_alarm(); ++n) {
    vel += 2.0 * kAcc * kDt;
    tool += vel * kDt;
    c.step(tool, vel, 0.0, 0.0);
  }
  ASSERT_TRUE(c.deviation_alarm());
  // Off by more than 30 deg/s for more than 0.05 s: 30 / 7200 s to get there, then 0.05 s.
  EXPECT_NEAR((n - 100) * kDt, 30.0 / kAcc + 0.05, 3 * kDt);
  EXPECT_TRUE(c.releasing());  // and the work axis stops
}

TEST(GearBoxCoupling, WithoutTheToolSpindleTheWorkAxisStops) {
  GearBoxCoupling c(setup());
  c.couple(gear(2, 1), 0.0, 0.0, 0.0);
  for (int n = 0; n < 2000; ++n) {
    c.step(0.36 * n, 360.0, 0.0, 0.0);
  }
  int cycles = 0;
  while (c.active() && cycles < 10000) {
    c.step_without_master();
    ++cycles;
  }
  EXPECT_FALSE(c.active());
  EXPECT_LE(cycles * kDt, 0.4 + kDt);
}

}  // namespace
}  // namespace mcnc::coupling
