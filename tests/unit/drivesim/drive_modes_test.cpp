// The simulated drive's modes of operation beyond CSP: cyclic synchronous velocity and homing
// by the current position (CiA 402 methods 35/37).
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/cia402_state.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::drivesim {
namespace {

constexpr double kCycle = 0.001;

void write_i8(SimulatedDrive& d, std::uint16_t index, std::int8_t v) {
  const auto b = static_cast<std::uint8_t>(v);
  ASSERT_EQ(d.objects().write(index, 0, &b, 1), 0U);
}

void write_i32(SimulatedDrive& d, std::uint16_t index, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  const std::uint8_t b[4] = {static_cast<std::uint8_t>(u), static_cast<std::uint8_t>(u >> 8),
                             static_cast<std::uint8_t>(u >> 16),
                             static_cast<std::uint8_t>(u >> 24)};
  ASSERT_EQ(d.objects().write(index, 0, b, 4), 0U);
}

// Powered, started and walked to operation enabled by the controlword sequence.
SimulatedDrive enabled_drive(double start) {
  SimulatedDrive d(DriveParams{1, 10000.0, 0.004, 500.0, 5000.0, start}, kCycle);
  d.power_on();
  d.on_nmt(canopen::NmtCommand::start);
  for (const std::uint16_t cw : {0x06, 0x07, 0x0F, 0x0F}) {
    d.on_rpdo(canopen::RxPdoCsp{cw, static_cast<std::int32_t>(std::lround(start * 10000.0))});
    d.on_sync();
  }
  return d;
}

TEST(DriveModes, CsvFollowsTheTargetVelocity) {
  SimulatedDrive d = enabled_drive(5.0);
  ASSERT_EQ(d.state(), cia402::State::operation_enabled);
  write_i8(d, 0x6060, 9);
  // 20 mm/s = 200 000 counts/s for 0.5 s: about 10 mm, the velocity settled on its target.
  RpdoValues csv;
  csv.controlword = 0x0F;
  csv.has_controlword = true;
  csv.target_velocity = 200000;  // 0x60FF
  csv.has_target_velocity = true;
  for (int i = 0; i < 500; ++i) {
    d.on_rpdo(csv);
    d.on_sync();
  }
  EXPECT_NEAR(d.velocity(), 20.0, 1e-6);
  // Less the velocity loop's lag (a few milliseconds at 20 mm/s): under 0.1 mm.
  EXPECT_NEAR(d.position(), 15.0, 0.1);
  // Velocity 0: it stops where it is (no position target pulls it back).
  csv.target_velocity = 0;
  for (int i = 0; i < 100; ++i) {
    d.on_rpdo(csv);
    d.on_sync();
  }
  EXPECT_NEAR(d.velocity(), 0.0, 1e-6);
  EXPECT_GT(d.position(), 14.9);
}

TEST(DriveModes, HomingByTheCurrentPositionSetsTheHomeOffset) {
  SimulatedDrive d = enabled_drive(123.4);
  write_i32(d, 0x607C, -5000);  // home offset -0.5 mm
  write_i8(d, 0x6098, 37);
  write_i8(d, 0x6060, 6);
  d.on_rpdo(canopen::RxPdoCsp{0x0F, 0});
  canopen::TxPdoCsp t = d.on_sync();
  EXPECT_EQ(t.statusword & 0x1000U, 0U);  // not homed yet
  d.on_rpdo(canopen::RxPdoCsp{0x1F, 0});  // bit 4: start
  t = d.on_sync();
  EXPECT_NE(t.statusword & 0x1000U, 0U);  // homing attained
  EXPECT_EQ(t.position_actual, -5000);
  EXPECT_DOUBLE_EQ(d.position(), -0.5);
  EXPECT_DOUBLE_EQ(d.velocity(), 0.0);  // it did not move
  // Back to CSP: the bit goes, the position stays.
  write_i8(d, 0x6060, 8);
  d.on_rpdo(canopen::RxPdoCsp{0x0F, -5000});
  t = d.on_sync();
  EXPECT_EQ(t.statusword & 0x1000U, 0U);
  EXPECT_EQ(t.position_actual, -5000);
  // Methods that need switches are refused.
  const auto method = static_cast<std::uint8_t>(1);
  EXPECT_NE(d.objects().write(0x6098, 0, &method, 1), 0U);
}

}  // namespace
}  // namespace mcnc::drivesim
