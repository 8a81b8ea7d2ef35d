// G160 in the axis node's core, in closed loop with a simulated drive whose load meets a
// contact at 12.0 coming from above: the owner's torque limit goes out as 0x6072, the torque
// skip latches once the torque (0x6077) stands at the limit and the following error is beyond
// the deviation, where the axis stands then, and the following-error check (alarm 2009) allows
// the deviation on top of its limit while the limit stands.
#include "axisnode/control/torque_units.hpp"
#include "tests/unit/axisnode/node_drive_loop.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace mcnc;
using axisnode::AxisAlarm;
using axisnode::AxisNodeController;
using axisnode::AxisNodeInput;
using axisnode::ProbeRequest;
using axisnode::ProbeState;

namespace {

constexpr double kCycle = 0.001;

// The node and a drive whose load meets the contact at 12.0 from above.
// `torque_scale`: param 5522 (decision 164).
struct PressLoop : test::NodeDriveLoop {
  explicit PressLoop(bool torque_skip, double torque_scale = 100.0)
      : NodeDriveLoop(
            [&] {
              axisnode::AxisNodeSetup s{10000.0, kCycle, 5};
              s.following_error_limit = 2.0;
              s.torque_skip = torque_skip;
              s.torque_scale = torque_scale;
              return s;
            }(),
            [] {
              drivesim::DriveParams p{1, 10000.0, 0.004, 500.0, 5000.0, 12.5};
              p.contact_side = -1;
              p.contact_at = 12.0;
              return p;
            }(),
            kCycle) {}
};

// G160's setpoint: `pos` at `vel`, the torque skip asked, `limit` % and `deviation` mm.
AxisNodeInput pressing(double pos, double limit, double deviation,
                       ProbeRequest probe = ProbeRequest::torque, double vel = -10.0) {
  AxisNodeInput in;
  in.have_setpoint = true;
  in.setpoint_valid = true;
  in.setpoint_pos = pos;
  in.setpoint_vel = vel;
  in.probe = probe;
  in.torque_limit = limit;
  in.skip_deviation = deviation;
  return in;
}

}  // namespace

TEST(AxisNodeTorqueSkip, LatchesWhereTheTorqueIsAtTheLimitAndTheErrorBeyondTheDeviation) {
  PressLoop loop(true);
  ASSERT_TRUE(loop.node.output().enabled);
  EXPECT_EQ(loop.node.output().max_torque, canopen::kNoTorqueLimit);
  // The limit goes out at once; the skip is armed once the drive ran a SYNC under it.
  const auto& first = loop.step(pressing(12.5, 50.0, 1.0));
  EXPECT_EQ(first.max_torque, 500);
  EXPECT_EQ(first.probe, ProbeState::off);
  EXPECT_EQ(loop.step(pressing(12.5, 50.0, 1.0)).probe, ProbeState::armed);
  // Down at 10 mm/s: the contact at 12.0 holds the load, the torque rises to 50 %, the
  // following error grows; the skip latches once it passes 1 mm, not before.
  double pos = 12.5;
  double error_at_latch = 0.0;
  while (pos > 10.0 && loop.node.output().probe != ProbeState::latched) {
    pos -= 0.01;
    const auto& out = loop.step(pressing(pos, 50.0, 1.0));
    error_at_latch = out.cmd - out.act;
  }
  ASSERT_EQ(loop.node.output().probe, ProbeState::latched);
  EXPECT_NEAR(loop.node.output().probe_pos, 12.0, 1e-9);
  EXPECT_LT(error_at_latch, -1.0);
  EXPECT_GT(error_at_latch, -1.0 - 0.05);
  EXPECT_EQ(loop.torque, -500);
  // The limit stays after the skip; the latch too while the skip is asked.
  for (int i = 0; i < 50; ++i) {
    loop.step(pressing(pos, 50.0, 1.0));
  }
  EXPECT_EQ(loop.node.output().probe, ProbeState::latched);
  EXPECT_EQ(loop.node.output().max_torque, 500);
  EXPECT_DOUBLE_EQ(loop.drive.position(), 12.0);
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
}

// Param 5522 (decision 164): a drive whose 1000 per mille are 250 % of the rated torque takes
// G160's 50 % as 200 per mille, and the skip latches where its 0x6077 reaches that.
TEST(AxisNodeTorqueSkip, TheTorqueScaleOfParam5522ConvertsTheLimit) {
  PressLoop loop(true, 250.0);
  EXPECT_EQ(loop.step(pressing(12.5, 50.0, 0.5)).max_torque, 200);
  double pos = 12.5;
  while (pos > 10.0 && loop.node.output().probe != ProbeState::latched) {
    pos -= 0.01;
    loop.step(pressing(pos, 50.0, 0.5));
  }
  ASSERT_EQ(loop.node.output().probe, ProbeState::latched);
  EXPECT_EQ(loop.torque, -200);  // the drive held at 200 per mille of its rated torque
  EXPECT_EQ(axisnode::rated_percent(-200.0, 250.0), -50.0);  // what the feedback reports
}

TEST(AxisNodeTorqueSkip, DoesNotLatchWhileTheAxisMovesFreely) {
  PressLoop loop(true);
  for (double pos = 12.5; pos < 20.0; pos += 0.01) {
    const auto& out = loop.step(pressing(pos, 50.0, 0.0, ProbeRequest::torque, 10.0));
    EXPECT_NE(out.probe, ProbeState::latched) << pos;
  }
}

