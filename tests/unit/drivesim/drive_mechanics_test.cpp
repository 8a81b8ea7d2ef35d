// The simulated drive's mechanics under its loops: a P position loop over a PI velocity loop,
// torque-limited, driving J w' = T - B w. What a user of the simulator relies on: the target
// is reached, the speed and torque limits hold, inertia and friction act as physics says, and a
// quick stop ramps at the configured deceleration.
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/cia402_state.hpp"
#include "pressing_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

namespace mcnc::drivesim {
namespace {

constexpr double kCycle = 0.001;
constexpr double kTwoPi = 6.283185307179586;

DriveParams params() {
  DriveParams p;
  p.counts_per_unit = 10000.0;
  p.time_constant_s = 0.004;
  p.max_velocity = 500.0;
  p.quick_stop_decel = 5000.0;
  return p;
}

SimulatedDrive enabled(const DriveParams& p, double cycle_s = kCycle) {
  return test::enabled_drive(p, cycle_s);
}

canopen::TxPdoCsp cycle(SimulatedDrive& d, double target, std::uint16_t cw = 0x0F) {
  d.on_rpdo(canopen::RxPdoCsp{cw, static_cast<std::int32_t>(std::lround(target * 10000.0))});
  return d.on_sync();
}

TEST(DriveMechanics, AStepIsReachedWithinAFewLoopTimeConstantsAndBarelyOvershoots) {
  SimulatedDrive d = enabled(params());
  ASSERT_EQ(d.state(), cia402::State::operation_enabled);
  double peak = 0.0;
  int reached_at = -1;
  for (int n = 1; n <= 100; ++n) {
    const auto t = cycle(d, 1.0);
    peak = std::max(peak, d.position());
    EXPECT_EQ(t.position_actual, static_cast<std::int32_t>(std::lround(d.position() * 1e4)));
    if (reached_at < 0 && (t.statusword & 0x0400U) != 0) {
      reached_at = n;
    }
  }
  // A first-order loop with tau = 4 ms is within half a count after 34 cycles; the velocity
  // loop's lag and the fine interpolation of the step over its cycle add some.
  EXPECT_GE(reached_at, 30);
  EXPECT_LE(reached_at, 60);
  EXPECT_LT(peak, 1.0 + 0.02);  // under 2 % overshoot
  EXPECT_NEAR(d.position(), 1.0, 0.5e-4);
}

TEST(DriveMechanics, FollowingErrorAtConstantSpeedIsSpeedTimesTheLoopTimeConstant) {
  SimulatedDrive d = enabled(params());
  double target = 0.0;
  for (int n = 0; n < 500; ++n) {
    target += 100.0 * kCycle;  // 100 units/s
    cycle(d, target);
  }
  EXPECT_NEAR(d.velocity(), 100.0, 1e-3);
  EXPECT_NEAR(target - d.position(), 100.0 * 0.004, 0.02);
}

TEST(DriveMechanics, SpeedStaysAtTheDrivesLimit) {
  SimulatedDrive d = enabled(params());
  double fastest = 0.0;
  for (int n = 0; n < 300; ++n) {
    cycle(d, 1000.0);
    fastest = std::max(fastest, std::abs(d.velocity()));
  }
  EXPECT_LE(fastest, 500.0 * 1.02);  // the velocity loop overshoots its command by little
  EXPECT_NEAR(d.velocity(), 500.0, 0.5);
}

TEST(DriveMechanics, AccelerationIsTheTorqueLimitOverTheInertia) {
  // A far target saturates the torque: a = T_max / J at the motor, less friction, times the
  // lead per radian at the load. Twice the inertia, half the acceleration.
  auto peak_acceleration = [](double inertia) {
    DriveParams p = params();
    p.inertia = inertia;
    SimulatedDrive d = enabled(p);
    double peak = 0.0;
    double v = d.velocity();
    for (int n = 0; n < 5; ++n) {
      cycle(d, 100.0);
      peak = std::max(peak, (d.velocity() - v) / kCycle);
      v = d.velocity();
      EXPECT_LE(std::abs(d.torque()), p.torque_limit);
    }
    return peak;
  };
  const double a1 = peak_acceleration(0.0005);
  const double a2 = peak_acceleration(0.0010);
  const double limit = 10.0 / 0.0005 * 10.0 / kTwoPi;  // 31 831 units/s^2
  EXPECT_LE(a1, limit);
  EXPECT_GT(a1, 0.95 * limit);
  EXPECT_NEAR(a2 / a1, 0.5, 0.02);
}

TEST(DriveMechanics, HoldingASpeedTakesTheFrictionTorque) {
  DriveParams p = params();
  p.friction = 0.002;
  SimulatedDrive d = enabled(p);
  const std::uint8_t csv_mode = 9;
  ASSERT_EQ(d.objects().write(0x6060, 0, &csv_mode, 1), 0U);
  RpdoValues csv;
  csv.controlword = 0x0F;
  csv.has_controlword = true;
  csv.target_velocity = 300000;  // 30 units/s in 0x60FF
  csv.has_target_velocity = true;
  for (int n = 0; n < 1000; ++n) {
    d.on_rpdo(csv);
    d.on_sync();
  }
  EXPECT_NEAR(d.velocity(), 30.0, 1e-6);
  const double w = 30.0 * kTwoPi / 10.0;  // rad/s at the motor
  EXPECT_NEAR(d.torque(), 0.002 * w, 1e-6);
}

TEST(DriveMechanics, QuickStopRampsAtItsDecelerationAndStays) {
  SimulatedDrive d = enabled(params());
  for (int n = 0; n < 100; ++n) {
    cycle(d, 1000.0);  // at the 500 units/s limit
  }
  ASSERT_NEAR(d.velocity(), 500.0, 0.5);
  const double start = d.position();
  int cycles = 0;
  double slowest = 1e9;
  while (d.velocity() != 0.0 && cycles < 1000) {
    const auto t = cycle(d, 1000.0, 0x0002);
    ++cycles;
    EXPECT_EQ(cia402::decode_statusword(t.statusword), cia402::State::quick_stop_active);
    slowest = std::min(slowest, d.velocity());
  }
  // 500 units/s at 5000 units/s^2: 100 ms and v^2 / 2a = 25 units, give or take the velocity
  // loop settling at the end of the ramp (its integral still holds the friction torque).
  EXPECT_GE(cycles, 100);
  EXPECT_LE(cycles, 110);
  EXPECT_NEAR(d.position() - start, 25.0, 0.6);
  EXPECT_GT(slowest, -1.0);  // no more than a trace of reversing (under a micrometre)
  const double rest = d.position();
  for (int n = 0; n < 50; ++n) {
    const auto t = cycle(d, 1000.0, 0x0002);
    EXPECT_NE(t.statusword & 0x0400U, 0U);  // halted
  }
  EXPECT_EQ(d.position(), rest);
  // Back to operation (transition 16) without a jump to the old target.
  cycle(d, 1000.0);
  EXPECT_EQ(d.state(), cia402::State::operation_enabled);
  EXPECT_NEAR(d.position(), rest, 1e-9);
}

TEST(DriveMechanics, TheQuickStopRampIsTheDecelerationInTheObjectDictionary) {
  // The drive's own default (quick_stop_decel) until a master writes 0x6085; 10 000 units/s^2
  // stops 500 units/s in 50 ms instead of 100.
  SimulatedDrive d = enabled(params());
  EXPECT_EQ(d.objects().quick_stop_deceleration(), 5000U * 10000U);
  const std::uint32_t v = 10000U * 10000U;
  const std::uint8_t bytes[4] = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                 static_cast<std::uint8_t>(v >> 16),
                                 static_cast<std::uint8_t>(v >> 24)};
  ASSERT_EQ(d.objects().write(0x6085, 0, bytes, 4), 0U);
  for (int n = 0; n < 100; ++n) {
    cycle(d, 1000.0);
  }
  int cycles = 0;
  while (d.velocity() != 0.0 && cycles < 1000) {
    cycle(d, 1000.0, 0x0002);
    ++cycles;
  }
  EXPECT_GE(cycles, 50);
  EXPECT_LE(cycles, 60);
}

TEST(DriveMechanics, ObjectDefaultsAreAppliedAtPowerOnAndAfterResetNode) {
  DriveParams p = params();
  p.objects[0] = ObjectDefault{0x607C, 0, -1234};  // home offset
  p.objects[1] = ObjectDefault{0x6098, 0, 35};     // homing method
  p.object_count = 2;
  SimulatedDrive d(p, kCycle);
  EXPECT_EQ(d.objects().home_offset(), -1234);
  EXPECT_EQ(d.objects().homing_method(), 35);
  d.power_on();
  d.on_nmt(canopen::NmtCommand::reset_node);
  EXPECT_EQ(d.objects().home_offset(), -1234);
  // A value the dictionary refuses, or an object it does not have, is reported.
  p.objects[1] = ObjectDefault{0x6098, 0, 12};
  SimulatedDrive bad(p, kCycle);
  ObjectDefault failed;
  EXPECT_NE(bad.apply_defaults(&failed), 0U);
  EXPECT_EQ(failed.index, 0x6098);
  p.objects[1] = ObjectDefault{0x6098, 0, 264};  // does not fit the 8-bit object
  SimulatedDrive too_big(p, kCycle);
  EXPECT_EQ(too_big.apply_defaults(&failed), 0x06090030U);
  p.objects[1] = ObjectDefault{0x2000, 0, 1};
  SimulatedDrive unknown(p, kCycle);
  EXPECT_EQ(unknown.apply_defaults(&failed), 0x06020000U);  // object does not exist
}

TEST(DriveMechanics, StaysStableAtLongCyclesAndStiffTunings) {
  // A 32 ms cycle, a 2 kHz velocity loop, a tiny inertia: the step settles all the same.
  for (const auto& [cycle_s, bandwidth, inertia] :
       {std::tuple{0.032, 200.0, 0.0005}, std::tuple{0.001, 2000.0, 0.0005},
        std::tuple{0.001, 200.0, 1e-7}}) {
    DriveParams p = params();
    p.velocity_bandwidth_hz = bandwidth;
    p.inertia = inertia;
    SimulatedDrive d = enabled(p, cycle_s);
    for (int n = 0; n < static_cast<int>(2.0 / cycle_s); ++n) {
      d.on_rpdo(canopen::RxPdoCsp{0x0F, 100000});  // 10 units
      d.on_sync();
    }
    EXPECT_NEAR(d.position(), 10.0, 1e-3) << cycle_s << " " << bandwidth << " " << inertia;
    EXPECT_NEAR(d.velocity(), 0.0, 1e-2) << cycle_s << " " << bandwidth << " " << inertia;
  }
}

}  // namespace
}  // namespace mcnc::drivesim
