// A G04.1 block: arrive once the writes before it are out, wait for the participants, and the
// alarms of a partner gone or a mismatch. (The barrier's own rules: sync_barrier_test.cpp.)
#include "channel/coordination/sync_mark.hpp"

#include <gtest/gtest.h>

namespace mcnc::coordination {
namespace {

ChannelSet both() {
  ChannelSet s;
  s.set(1);
  s.set(2);
  return s;
}

SyncMarkInputs running_both() {
  SyncMarkInputs in;
  in.active = both();
  return in;
}

TEST(SyncMark, ArrivesAfterTheWritesAndIsReleasedWhenThePartnerArrives) {
  SyncMark ch1(1);
  SyncMark ch2(2);
  ch1.begin(true, 7, both(), false);
  SyncMarkInputs in = running_both();
  in.writes_pending = true;
  ASSERT_EQ(ch1.step(in), SyncMarkStep::pending);
  EXPECT_FALSE(ch1.arrived_now());
  in.writes_pending = false;
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  ASSERT_TRUE(ch1.arrived_now());
  EXPECT_EQ(ch1.barrier().current().p, 7);
  EXPECT_EQ(ch1.barrier().current().generation, 1U);
  ch2.on_arrival(ch1.barrier().current());
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  EXPECT_FALSE(ch1.arrived_now());  // once
  ch2.begin(true, 7, both(), false);
  ASSERT_EQ(ch2.step(in), SyncMarkStep::released);  // CH1 was there first
  EXPECT_TRUE(ch2.arrived_now());
  ch1.on_arrival(ch2.barrier().current());
  EXPECT_EQ(ch1.step(in), SyncMarkStep::released);
}

TEST(SyncMark, WithoutPItOnlyStopsReadAhead) {
  SyncMark ch1(1);
  ch1.begin(false, 0, {}, false);
  SyncMarkInputs in = running_both();
  in.writes_pending = true;
  EXPECT_EQ(ch1.step(in), SyncMarkStep::done);
  EXPECT_FALSE(ch1.arrived_now());
}

TEST(SyncMark, APartnerGoneWhileWaitedForIsAnAlarmThatNamesIt) {
  SyncMark ch1(1);
  ch1.begin(true, 3, both(), false);
  SyncMarkInputs in = running_both();
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  in.lost.set(2);
  ASSERT_EQ(ch1.step(in), SyncMarkStep::alarm);
  EXPECT_EQ(ch1.alarm().number, kAlarmSyncPartnerLost);
  EXPECT_STREQ(ch1.alarm().text.data(),
               "G04.1 P3: channel 2 is gone while this channel waits for it");
}

TEST(SyncMark, PartnersNamingOtherParticipantsAreAMismatch) {
  SyncMark ch1(1);
  SyncMark ch2(2);
  ChannelSet three = both();
  three.set(3);
  ch1.begin(true, 5, both(), false);
  ch2.begin(true, 5, three, false);
  SyncMarkInputs in = running_both();
  in.active.set(3);
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  ASSERT_EQ(ch2.step(in), SyncMarkStep::waiting);
  ch1.on_arrival(ch2.barrier().current());
  ASSERT_EQ(ch1.step(in), SyncMarkStep::alarm);
  EXPECT_EQ(ch1.alarm().number, kAlarmSyncMismatch);
}

TEST(SyncMark, AnAbandonedWaitArrivesAgainAtTheNextMark) {
  SyncMark ch1(1);
  ch1.begin(true, 1, both(), false);
  SyncMarkInputs in = running_both();
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  ch1.abandon();  // a reset
  EXPECT_FALSE(ch1.barrier().waiting());
  ch1.begin(true, 1, both(), false);
  ASSERT_EQ(ch1.step(in), SyncMarkStep::waiting);
  EXPECT_TRUE(ch1.arrived_now());
  EXPECT_EQ(ch1.barrier().current().generation, 2U);
}

}  // namespace
}  // namespace mcnc::coordination