TEST(AxisNodeTorqueSkip, AMoveAwayFromWhatHoldsTheAxisDoesNotSkipWhereItStarts) {
  PressLoop loop(true);
  // Pressed 1.5 mm beyond the contact with the limit, then asked again on the way back up.
  for (double pos = 12.5; pos > 10.5; pos -= 0.01) {
    loop.step(pressing(std::max(pos, 10.5), 50.0, 1.0, ProbeRequest::off));
  }
  for (int i = 0; i < 20; ++i) {
    loop.step(pressing(10.5, 50.0, 1.0, ProbeRequest::off));
  }
  ASSERT_EQ(loop.torque, -500);
  for (double pos = 10.5; pos < 14.0; pos += 0.01) {
    const auto& out = loop.step(pressing(pos, 50.0, 1.0, ProbeRequest::torque, 10.0));
    EXPECT_NE(out.probe, ProbeState::latched) << pos;
  }
  EXPECT_NEAR(loop.drive.position(), 14.0, 0.1);
}

TEST(AxisNodeTorqueSkip, TheFollowingErrorCheckAllowsTheDeviationWhileTheLimitStands) {
  PressLoop loop(true);
  // Pressed with the target 2.8 mm below the contact: beyond the 2 mm limit, within 2 + 1.
  for (double pos = 12.5; pos > 9.2; pos -= 0.01) {
    loop.step(pressing(std::max(pos, 9.2), 50.0, 1.0, ProbeRequest::off));
  }
  for (int i = 0; i < 20; ++i) {
    loop.step(pressing(9.2, 50.0, 1.0, ProbeRequest::off));
  }
  EXPECT_EQ(loop.node.output().alarm, AxisAlarm::none);
  EXPECT_NEAR(loop.node.output().cmd - loop.node.output().act, -2.8, 1e-9);
  // The limit cancelled with the axis still pressed: 2009 at once.
  const auto& out = loop.step(pressing(9.2, 0.0, 0.0, ProbeRequest::off));
  EXPECT_EQ(out.new_alarm, AxisAlarm::following_error);
  EXPECT_EQ(out.max_torque, canopen::kNoTorqueLimit);
}

TEST(AxisNodeTorqueSkip, AnAxisWithoutTheTorqueMappingNeitherLimitsNorSkips) {
  PressLoop loop(false);
  double pos = 12.5;
  for (int i = 0; i < 150; ++i) {
    pos -= 0.01;
    const auto& out = loop.step(pressing(pos, 50.0, 1.0));
    EXPECT_EQ(out.max_torque, canopen::kNoTorqueLimit);
    EXPECT_EQ(out.probe, ProbeState::off);
  }
  EXPECT_EQ(loop.node.output().touch_probe, 0);  // nor does it arm a touch probe
}

// G10 L14 P10-P12 (setup torque_mode): the owner's torque mode goes out as CST (mode 10) with
// the torque and the speed limit; the drive presses against the contact with the set torque
// while the node's command follows it (no following error, no alarm); back in CSP the node
// holds where the motor stands.
TEST(AxisNodeTorqueMode, PressesWithTheSetTorqueThenHoldsWhereItStandsInCsp) {
  test::NodeDriveLoop loop(
      [] {
        axisnode::AxisNodeSetup s{10000.0, kCycle, 5};
        s.following_error_limit = 0.1;
        s.torque_skip = true;
        s.torque_mode = true;
        return s;
      }(),
      [] {
        drivesim::DriveParams p{1, 10000.0, 0.004, 500.0, 5000.0, 12.5};
        p.contact_side = -1;
        p.contact_at = 12.0;
        return p;
      }(),
      kCycle);
  ASSERT_TRUE(loop.node.output().enabled);
  AxisNodeInput in;
  in.have_setpoint = true;
  in.setpoint_valid = true;
  in.setpoint_pos = 12.5;
  in.torque_mode = true;
  in.torque = -50.0;
  in.torque_speed = 600.0;  // 100 mm/s at 10 mm a revolution
  for (int i = 0; i < 500; ++i) {
    loop.step(in);
  }
  const axisnode::AxisNodeOutput& out = loop.node.output();
  EXPECT_EQ(out.mode, axisnode::kModeCst);
  EXPECT_EQ(out.mode_display, axisnode::kModeCst);
  EXPECT_EQ(out.target_torque, -500);
  EXPECT_EQ(out.max_motor_speed, 600U);
  EXPECT_DOUBLE_EQ(loop.drive.position(), 12.0);
  EXPECT_EQ(loop.torque, -500);      // the drive holds the set torque against the contact
  EXPECT_NEAR(out.cmd, 12.0, 1e-9);  // the command follows the motor
  EXPECT_EQ(out.alarm, AxisAlarm::none);
  // Back to position mode: the owner commands where the axis stands.
  in.torque_mode = false;
  in.setpoint_pos = 12.0;
  for (int i = 0; i < 100; ++i) {
    loop.step(in);
  }
  EXPECT_EQ(out.mode_display, axisnode::kModeCsp);
  EXPECT_EQ(out.target_torque, 0);
  EXPECT_DOUBLE_EQ(loop.drive.position(), 12.0);
  EXPECT_EQ(out.alarm, AxisAlarm::none);
  EXPECT_TRUE(out.enabled);
}
