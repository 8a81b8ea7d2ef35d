// G144 / G145 on both sides: the checks before a call, the wait for a free target, the release
// and its outcomes, the calls a channel serves and their repetitions.
#include "channel/coordination/sub_call.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::coordination {
namespace {

PartnerStatus partner(ChannelState state, std::uint64_t call_id = 0, std::uint32_t caller = 0) {
  return PartnerStatus{true, state, call_id, caller};
}

CallRequest call_to(std::uint32_t target, bool wait = true, int repeat = 1) {
  CallRequest c;
  c.caller = 1;
  c.target = target;
  c.program = 1234;
  c.wait = wait;
  c.repeat = repeat;
  return c;
}

const ChannelSet kNoneLost;

TEST(SubCall, AFreeTargetIsCalledAndTheCallerWaitsForItsRelease) {
  SubCall calls(1, 0);
  calls.set_partner(2, partner(ChannelState::idle));
  calls.begin(call_to(2));
  ASSERT_EQ(calls.step(5, kNoneLost, true), CallStep::pending);  // writes go out first
  ASSERT_EQ(calls.step(6, kNoneLost, false), CallStep::send);
  EXPECT_EQ(calls.call().call_id, (std::uint64_t{1} << 40) | 1);
  EXPECT_EQ(calls.waiting_for(), 2U);
  EXPECT_EQ(calls.step(7, kNoneLost, false), CallStep::pending);
  calls.on_release(CallRelease{calls.call().call_id + 1, 1, 2, CallOutcome::released});  // not ours
  EXPECT_EQ(calls.step(8, kNoneLost, false), CallStep::pending);
  calls.on_release(CallRelease{calls.call().call_id, 1, 2, CallOutcome::released});
  EXPECT_EQ(calls.step(9, kNoneLost, false), CallStep::done);
  EXPECT_EQ(calls.waiting_for(), 0U);
}

TEST(SubCall, ATargetStillOnItsWayUpOrFinishingOurCallIsWaitedForWithinTheLimit) {
  SubCall calls(1, 10);
  calls.set_partner(2, partner(ChannelState::reset));
  calls.begin(call_to(2));
  EXPECT_EQ(calls.step(100, kNoneLost, false), CallStep::waiting);
  EXPECT_EQ(calls.step(109, kNoneLost, false), CallStep::waiting);
  ASSERT_EQ(calls.step(110, kNoneLost, false), CallStep::alarm);
  EXPECT_EQ(calls.alarm().number, kAlarmCallTimeout);
  // Without a limit it waits for ever, and calls once the target is idle.
  SubCall patient(1, 0);
  patient.set_partner(2, partner(ChannelState::running, (std::uint64_t{1} << 40) | 7, 1));
  patient.begin(call_to(2));
  EXPECT_EQ(patient.step(1, kNoneLost, false), CallStep::waiting);
  EXPECT_EQ(patient.step(100000, kNoneLost, false), CallStep::waiting);
  patient.set_partner(2, partner(ChannelState::idle));
  EXPECT_EQ(patient.step(100001, kNoneLost, false), CallStep::send);
}

TEST(SubCall, ABusySelfOrLostTargetIsAnAlarm) {
  SubCall calls(1, 0);
  calls.set_partner(2, partner(ChannelState::running));
  calls.begin(call_to(2));
  ASSERT_EQ(calls.step(1, kNoneLost, false), CallStep::alarm);
  EXPECT_EQ(calls.alarm().number, kAlarmCallBusy);
  EXPECT_STREQ(calls.alarm().text.data(), "G144 N2: channel 2 is busy (running)");
  calls.begin(call_to(1));
  ASSERT_EQ(calls.step(1, kNoneLost, false), CallStep::alarm);
  EXPECT_EQ(calls.alarm().number, kAlarmCallCycle);
  ChannelSet lost;
  lost.set(2);
  calls.begin(call_to(2));
  ASSERT_EQ(calls.step(1, lost, false), CallStep::alarm);
  EXPECT_EQ(calls.alarm().number, kAlarmCallFailed);
}

TEST(SubCall, CallingTheChannelThatWaitsForOurCallIsACycle) {
  SubCall calls(2, 0);
  CallRequest from3 = call_to(2);
  from3.caller = 3;
  calls.serve(from3);  // channel 3 waits (H1) for the program this channel runs
  calls.set_partner(3, partner(ChannelState::waiting));
  calls.begin(call_to(3));
  ASSERT_EQ(calls.step(1, kNoneLost, false), CallStep::alarm);
  EXPECT_EQ(calls.alarm().number, kAlarmCallCycle);
  // Released (G145), channel 3 may be called again: no circle.
  ASSERT_TRUE(calls.release_caller(CallOutcome::released));
  calls.set_partner(3, partner(ChannelState::idle));
  calls.begin(call_to(3));
  EXPECT_EQ(calls.step(2, kNoneLost, false), CallStep::send);
}

TEST(SubCall, EveryEndOtherThanAReleaseIsAnAlarm) {
  const auto ended = [](CallOutcome outcome, bool lost_target) {
    SubCall calls(1, 0);
    calls.set_partner(2, partner(ChannelState::idle));
    calls.begin(call_to(2));
    EXPECT_EQ(calls.step(1, kNoneLost, false), CallStep::send);
    ChannelSet lost;
    if (lost_target) {
      lost.set(2);
    } else {
      calls.on_release(CallRelease{calls.call().call_id, 1, 2, outcome});
    }
    EXPECT_EQ(calls.step(2, lost, false), CallStep::alarm);
    return calls.alarm().number;
  };
  EXPECT_EQ(ended(CallOutcome::refused, false), kAlarmCallRefused);
  EXPECT_EQ(ended(CallOutcome::failed, false), kAlarmCallFailed);
  EXPECT_EQ(ended(CallOutcome::aborted, false), kAlarmCallFailed);
  EXPECT_EQ(ended(CallOutcome::released, true), kAlarmCallFailed);  // its process is gone
}

TEST(SubCall, ACallWithoutWaitEndsAtOnceAndItsRefusalIsAnAlarmOnce) {
  SubCall calls(1, 0);
  calls.set_partner(2, partner(ChannelState::idle));
  calls.begin(call_to(2, false));
  ASSERT_EQ(calls.step(1, kNoneLost, false), CallStep::send);
  EXPECT_EQ(calls.waiting_for(), 0U);
  EXPECT_EQ(calls.take_refusal(), nullptr);
  calls.on_release(CallRelease{calls.call().call_id, 1, 2, CallOutcome::refused});
  const CoordinationAlarm* refusal = calls.take_refusal();
  ASSERT_NE(refusal, nullptr);
  EXPECT_EQ(refusal->number, kAlarmCallRefused);
  EXPECT_EQ(calls.take_refusal(), nullptr);
}

TEST(SubCall, TheTargetIsNotFreeAgainUntilItsStatusShowsTheCall) {
  SubCall calls(1, 0);
  calls.set_partner(2, partner(ChannelState::idle));
  calls.begin(call_to(2, false));
  ASSERT_EQ(calls.step(1, kNoneLost, false), CallStep::send);
  const std::uint64_t first = calls.call().call_id;
  calls.begin(call_to(2, false));  // its status still says idle, from before the call
  EXPECT_EQ(calls.step(2, kNoneLost, false), CallStep::waiting);
  calls.set_partner(2, partner(ChannelState::running, first, 1));
  calls.set_partner(2, partner(ChannelState::idle));
  EXPECT_EQ(calls.step(3, kNoneLost, false), CallStep::send);
}

TEST(SubCall, AServedCallReleasesItsCallerOnceAndRepeats) {
  SubCall calls(2, 0);
  CallRequest c = call_to(2, true, 3);
  c.call_id = 77;
  EXPECT_FALSE(calls.on_call(c));
  ASSERT_EQ(calls.incoming().size(), 1U);
  calls.serve(calls.incoming()[0]);
  calls.clear_incoming();
  EXPECT_EQ(calls.serving_call(), 77U);
  EXPECT_EQ(calls.serving_caller(), 1U);
  const auto release = calls.release_caller(CallOutcome::released);
  ASSERT_TRUE(release);
  EXPECT_EQ(release->call_id, 77U);
  EXPECT_EQ(release->target, 2U);
  EXPECT_FALSE(calls.release_caller(CallOutcome::failed));  // once
  EXPECT_TRUE(calls.repeat_served());
  EXPECT_TRUE(calls.repeat_served());
  EXPECT_FALSE(calls.repeat_served());  // L3: three runs
  EXPECT_EQ(calls.serving_call(), 0U);
  EXPECT_EQ(calls.refusal(c).outcome, CallOutcome::refused);
}

}  // namespace
}  // namespace mcnc::coordination
