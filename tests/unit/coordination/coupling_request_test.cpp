// G114.1 / G113 and G51.4 / G50.4: checked against the set-up, sent once, and ended by what
// the slave's feedback shows, never before the answer can be visible (two cycles after sending).
#include "channel/coordination/coupling_request.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace mcnc::coordination {
namespace {

// Channel with X (id 1), Z (id 2, may follow, default master 4) and a spindle; group 1's slave
// spindle's feedback at view 3. Machine axes: 1 X, 2 Z, 3 spindle, 4 W (linear), 5 B (rotary).
CouplingSetup setup() {
  CouplingSetup s;
  s.axis_count = 2;
  s.slots = {AxisSlot{'X', false, 1, 1, false, 0, false},
             AxisSlot{'Z', false, 1, 2, true, 4, false}};
  s.spindle_groups = {SpindleGroupSetup{1, 3}};
  s.machine_axes = {
      MachineAxis{MachineAxisKind::linear, false}, MachineAxis{MachineAxisKind::linear, true},
      MachineAxis{MachineAxisKind::spindle, false}, MachineAxis{MachineAxisKind::linear, false},
      MachineAxis{MachineAxisKind::rotary, false}};
  return s;
}

struct Rig {
  CouplingRequest request{setup()};
  std::array<AxisFeedbackView, 4> feedback{};
  std::array<SlotUse, 2> uses{SlotUse::commanded, SlotUse::commanded};
  CouplingStep step(std::uint64_t cycle) {
    return request.step(CouplingInputs{cycle, feedback, uses});
  }
};

TEST(CouplingRequest, SpindleSyncEndsOnlyOnceTheSlaveIsLockedAndTheAnswerVisible) {
  Rig r;
  r.request.begin_spindle(SpindleSyncOut{true, 1, 1, 2, 45.0});
  ASSERT_EQ(r.step(10), CouplingStep::send);
  EXPECT_FALSE(r.request.axis());
  EXPECT_EQ(r.request.spindle_sync().q, 2);
  r.feedback[3].coupled_to = 3;
  r.feedback[3].coupling_locked = true;
  EXPECT_EQ(r.step(11), CouplingStep::waiting);  // sent at 10, taken at 11: not visible yet
  r.feedback[3].coupling_locked = false;
  EXPECT_EQ(r.step(12), CouplingStep::waiting);  // coupled, not yet in phase
  r.feedback[3].coupling_locked = true;
  EXPECT_EQ(r.step(13), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::none);
}

TEST(CouplingRequest, AGroupThisChannelDoesNotLeadIsAnAlarmAndG113EndsWhenFree) {
  Rig r;
  r.request.begin_spindle(SpindleSyncOut{true, 2, 1, 1, 0.0});
  ASSERT_EQ(r.step(1), CouplingStep::alarm);
  EXPECT_EQ(r.request.alarm().number, kAlarmSyncGroup);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G114.1 K2: no synchronisation group 2 has this channel's spindle as master");
  r.request.begin_spindle(SpindleSyncOut{false, 0, 1, 1, 0.0});
  ASSERT_EQ(r.step(5), CouplingStep::send);
  r.feedback[3].coupled_to = 3;
  EXPECT_EQ(r.step(7), CouplingStep::waiting);
  r.feedback[3].coupled_to = 0;
  EXPECT_EQ(r.step(8), CouplingStep::done);
}

TEST(CouplingRequest, AxisSyncFollowsTheDefaultMasterAndG50_4GivesTheAxisBackWhereItStands) {
  Rig r;
  r.request.begin_axis(true, 0, 2);  // G51.4 Q2: its default master, axis 4
  ASSERT_EQ(r.step(20), CouplingStep::send);
  EXPECT_EQ(r.request.axis_sync().slot, 1U);
  EXPECT_EQ(r.request.axis_sync().master, 4U);
  r.feedback[1].coupled_to = 4;
  EXPECT_EQ(r.step(21), CouplingStep::waiting);
  ASSERT_EQ(r.step(22), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::follows);
  EXPECT_EQ(r.request.slot_change().slot, 1U);

  r.uses[1] = SlotUse::follows;
  r.request.begin_axis(false, 0, 2);
  ASSERT_EQ(r.step(30), CouplingStep::send);
  EXPECT_FALSE(r.request.axis_sync().on);
  r.feedback[1].cmd = 12.5;
  EXPECT_EQ(r.step(32), CouplingStep::waiting);  // still follows
  r.feedback[1].coupled_to = 0;
  ASSERT_EQ(r.step(33), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::commanded);
  EXPECT_DOUBLE_EQ(r.request.slot_change().at, 12.5);
}

TEST(CouplingRequest, AnAxisAlreadyFollowingItsMasterEndsWithoutARequest) {
  Rig r;
  r.feedback[1].coupled_to = 4;
  r.request.begin_axis(true, 4, 2);
  ASSERT_EQ(r.step(1), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::follows);
  r.request.begin_axis(true, 1, 2);  // another master
  ASSERT_EQ(r.step(2), CouplingStep::alarm);
  EXPECT_STREQ(r.request.alarm().text.data(), "G51.4 Q2: Z already follows axis 4: G50.4 Q2 first");
  r.feedback[1].coupled_to = 0;
  r.request.begin_axis(false, 0, 2);  // G50.4 of an axis that follows nothing
  EXPECT_EQ(r.step(3), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::none);
}

TEST(CouplingRequest, TheAxesMustAllowTheCoupling) {
  Rig r;
  const auto alarm_of = [&](bool on, std::uint32_t master, std::uint32_t slave) {
    r.request.begin_axis(on, master, slave);
    EXPECT_EQ(r.step(1), CouplingStep::alarm);
    EXPECT_EQ(r.request.alarm().number, kAlarmAxisSync);
    return std::string(r.request.alarm().text.data());
  };
  EXPECT_NE(alarm_of(true, 4, 1).find("X cannot follow"), std::string::npos);
  EXPECT_NE(alarm_of(true, 4, 7).find("axis 7 is not this channel's"), std::string::npos);
  EXPECT_NE(alarm_of(true, 9, 2).find("no such axis"), std::string::npos);
  EXPECT_NE(alarm_of(true, 5, 2).find("not of the same kind"), std::string::npos);
  EXPECT_NE(alarm_of(true, 2, 2).find("it cannot lead"), std::string::npos);
  r.uses[1] = SlotUse::away;  // with another channel
  EXPECT_NE(alarm_of(false, 0, 2).find("G50.4 Q2: axis 2 is not this channel's"),
            std::string::npos);
}

}  // namespace
}  // namespace mcnc::coordination
