// G51.2 / G50.2 (spec dafeng §2.6.6): refused before anything is sent when the channel has no
// polygon axis, the axis turns or already follows, or the master's speed would take it beyond
// its limit (L2911); sent once, and ended by what the polygon axis's feedback shows: locked
// (G51.2), free (G50.2, P1) or at once (G50.2 P0). A reset releases it.
#include "channel/coordination/coupling_request.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace mcnc::coordination {
namespace {

// Channel with X and Z, spindles S1 (id 3, view 2, the master) and T1 (id 4, view 3, the
// polygon axis, at most 3000 rpm).
CouplingSetup setup(bool polygon = true) {
  CouplingSetup s;
  s.axis_count = 2;
  s.slots = {AxisSlot{'X', false, 1, 1, false, 0, false},
             AxisSlot{'Z', false, 1, 2, false, 0, false}};
  s.machine_axes = {
      MachineAxis{MachineAxisKind::linear, false}, MachineAxis{MachineAxisKind::linear, false},
      MachineAxis{MachineAxisKind::spindle, false}, MachineAxis{MachineAxisKind::spindle, false}};
  if (polygon) {
    s.polygon = PolygonSetup{3, 2, 3, 3000.0 * 6.0};
  }
  return s;
}

struct Rig {
  explicit Rig(bool polygon = true) : request(setup(polygon)) {}
  CouplingRequest request;
  std::array<AxisFeedbackView, 4> feedback{};
  std::array<SlotUse, 2> uses{SlotUse::commanded, SlotUse::commanded};
  CouplingStep step(std::uint64_t cycle) {
    return request.step(CouplingInputs{cycle, feedback, uses});
  }
};

TEST(PolygonRequest, G512IsSentOnceAndEndsWhenThePolygonAxisIsInPhase) {
  Rig r;
  r.feedback[2].vel = 3000.0;  // S500
  r.request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(r.step(10), CouplingStep::send);
  EXPECT_EQ(r.request.kind(), CouplingKind::polygon);
  EXPECT_EQ(r.request.polygon().q, 2);
  r.feedback[3].coupled_to = 3;
  EXPECT_EQ(r.step(11), CouplingStep::waiting);  // catching up
  r.feedback[3].coupling_locked = true;
  EXPECT_EQ(r.step(12), CouplingStep::done);
}

TEST(PolygonRequest, WithoutAPolygonAxisG512IsAnAlarmAndG502DoesNothing) {
  Rig r(false);
  r.request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(r.step(1), CouplingStep::alarm);
  EXPECT_EQ(r.request.alarm().number, kAlarmPolygon);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G51.2: this channel has no polygon axis (polygon in the machine file, parameters "
               "5310/5311)");
  r.request.begin_polygon(PolygonOut{false, 1, 1, 0.0, true});
  EXPECT_EQ(r.step(2), CouplingStep::done);
}

TEST(PolygonRequest, APolygonAxisThatTurnsOrFollowsAlreadyIsRefused) {
  Rig r;
  r.feedback[3].vel = -60.0;  // 10 rpm backwards
  r.request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(r.step(1), CouplingStep::alarm);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G51.2: the polygon axis turns at -10.0 rpm: stop its spindle (M05) before G51.2");
  r.feedback[3].vel = 0.0;
  r.feedback[3].coupled_to = 3;
  r.request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(r.step(2), CouplingStep::alarm);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G51.2: the polygon axis follows its master already: G50.2 first");
}

TEST(PolygonRequest, ARatioThatWouldExceedTheLimitIsRefusedWithTheSpeeds) {
  Rig r;
  r.feedback[2].vel = -3000.0;  // S500 backwards (M04): the limit holds for both directions
  r.request.begin_polygon(PolygonOut{true, 1, 7, 0.0, true});
  ASSERT_EQ(r.step(1), CouplingStep::alarm);
  EXPECT_EQ(r.request.alarm().number, kAlarmPolygon);
  EXPECT_STREQ(r.request.alarm().text.data(),
               "G51.2 P1 Q7: the polygon axis would turn at 3500 rpm, above its 3000 rpm "
               "(parameter 5312: polygon max_rpm)");
  r.request.begin_polygon(PolygonOut{true, 1, -6, 0.0, true});  // exactly 3000: allowed
  EXPECT_EQ(r.step(2), CouplingStep::send);
}

TEST(PolygonRequest, G502WaitsForThePolygonAxisToStandFreeUnlessP0) {
  Rig r;
  r.feedback[3].coupled_to = 3;
  r.request.begin_polygon(PolygonOut{false, 1, 1, 0.0, true});
  ASSERT_EQ(r.step(20), CouplingStep::send);
  EXPECT_FALSE(r.request.polygon().on);
  EXPECT_EQ(r.step(21), CouplingStep::waiting);
  EXPECT_EQ(r.step(22), CouplingStep::waiting);  // still slowing down
  r.feedback[3].coupled_to = 0;
  EXPECT_EQ(r.step(23), CouplingStep::done);

  r.feedback[3].coupled_to = 3;
  r.request.begin_polygon(PolygonOut{false, 1, 1, 0.0, false});  // G50.2 P0
  ASSERT_EQ(r.step(30), CouplingStep::send);
  EXPECT_EQ(r.step(31), CouplingStep::done);
  // Nothing follows: G50.2 sends nothing.
  r.feedback[3].coupled_to = 0;
  r.request.begin_polygon(PolygonOut{false, 1, 1, 0.0, true});
  EXPECT_EQ(r.step(40), CouplingStep::done);
}

TEST(PolygonRequest, AResetReleasesAPolygonAxisThatFollowsOrWasAskedTo) {
  Rig r;
  EXPECT_FALSE(r.request.polygon_on_reset(r.feedback).has_value());
  r.request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(r.step(1), CouplingStep::send);
  // Reset before the node's answer shows: released all the same, once.
  const auto off = r.request.polygon_on_reset(r.feedback);
  ASSERT_TRUE(off.has_value());
  EXPECT_FALSE(off->on);
  EXPECT_FALSE(r.request.polygon_on_reset(r.feedback).has_value());
  r.feedback[3].coupled_to = 3;  // following, whoever asked
  EXPECT_TRUE(r.request.polygon_on_reset(r.feedback).has_value());
}

// A servo polygon axis (param 5311, decision 157): C in slot 1 of a channel with X, C and the
// master S1 (id 3, view 2). The slot is the master's from the send, another channel's C is
// refused, G50.2 P0 waits for it to stand (decision 158) and hands over where it stands, and
// with 5300.5 = 1 G51.2 ends at once while the lock stays due until the feedback shows it.
TEST(PolygonRequest, AServoPolygonAxisIsTheMastersUntilItStandsAgain) {
  CouplingSetup s = setup();
  s.polygon = PolygonSetup{3, 2, 1, 3000.0 * 6.0, true};
  CouplingRequest request(s);
  std::array<AxisFeedbackView, 3> feedback{};
  std::array<SlotUse, 2> uses{SlotUse::commanded, SlotUse::away};
  const auto step = [&](std::uint64_t cycle) {
    return request.step(CouplingInputs{cycle, feedback, uses});
  };
  request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(step(1), CouplingStep::alarm);
  EXPECT_STREQ(request.alarm().text.data(),
               "G51.2: the polygon axis is not this channel's now (G141 first)");
  uses[1] = SlotUse::commanded;
  request.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(step(10), CouplingStep::send);
  EXPECT_EQ(request.slot_change().to, SlotChange::To::follows);
  EXPECT_EQ(request.slot_change().slot, 1U);
  uses[1] = SlotUse::follows;
  feedback[1].coupled_to = 3;
  feedback[1].coupling_locked = true;
  EXPECT_EQ(step(12), CouplingStep::done);
  // G50.2 P0: waits until C stands free, then the channel commands it at 1234.5.
  request.begin_polygon(PolygonOut{false, 1, 1, 0.0, false});
  ASSERT_EQ(step(20), CouplingStep::send);
  feedback[1].cmd = 1234.5;
  EXPECT_EQ(step(22), CouplingStep::waiting);
  feedback[1].coupled_to = 0;
  feedback[1].coupling_locked = false;
  ASSERT_EQ(step(30), CouplingStep::done);
  EXPECT_EQ(request.slot_change().to, SlotChange::To::commanded);
  EXPECT_EQ(request.slot_change().at, 1234.5);

  s.polygon.no_wait = true;
  CouplingRequest no_wait(s);
  uses[1] = SlotUse::commanded;
  no_wait.begin_polygon(PolygonOut{true, 1, 2, 0.0, true});
  ASSERT_EQ(no_wait.step(CouplingInputs{40, feedback, uses}), CouplingStep::send);
  EXPECT_EQ(no_wait.step(CouplingInputs{41, feedback, uses}), CouplingStep::done);
  EXPECT_TRUE(no_wait.lock_pending(CouplingInputs{41, feedback, uses}));
  feedback[1].coupled_to = 3;
  EXPECT_TRUE(no_wait.lock_pending(CouplingInputs{42, feedback, uses}));  // catching up
  feedback[1].coupling_locked = true;
  EXPECT_FALSE(no_wait.lock_pending(CouplingInputs{50, feedback, uses}));
  EXPECT_FALSE(no_wait.lock_pending(CouplingInputs{51, feedback, uses}));  // once locked: done
}

}  // namespace
}  // namespace mcnc::coordination
