// The simulated drive's max torque (CiA 402 0x6072) and its contact (G160): the load cannot
// pass the contact, so there the motor stands while the position loop's torque rises to the
// limit, and the following error grows as the target moves on. The limit comes by SDO or in an
// RPDO that maps 0x6072 (canopen::add_torque_limit); without one it is the drive's peak torque.
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "tests/unit/drivesim/pressing_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace mcnc::drivesim {
namespace {

constexpr double kCounts = test::kPressCounts;
// test::pressing_drive(): 0x6072's default is 3334 per mille, the peak rounded up.
using test::pressing_drive;

// One cycle towards `target` (units) with the max torque `max_torque` (per mille; 0: not sent).
void cycle(SimulatedDrive& d, double target, std::uint16_t max_torque) {
  RpdoValues v;
  v.controlword = 0x0F;
  v.has_controlword = true;
  v.target_position = static_cast<std::int32_t>(std::lround(target * kCounts));
  v.has_target_position = true;
  v.max_torque = max_torque;
  v.has_max_torque = max_torque != 0;
  d.on_rpdo(v);
  d.on_sync();
}

// Down from where the target is at 10 mm/s to `until`, then 200 cycles there.
void press_down(SimulatedDrive& d, double until, std::uint16_t max_torque) {
  for (double target = d.target(); target > until;) {
    target = std::max(until, target - 0.01);
    cycle(d, target, max_torque);
  }
  for (int i = 0; i < 200; ++i) {
    cycle(d, until, max_torque);
  }
}

TEST(DriveTorqueLimit, WithoutALimitTheContactHoldsTheLoadAtThePeakTorque) {
  SimulatedDrive d = pressing_drive();
  EXPECT_EQ(d.objects().max_torque(), 3334);  // 10 N m of 3 N m rated, rounded up
  press_down(d, -13.0, 0);
  EXPECT_DOUBLE_EQ(d.position(), -12.5);
  EXPECT_EQ(d.velocity(), 0.0);
  EXPECT_DOUBLE_EQ(std::abs(d.torque()), 10.0);  // the peak itself: 0x6072 does not cut it
  EXPECT_EQ(d.objects().live.torque, -3333);
  EXPECT_EQ(d.objects().live.following_error, -5000);  // the target 0.5 below the contact
}

TEST(DriveTorqueLimit, TheRpdosMaxTorqueLimitsThePressAndTheFollowingErrorGrows) {
  SimulatedDrive d = pressing_drive();
  press_down(d, -14.0, 500);  // 50 % of the rated torque
  EXPECT_EQ(d.objects().max_torque(), 500);
  EXPECT_DOUBLE_EQ(d.position(), -12.5);
  EXPECT_NEAR(d.torque(), -1.5, 1e-9);
  EXPECT_EQ(d.objects().live.torque, -500);
  EXPECT_EQ(d.objects().live.following_error, -15000);
  // Away from the contact the limit still holds the torque, and the load follows again.
  press_down(d, -12.0, 500);
  EXPECT_NEAR(d.position(), -12.0, 1e-3);
  EXPECT_LE(std::abs(d.torque()), 1.5 + 1e-9);
}

TEST(DriveTorqueLimit, BeforeTheContactTheLoadFollowsUnderTheLimit) {
  SimulatedDrive d = pressing_drive();
  press_down(d, -10.0, 500);
  EXPECT_NEAR(d.position(), -10.0, 1e-3);
  EXPECT_LT(std::abs(d.objects().live.torque), 500);
}

TEST(DriveTorqueLimit, TheMaxTorqueIsAnSdoObjectToo) {
  SimulatedDrive d = pressing_drive();
  const std::uint8_t value[2] = {0xF4, 0x01};  // 500
  EXPECT_EQ(d.objects().write(0x6072, 0, value, 2), 0u);
  canopen::SdoValue read;
  ASSERT_EQ(d.objects().read(0x6072, 0, read), 0u);
  EXPECT_EQ(read.size, 2u);
  EXPECT_EQ(read.bytes[0], 0xF4);
  EXPECT_EQ(read.bytes[1], 0x01);
  press_down(d, -14.0, 0);
  EXPECT_EQ(d.objects().live.torque, -500);
}

TEST(DriveTorqueLimit, TheLayoutCarriesTheLimitInRpdo2AndTheTorqueInTpdo2) {
  canopen::PdoLayout layout = canopen::axis_pdos(false, false, false);
  canopen::add_torque_limit(layout);
  ASSERT_EQ(layout.rpdo2.count, 1u);
  EXPECT_EQ(layout.rpdo2.objects[0].index, 0x6072);
  ASSERT_EQ(layout.tpdo2.count, 1u);
  EXPECT_EQ(layout.tpdo2.objects[0].index, 0x6077);
  canopen::DriveCommand command;
  command.max_torque = 500;
  can::CanFrame frame;
  ASSERT_TRUE(canopen::pack_command(layout.rpdo2, 3, command, frame));
  EXPECT_EQ(frame.id, 0x303u);
  EXPECT_EQ(frame.dlc, 2);
  EXPECT_EQ(frame.data[0], 0xF4);
  EXPECT_EQ(frame.data[1], 0x01);
  // Without a limit the master sends 1000 % of the rated torque: the drive's peak applies.
  ASSERT_TRUE(canopen::pack_command(layout.rpdo2, 3, canopen::DriveCommand{}, frame));
  EXPECT_EQ(frame.data[0] | (frame.data[1] << 8), canopen::kNoTorqueLimit);
  canopen::DriveFeedback drive;
  drive.torque_actual = -500;
  ASSERT_TRUE(canopen::pack_feedback(layout.tpdo2, 3, drive, frame));
  canopen::DriveFeedback read;
  ASSERT_TRUE(canopen::unpack_feedback(layout.tpdo2, frame, read));
  EXPECT_EQ(read.torque_actual, -500);
}

}  // namespace
}  // namespace mcnc::drivesim
