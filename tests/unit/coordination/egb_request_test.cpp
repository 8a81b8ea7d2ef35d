// G81.4 / G80.4 (spec dafeng §2.6.11): refused before anything is sent when the channel has no
// gear box, when one is on already, for a helical gear without the axial axis, and without R
// while the tool spindle turns; sent once, and ended by what the work axis's feedback shows:
// locked (G81.4, or at once with param 5320.5) or stopped (G80.4), the channel then taking the
// angle it stopped at. A gear box that stops by itself is an alarm once; a reset stops it.
#include "channel/coordination/coupling_request.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace mcnc::coordination {
namespace {

// Channel with X (id 1, slot 0), Z (id 2, slot 1, the axial axis) and C (id 3, slot 2, the work
// axis), spindle S1 (id 4, view 3, the tool).
CouplingSetup setup(bool egb = true, bool no_wait = false) {
  CouplingSetup s;
  s.axis_count = 3;
  s.slots = {AxisSlot{'X', false, 1, 1, false, 0, false},
             AxisSlot{'Z', false, 1, 2, false, 0, false},
             AxisSlot{'C', false, 1, 3, false, 0, false}};
  s.machine_axes = {
      MachineAxis{MachineAxisKind::linear, false}, MachineAxis{MachineAxisKind::linear, false},
      MachineAxis{MachineAxisKind::rotary, false}, MachineAxis{MachineAxisKind::spindle, false}};
  if (egb) {
    s.egb = EgbSetup{4, 3, 2, true, no_wait};
  }
  return s;
}

EgbOut gear(bool on, bool phase = true) {
  EgbOut g;
  g.on = on;
  g.teeth = 20;
  g.threads = 1;
  g.phase = phase;
  g.r = 30.0;
  return g;
}

struct Rig {
  explicit Rig(bool egb = true, bool no_wait = false) : request(setup(egb, no_wait)) {}
  CouplingRequest request;
  std::array<AxisFeedbackView, 4> feedback{};
  std::array<SlotUse, 3> uses{SlotUse::commanded, SlotUse::commanded, SlotUse::commanded};
  CouplingStep step(std::uint64_t cycle) {
    return request.step(CouplingInputs{cycle, feedback, uses});
  }
  bool lost(std::uint64_t cycle) { return request.egb_lost(CouplingInputs{cycle, feedback, uses}); }
  // The work axis as its node reports it.
  void work(std::uint32_t coupled_to, bool locked, double cmd = 0.0, double offset = 0.0) {
    feedback[2].coupled_to = coupled_to;
    feedback[2].coupling_locked = locked;
    feedback[2].cmd = cmd;
    feedback[2].superimposed = offset;
  }
};

TEST(EgbRequest, G814IsSentOnceAndEndsWhenTheWorkAxisIsLocked) {
  Rig r;
  r.feedback[3].vel = 1800.0;  // the hob turns: R matches the phase
  r.request.begin_egb(gear(true));
  ASSERT_EQ(r.step(10), CouplingStep::send);
  EXPECT_EQ(r.request.kind(), CouplingKind::egb);
  EXPECT_EQ(r.request.egb().teeth, 20);
  EXPECT_EQ(r.request.egb().r, 30.0);
  EXPECT_EQ(r.step(11), CouplingStep::waiting);  // the node has not heard yet
  r.work(4, false);
  EXPECT_EQ(r.step(12), CouplingStep::waiting);  // catching up
  r.work(4, true);
  EXPECT_EQ(r.step(13), CouplingStep::done);
  EXPECT_EQ(r.request.slot_change().to, SlotChange::To::none);
}

TEST(EgbRequest, WithNoWaitG814EndsOnceSent) {
  Rig r(true, true);  // param 5320.5 = 1
  r.request.begin_egb(gear(true));
  ASSERT_EQ(r.step(1), CouplingStep::send);
  EXPECT_EQ(r.step(2), CouplingStep::done);
}

TEST(EgbRequest, G804EndsOnceTheWorkAxisStandsAndHandsItsAngleToTheChannel) {
  Rig r;
  r.request.begin_egb(gear(true));
  ASSERT_EQ(r.step(1), CouplingStep::send);
  r.work(4, true, 12.5, 12.5);
  ASSERT_EQ(r.step(3), CouplingStep::done);
  EgbOut off = gear(false);
  r.request.begin_egb(off);
  ASSERT_EQ(r.step(5), CouplingStep::send);
  EXPECT_FALSE(r.request.egb().on);
  EXPECT_EQ(r.request.egb().off, EgbOut::Off::stop);
  r.work(4, false, 20.0, 20.0);
  EXPECT_EQ(r.step(7), CouplingStep::waiting);  // slowing down
  r.work(0, false, 21.25, 21.25);
  ASSERT_EQ(r.step(8), CouplingStep::done);
  // The channel commands C where it stopped, and the node is told to take its offset off.
  const SlotChange& change = r.request.slot_change();
  EXPECT_EQ(change.to, SlotChange::To::commanded);
  EXPECT_EQ(change.slot, 2U);
  EXPECT_EQ(change.at, 21.25);
  EXPECT_EQ(r.request.egb().off, EgbOut::Off::absorb);
  EXPECT_FALSE(r.lost(20)) << "a G80.4 is no loss";
}

TEST(EgbRequest, WhatTheChannelCannotRunIsAnAlarmBeforeAnythingIsSent) {
  Rig none(false);
  none.request.begin_egb(gear(true));
  ASSERT_EQ(none.step(1), CouplingStep::alarm);
  EXPECT_EQ(none.request.alarm().number, kAlarmEgb);
  EXPECT_STREQ(none.request.alarm().text.data(),
               "G81.4: this channel has no electronic gear box (egb in the machine file, "
               "parameters 5330/5331)");
  none.request.begin_egb(gear(false));
  EXPECT_EQ(none.step(2), CouplingStep::done);  // G80.4: nothing to stop

  Rig twice;
  twice.request.begin_egb(gear(true));
  ASSERT_EQ(twice.step(1), CouplingStep::send);
  twice.request.begin_egb(gear(true));  // asked for, not heard of yet
  ASSERT_EQ(twice.step(2), CouplingStep::alarm);
  EXPECT_NE(std::string(twice.request.alarm().text.data()).find("on already"), std::string::npos);

  CouplingSetup spur = setup();
  spur.egb.axial = false;
  CouplingRequest no_axial(spur);
  EgbOut h = gear(true);
  h.helix = 15.0;
  h.module = 2.0;
  no_axial.begin_egb(h);
  const std::array<AxisFeedbackView, 4> at_rest{};
  const std::array<SlotUse, 3> uses{SlotUse::commanded, SlotUse::commanded, SlotUse::commanded};
  ASSERT_EQ(no_axial.step(CouplingInputs{1, at_rest, uses}), CouplingStep::alarm);
  EXPECT_NE(std::string(no_axial.alarm().text.data()).find("5332"), std::string::npos);

  Rig turning;
  turning.feedback[3].vel = 1800.0;
  turning.request.begin_egb(gear(true, false));
  ASSERT_EQ(turning.step(1), CouplingStep::alarm);
  EXPECT_NE(std::string(turning.request.alarm().text.data()).find("300.0 rpm"), std::string::npos)
      << turning.request.alarm().text.data();
  turning.feedback[3].vel = 0.0;  // standing: the phase it has is kept
  turning.request.begin_egb(gear(true, false));
  EXPECT_EQ(turning.step(2), CouplingStep::send);
}

TEST(EgbRequest, AGearBoxThatStopsByItselfIsAnAlarmOnce) {
  Rig r;
  r.request.begin_egb(gear(true));
  ASSERT_EQ(r.step(10), CouplingStep::send);
  EXPECT_FALSE(r.lost(11)) << "the node cannot have answered yet";
  r.work(4, true);
  ASSERT_EQ(r.step(12), CouplingStep::done);
  EXPECT_FALSE(r.lost(13));
  r.work(0, false, 7.0, 7.0);  // stopped: off the ratio too long, or the tool lost
  ASSERT_TRUE(r.lost(500));
  EXPECT_EQ(r.request.alarm().number, kAlarmEgb);
  EXPECT_NE(std::string(r.request.alarm().text.data()).find("7.000 deg"), std::string::npos)
      << r.request.alarm().text.data();
  EXPECT_FALSE(r.lost(501));
  // A run's start takes the angle it left.
  const auto change = r.request.egb_hand_over(r.feedback);
  ASSERT_TRUE(change.has_value());
  EXPECT_EQ(change->at, 7.0);
  EXPECT_EQ(r.request.egb().off, EgbOut::Off::absorb);
  r.work(0, false, 7.0, 0.0);
  EXPECT_FALSE(r.request.egb_hand_over(r.feedback).has_value());
}

TEST(EgbRequest, AResetStopsAGearBoxThatRunsOrWasAskedFor) {
  Rig r;
  EXPECT_FALSE(r.request.egb_on_reset(r.feedback));  // none
  r.request.begin_egb(gear(true));
  ASSERT_EQ(r.step(1), CouplingStep::send);
  ASSERT_TRUE(r.request.egb_on_reset(r.feedback));  // asked for, not heard of yet
  EXPECT_FALSE(r.request.egb().on);
  EXPECT_EQ(r.request.egb().off, EgbOut::Off::reset);
  EXPECT_FALSE(r.request.egb_on_reset(r.feedback));  // once
  r.work(4, true);                                   // a gear box that runs (from before a restart)
  EXPECT_TRUE(r.request.egb_on_reset(r.feedback));
}

}  // namespace
}  // namespace mcnc::coordination
