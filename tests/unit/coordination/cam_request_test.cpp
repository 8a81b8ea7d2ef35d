// G51.8 / G50.8 (spec dafeng §2.6.7): refused before anything is sent when the channel has no
// cam; sent once with its table, and ended by what the slave's feedback shows: on its lift
// (G51.8) or free of it (G50.8). A reset takes the lift off.
#include "channel/coordination/coupling_request.hpp"

#include <gtest/gtest.h>

#include <array>

namespace mcnc::coordination {
namespace {

// Channel with X (id 1, slot 0, the cam's slave) and Z, spindle S1 (id 3, view 2, the master).
CouplingSetup setup(bool cam = true) {
  CouplingSetup s;
  s.axis_count = 2;
  s.slots = {AxisSlot{'X', false, 1, 1, false, 0, false},
             AxisSlot{'Z', false, 1, 2, false, 0, false}};
  s.machine_axes = {MachineAxis{MachineAxisKind::linear, false},
                    MachineAxis{MachineAxisKind::linear, false},
                    MachineAxis{MachineAxisKind::spindle, false}};
  if (cam) {
    s.cam = CamSetup{3, 0};
  }
  return s;
}

CamOut table(bool on) {
  CamOut c;
  c.on = on;
  c.points = 3;
  c.lift = {0.0, 0.5, 0.25};
  c.r = 90.0;
  return c;
}

struct Rig {
  explicit Rig(bool cam = true) : request(setup(cam)) {}
  CouplingRequest request;
  std::array<AxisFeedbackView, 3> feedback{};
  std::array<SlotUse, 2> uses{SlotUse::commanded, SlotUse::commanded};
  CouplingStep step(std::uint64_t cycle) {
    return request.step(CouplingInputs{cycle, feedback, uses});
  }
};

TEST(CamRequest, G518IsSentOnceWithItsTableAndEndsWhenTheSlaveIsOnItsLift) {
  Rig r;
  r.request.begin_cam(table(true));
  ASSERT_EQ(r.step(10), CouplingStep::send);
  EXPECT_EQ(r.request.kind(), CouplingKind::cam);
  EXPECT_EQ(r.request.cam().points, 3U);
  EXPECT_EQ(r.request.cam().lift[1], 0.5);
  EXPECT_EQ(r.request.cam().r, 90.0);
  EXPECT_EQ(r.step(11), CouplingStep::waiting);  // the node has not heard yet
  r.feedback[0].coupled_to = 3;
  EXPECT_EQ(r.step(12), CouplingStep::waiting);  // on its way to the lift
  r.feedback[0].coupling_locked = true;
  EXPECT_EQ(r.step(13), CouplingStep::done);
}

TEST(CamRequest, G508EndsOnceTheLiftIsOffAndDoesNothingWithoutACam) {
  Rig r;
  r.request.begin_cam(table(false));
  EXPECT_EQ(r.step(1), CouplingStep::done);  // no cam runs: nothing to send
  r.request.begin_cam(table(true));
  ASSERT_EQ(r.step(2), CouplingStep::send);
  r.feedback[0].coupled_to = 3;
  r.feedback[0].coupling_locked = true;
  EXPECT_EQ(r.step(3), CouplingStep::waiting);  // the feedback of before the node heard it
  ASSERT_EQ(r.step(4), CouplingStep::done);
  r.request.begin_cam(table(false));
  ASSERT_EQ(r.step(5), CouplingStep::send);
  EXPECT_FALSE(r.request.cam().on);
  r.feedback[0].coupling_locked = false;
  EXPECT_EQ(r.step(7), CouplingStep::waiting);  // the lift is coming off
  r.feedback[0].coupled_to = 0;
  EXPECT_EQ(r.step(8), CouplingStep::done);
}

TEST(CamRequest, WithoutACamG518IsAnAlarmBeforeAnythingIsSent) {
  Rig r(false);
  r.request.begin_cam(table(true));
  ASSERT_EQ(r.step(1), CouplingStep::alarm);
  EXPECT_EQ(r.request.alarm().number, kAlarmCam);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G51.8: this channel has no electronic cam (cam in the machine file, parameters "
               "5350/5351)");
  r.request.begin_cam(table(false));
  EXPECT_EQ(r.step(2), CouplingStep::done);
}

TEST(CamRequest, AResetTakesTheLiftOffACamThatRunsOrWasAskedFor) {
  Rig r;
  EXPECT_FALSE(r.request.cam_on_reset(r.feedback));  // none
  r.request.begin_cam(table(true));
  ASSERT_EQ(r.step(1), CouplingStep::send);
  ASSERT_TRUE(r.request.cam_on_reset(r.feedback));  // asked for, not heard of yet
  EXPECT_FALSE(r.request.cam().on);
  EXPECT_FALSE(r.request.cam_on_reset(r.feedback));  // once
  r.feedback[0].coupled_to = 3;                      // a cam that runs (from before a restart)
  EXPECT_TRUE(r.request.cam_on_reset(r.feedback));
}

}  // namespace
}  // namespace mcnc::coordination
