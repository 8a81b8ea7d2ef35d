// The simulated drive's cyclic synchronous torque mode (CiA 402 mode 10): the target torque
// 0x6071 drives the mechanics, bounded by the max torque 0x6072 and the speed limit 0x6080
// (rpm) the way it turns the motor. A free motor runs up to the limit; against a contact it
// stands and presses with the set torque. Back in CSP the position loop starts where it stands.
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/object_access.hpp"
#include "canopen/pdo_layout.hpp"
#include "tests/unit/drivesim/pressing_drive.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

namespace mcnc::drivesim {
namespace {

constexpr double kCounts = test::kPressCounts;
// A tailstock's drive against its centre at -12.5 (test::pressing_drive).
SimulatedDrive tailstock_drive() {
  return test::pressing_drive();
}

// `n` cycles in CST at `torque` (per mille) within `rpm`, `max_torque` (per mille).
void torque_cycles(SimulatedDrive& d, int n, std::int16_t torque, std::uint32_t rpm,
                   std::uint16_t max_torque = canopen::kNoTorqueLimit) {
  for (int i = 0; i < n; ++i) {
    RpdoValues v;
    v.controlword = 0x0F;
    v.has_controlword = true;
    v.mode = 10;
    v.has_mode = true;
    v.target_position = static_cast<std::int32_t>(std::lround(d.position() * kCounts));
    v.has_target_position = true;
    v.target_torque = torque;
    v.has_target_torque = true;
    v.max_motor_speed = rpm;
    v.has_max_motor_speed = true;
    v.max_torque = max_torque;
    v.has_max_torque = true;
    d.on_rpdo(v);
    d.on_sync();
  }
}

TEST(DriveTorqueMode, AFreeMotorRunsUpToTheSpeedLimitTheWayTheTorqueTurnsIt) {
  SimulatedDrive d = tailstock_drive();
  torque_cycles(d, 500, 300, 60);  // 30 %, 60 rpm: 10 units/s
  EXPECT_EQ(d.objects().mode(), 10);
  EXPECT_NEAR(d.velocity(), 10.0, 0.05);
  EXPECT_GT(d.position(), 3.0);
  // At the limit it takes only what the friction asks, far below the set torque.
  EXPECT_GT(d.torque(), 0.0);
  EXPECT_LT(d.torque(), 0.1);
  torque_cycles(d, 500, -300, 120);  // the sign turns it the other way, at 20 units/s
  EXPECT_NEAR(d.velocity(), -20.0, 0.1);
}

TEST(DriveTorqueMode, AgainstTheContactItStandsAndPressesWithTheSetTorque) {
  SimulatedDrive d = tailstock_drive();
  torque_cycles(d, 1000, -500, 600);  // 50 % toward the centre at up to 100 units/s
  EXPECT_DOUBLE_EQ(d.position(), -12.5);
  EXPECT_EQ(d.velocity(), 0.0);
  EXPECT_NEAR(d.torque(), -1.5, 1e-9);
  EXPECT_EQ(d.objects().live.torque, -500);
  EXPECT_EQ(d.objects().live.following_error, 0);  // no position loop: no following error
  // 0x6072 bounds it as in CSP.
  torque_cycles(d, 10, -500, 600, 200);
  EXPECT_NEAR(d.torque(), -0.6, 1e-9);
  EXPECT_EQ(d.objects().live.torque, -200);
}

TEST(DriveTorqueMode, BackInCspThePositionLoopHoldsWhereTheMotorStands) {
  SimulatedDrive d = tailstock_drive();
  torque_cycles(d, 1000, -500, 600);
  ASSERT_DOUBLE_EQ(d.position(), -12.5);
  for (int i = 0; i < 200; ++i) {
    RpdoValues v;
    v.controlword = 0x0F;
    v.has_controlword = true;
    v.mode = 8;
    v.has_mode = true;
    v.target_position = -125000;
    v.has_target_position = true;
    d.on_rpdo(v);
    d.on_sync();
  }
  EXPECT_EQ(d.objects().mode(), 8);
  EXPECT_DOUBLE_EQ(d.position(), -12.5);
  EXPECT_NEAR(d.torque(), 0.0, 1e-6);  // the contact holds, the loop asks nothing
}

TEST(DriveTorqueMode, TheTargetTorqueAndSpeedLimitAreObjectsBySdoAndInAnRpdo) {
  DriveObjects o(1);
  const std::array<std::uint8_t, 1> cst{10};
  EXPECT_EQ(o.write(0x6060, 0, cst.data(), cst.size()), 0U);
  EXPECT_EQ(o.mode(), 10);
  const std::array<std::uint8_t, 2> torque{0x0C, 0xFE};  // -500
  EXPECT_EQ(o.write(0x6071, 0, torque.data(), torque.size()), 0U);
  EXPECT_EQ(o.target_torque(), -500);
  const std::array<std::uint8_t, 4> rpm{0xE8, 0x03, 0, 0};  // 1000
  EXPECT_EQ(o.write(0x6080, 0, rpm.data(), rpm.size()), 0U);
  EXPECT_EQ(o.max_motor_speed(), 1000U);
  EXPECT_NE(o.write(0x6080, 0, torque.data(), torque.size()), 0U);  // 2 bytes: refused
  canopen::SdoValue v;
  EXPECT_EQ(o.read(0x6071, 0, v), 0U);
  EXPECT_EQ(v.size, 2U);
  RpdoValues a;
  a.target_torque = 100;
  a.has_target_torque = true;
  RpdoValues b;
  b.max_motor_speed = 50;
  b.has_max_motor_speed = true;
  a.merge(b);
  EXPECT_TRUE(a.has_target_torque && a.has_max_motor_speed);
  EXPECT_EQ(a.target_torque, 100);
  EXPECT_EQ(a.max_motor_speed, 50U);
}

// The layout both ends use: the master packs mode 10, the target torque and the speed limit,
// the drive reads them by the same mapping, and a press follows.
TEST(DriveTorqueMode, TheLayoutCarriesTheModeTheTorqueAndTheSpeedLimit) {
  canopen::PdoLayout layout = canopen::axis_pdos(false, false, false);
  canopen::add_torque_limit(layout);
  canopen::add_torque_mode(layout);
  ASSERT_EQ(layout.rpdo1.count, 3u);
  EXPECT_EQ(layout.rpdo1.objects[2].index, 0x6060);
  ASSERT_EQ(layout.rpdo2.count, 3u);
  EXPECT_EQ(layout.rpdo2.objects[1].index, 0x6071);
  EXPECT_EQ(layout.rpdo2.objects[2].index, 0x6080);
  EXPECT_EQ(layout.tpdo1.objects[layout.tpdo1.count - 1].index, 0x6061);
  canopen::DriveCommand command;
  command.controlword = 0x0F;
  command.mode = 10;
  command.max_torque = 800;
  command.target_torque = -500;
  command.max_motor_speed = 600;
  can::CanFrame rpdo1;
  can::CanFrame rpdo2;
  ASSERT_TRUE(canopen::pack_command(layout.rpdo1, 1, command, rpdo1));
  ASSERT_TRUE(canopen::pack_command(layout.rpdo2, 1, command, rpdo2));
  EXPECT_EQ(rpdo1.dlc, 7);
  EXPECT_EQ(rpdo2.dlc, 8);

  // The drive mapped the same way (as the start-up writes it), then pressing by those frames.
  SimulatedDrive d = tailstock_drive();
  DriveObjects& o = d.objects();
  for (const canopen::PdoMapping* m : {&layout.rpdo1, &layout.rpdo2}) {
    canopen::SdoWriteList writes;
    ASSERT_TRUE(canopen::pdo_configuration(1, *m, writes));
    for (std::size_t k = 0; k < writes.count; ++k) {
      const canopen::SdoWrite& w = writes.writes[k];
      const std::array<std::uint8_t, 4> bytes{static_cast<std::uint8_t>(w.value & 0xFFU),
                                              static_cast<std::uint8_t>((w.value >> 8) & 0xFFU),
                                              static_cast<std::uint8_t>((w.value >> 16) & 0xFFU),
                                              static_cast<std::uint8_t>(w.value >> 24)};
      ASSERT_EQ(o.write(w.index, w.sub, bytes.data(), w.size), 0U) << std::hex << w.index;
    }
  }
  for (int i = 0; i < 1000; ++i) {
    command.target_position = static_cast<std::int32_t>(std::lround(d.position() * kCounts));
    ASSERT_TRUE(canopen::pack_command(layout.rpdo1, 1, command, rpdo1));
    RpdoValues v1;
    RpdoValues v2;
    ASSERT_TRUE(o.decode_rpdo(0, rpdo1, v1));
    ASSERT_TRUE(o.decode_rpdo(1, rpdo2, v2));
    v1.merge(v2);
    d.on_rpdo(v1);
    d.on_sync();
  }
  EXPECT_EQ(o.mode(), 10);
  EXPECT_EQ(o.max_motor_speed(), 600U);
  EXPECT_DOUBLE_EQ(d.position(), -12.5);
  EXPECT_EQ(o.live.torque, -500);
}

}  // namespace
}  // namespace mcnc::drivesim
