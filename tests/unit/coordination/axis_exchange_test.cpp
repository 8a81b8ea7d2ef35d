// G140 / G141 / G142 as one channel runs them against its axis nodes' feedback, and the table of
// what the channel does with each slot.
#include "channel/coordination/axis_exchange.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace mcnc::coordination {
namespace {

// Channel 1 with X (its own, home 1) and Y (an exchange slot for channel 2's axis, home 2).
ExchangeSetup setup() {
  ExchangeSetup s;
  s.channel_id = 1;
  s.axis_count = 2;
  s.slots = {AxisSlot{'X', false, 1, 1, false, 0, false},
             AxisSlot{'Y', true, 2, 2, false, 0, false}};
  return s;
}

struct Rig {
  AxisExchange exchange{setup()};
  std::array<AxisFeedbackView, 2> feedback{};
  std::array<double, 2> commanded{};
  Rig() {
    feedback[0].present = feedback[1].present = true;
    feedback[0].owner = 1;
    feedback[1].owner = 2;
  }
  ExchangeStep step(std::uint64_t cycle) {
    exchange.begin_cycle();
    return exchange.step(cycle, feedback, commanded);
  }
};

TEST(AxisExchange, SlotsStartAsConfigured) {
  Rig r;
  EXPECT_TRUE(r.exchange.exchanges());
  EXPECT_EQ(r.exchange.use(0), SlotUse::commanded);
  EXPECT_EQ(r.exchange.use(1), SlotUse::virtual_axis);
  ExchangeSetup c = setup();
  c.spindle_c_slot = 0;
  EXPECT_EQ(AxisExchange(c).use(0), SlotUse::speed_control);
}

TEST(AxisExchange, AcquireWaitsForTheGrantThenTakesTheAxisOverWhereItStands) {
  Rig r;
  r.exchange.begin(AxisRequestKind::acquire, 1, true);
  ASSERT_EQ(r.step(100), ExchangeStep::sent);
  ASSERT_EQ(r.exchange.requests().size(), 1U);
  EXPECT_EQ(r.exchange.requests()[0].kind, AxisRequestKind::acquire);
  EXPECT_TRUE(r.exchange.requests()[0].force);
  EXPECT_EQ(r.exchange.waiting_g(), 141);
  EXPECT_EQ(r.exchange.waiting_slot(), 1U);
  r.feedback[1].owner = 1;
  r.feedback[1].cmd = 42.0;
  EXPECT_EQ(r.step(101), ExchangeStep::waiting);  // the answer cannot be visible yet
  EXPECT_TRUE(r.exchange.requests().empty());
  ASSERT_EQ(r.step(102), ExchangeStep::done);
  EXPECT_TRUE(r.exchange.took_over());
  EXPECT_EQ(r.exchange.use(1), SlotUse::commanded);
  EXPECT_DOUBLE_EQ(r.commanded[1], 42.0);
  EXPECT_EQ(r.exchange.waiting_g(), 0);
}

TEST(AxisExchange, ReleasingAnAxisNotOwnedIsAnAlarmAndARefusalToo) {
  Rig r;
  r.exchange.begin(AxisRequestKind::release, 1, false);
  ASSERT_EQ(r.step(1), ExchangeStep::alarm);
  EXPECT_EQ(r.exchange.alarm().number, kAlarmNotOwner);
  EXPECT_EQ(r.exchange.alarm().axis, 2);
  EXPECT_STREQ(r.exchange.alarm().text.data(),
               "G140 Y: the axis is not this channel's (channel 2 has it)");

  r.exchange.begin(AxisRequestKind::release, 0, false);
  ASSERT_EQ(r.step(10), ExchangeStep::sent);
  r.feedback[0].request_refused = true;
  ASSERT_EQ(r.step(12), ExchangeStep::alarm);
  EXPECT_EQ(r.exchange.alarm().number, kAlarmRequestRefused);
  EXPECT_EQ(r.exchange.alarm().axis, 1);
}

TEST(AxisExchange, ReleaseEndsOnceAnotherChannelHasTheAxis) {
  Rig r;
  r.exchange.begin(AxisRequestKind::release, 0, false);
  ASSERT_EQ(r.step(10), ExchangeStep::sent);
  EXPECT_EQ(r.step(12), ExchangeStep::waiting);
  r.feedback[0].owner = 0;
  ASSERT_EQ(r.step(13), ExchangeStep::done);
  EXPECT_FALSE(r.exchange.took_over());
  EXPECT_EQ(r.exchange.use(0), SlotUse::away);
  // A release is never withdrawn: the axis is gone.
  r.exchange.begin_cycle();
  r.exchange.withdraw();
  EXPECT_TRUE(r.exchange.requests().empty());
}

TEST(AxisExchange, RestoreWaitsUntilNothingIsAwayOnThisChannelsAccount) {
  Rig r;
  r.feedback[0].owner = 2;  // X is with channel 2
  r.exchange.begin(AxisRequestKind::restore, 0, false);
  ASSERT_EQ(r.step(1), ExchangeStep::sent);
  EXPECT_EQ(r.exchange.requests()[0].slot, AxisRequestOut::kAllSlots);
  EXPECT_EQ(r.step(3), ExchangeStep::waiting);
  r.feedback[0].owner = 1;
  r.feedback[0].cmd = 7.0;
  ASSERT_EQ(r.step(4), ExchangeStep::done);
  EXPECT_TRUE(r.exchange.took_over());
}

TEST(AxisExchange, AWaitingAcquireIsWithdrawnAndALateGrantGivenBackOnce) {
  Rig r;
  r.exchange.begin(AxisRequestKind::acquire, 1, false);
  ASSERT_EQ(r.step(1), ExchangeStep::sent);
  r.exchange.begin_cycle();
  r.exchange.withdraw();  // an alarm or a reset
  ASSERT_EQ(r.exchange.requests().size(), 1U);
  EXPECT_EQ(r.exchange.requests()[0].kind, AxisRequestKind::withdraw);
  EXPECT_EQ(r.exchange.requests()[0].slot, 1U);
  r.exchange.abandon();
  // The grant crossed the withdraw: the axis goes back at once, and only once.
  r.feedback[1].owner = 1;
  r.exchange.begin_cycle();
  EXPECT_FALSE(r.exchange.update(1, r.feedback[1]));
  ASSERT_EQ(r.exchange.requests().size(), 1U);
  EXPECT_EQ(r.exchange.requests()[0].kind, AxisRequestKind::release);
  r.exchange.begin_cycle();
  EXPECT_FALSE(r.exchange.update(1, r.feedback[1]));
  EXPECT_TRUE(r.exchange.requests().empty());
}

TEST(AxisExchange, ACommandedAxisTakenOrFollowingIsLost) {
  Rig r;
  r.feedback[0].owner = 3;
  const auto loss = r.exchange.update(0, r.feedback[0]);
  ASSERT_TRUE(loss);
  EXPECT_EQ(loss->slot, 0U);
  EXPECT_STREQ(loss->why.data(), "was taken by channel 3: this program still moves it");
  EXPECT_EQ(r.exchange.use(0), SlotUse::away);
  EXPECT_FALSE(r.exchange.update(0, r.feedback[0]));  // once
  // A foreign slot may not move; the alarm says why.
  const std::array<double, 2> from{0.0, 0.0};
  const std::array<double, 2> to{5.0, 0.0};
  ASSERT_EQ(r.exchange.foreign_slot(from, to), std::optional<std::size_t>(0));
  const CoordinationAlarm a = r.exchange.foreign_move_alarm(0, r.feedback);
  EXPECT_EQ(a.number, kAlarmAxisAway);
  EXPECT_NE(std::string(a.text.data()).find("X is with channel 3"), std::string::npos);
  // Back at a program start (settle): taken over from where it stands.
  r.feedback[0].owner = 1;
  r.feedback[0].cmd = -3.0;
  r.exchange.settle(r.feedback, r.commanded);
  EXPECT_EQ(r.exchange.use(0), SlotUse::commanded);
  EXPECT_DOUBLE_EQ(r.commanded[0], -3.0);
  EXPECT_FALSE(r.exchange.foreign_slot(from, to));
}

}  // namespace
}  // namespace mcnc::coordination
