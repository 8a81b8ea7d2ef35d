#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/cycle_buffer.hpp"

#include <gtest/gtest.h>

using mcnc::cycle::CycleBuffer;
using mcnc::cycle::LockstepGate;

TEST(LockstepGate, CycleZeroNeedsNothing) {
  LockstepGate gate(2);
  EXPECT_TRUE(gate.may_run(0));
  EXPECT_FALSE(gate.may_run(1));
}

TEST(LockstepGate, CycleNNeedsEveryInputStampedNMinus1) {
  LockstepGate gate(2);
  gate.on_sample(0, 4, 0);
  EXPECT_FALSE(gate.may_run(5));
  EXPECT_EQ(gate.first_missing(5), 1U);
  gate.on_sample(1, 4, 0);
  EXPECT_TRUE(gate.may_run(5));
  // A sample of another cycle does not count for this one.
  EXPECT_FALSE(gate.may_run(6));
  EXPECT_FALSE(gate.may_run(4));
}

TEST(LockstepGate, ProducerRunningAheadKeepsOlderStamps) {
  LockstepGate gate(1);
  for (std::uint64_t c = 10; c < 14; ++c) {
    gate.on_sample(0, c, 0);
  }
  EXPECT_TRUE(gate.may_run(11));
  EXPECT_TRUE(gate.may_run(14));
  EXPECT_FALSE(gate.may_run(15));
}

TEST(LockstepGate, AnnouncedEventsMustHaveArrived) {
  LockstepGate gate(1);
  gate.on_sample(0, 7, 2);  // sender says: I had sent events 1 and 2 by cycle 7
  EXPECT_FALSE(gate.may_run(8));
  gate.on_event(0, 2);  // out of order: 1 still missing
  EXPECT_FALSE(gate.may_run(8));
  EXPECT_EQ(gate.events_received(0), 0U);
  gate.on_event(0, 1);
  EXPECT_EQ(gate.events_received(0), 2U);
  EXPECT_TRUE(gate.may_run(8));
}

TEST(LockstepGate, EventsArrivingAheadAreAbsorbedInOrder) {
  LockstepGate gate(1);
  gate.on_event(0, 3);
  gate.on_event(0, 5);
  gate.on_event(0, 2);
  EXPECT_EQ(gate.events_received(0), 0U);
  gate.on_event(0, 1);
  EXPECT_EQ(gate.events_received(0), 3U);
  gate.on_event(0, 4);
  EXPECT_EQ(gate.events_received(0), 5U);
  gate.on_event(0, 4);  // duplicate
  EXPECT_EQ(gate.events_received(0), 5U);
}

TEST(LockstepGate, LostInputIsNoLongerAwaited) {
  LockstepGate gate(2);
  gate.on_sample(0, 0, 0);
  EXPECT_FALSE(gate.may_run(1));
  gate.set_expected(1, false);
  EXPECT_TRUE(gate.may_run(1));
}

// A slow wait says what it waits for: whose input, the latest cycle it has, the events it lacks.
TEST(LockstepGate, AWaitNamesTheInputAndHowFarItCame) {
  LockstepGate gate(2);
  gate.on_sample(0, 4, 0);
  gate.on_sample(1, 2, 0);
  auto w = gate.wait(5);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->input, 1U);
  EXPECT_TRUE(w->sample_missing);
  EXPECT_TRUE(w->any_sample);
  EXPECT_EQ(w->latest_cycle, 2U);
  gate.on_sample(1, 4, 3);  // announces events 1..3, of which only 1 came
  gate.on_event(1, 1);
  w = gate.wait(5);
  ASSERT_TRUE(w.has_value());
  EXPECT_FALSE(w->sample_missing);
  EXPECT_EQ(w->events_announced, 3U);
  EXPECT_EQ(w->events_received, 1U);
  gate.on_event(1, 2);
  gate.on_event(1, 3);
  EXPECT_FALSE(gate.wait(5).has_value());
  EXPECT_FALSE(LockstepGate(1).wait(1)->any_sample);
}

TEST(CycleBuffer, FindsByStampAndForgetsOverwritten) {
  CycleBuffer<int, 4> buffer;
  EXPECT_TRUE(buffer.empty());
  EXPECT_EQ(buffer.at(0), nullptr);
  for (int c = 0; c < 6; ++c) {
    buffer.put(static_cast<std::uint64_t>(c), c * 10);
  }
  EXPECT_EQ(buffer.at(1), nullptr);  // overwritten by cycle 5
  ASSERT_NE(buffer.at(3), nullptr);
  EXPECT_EQ(*buffer.at(3), 30);
  ASSERT_NE(buffer.latest(), nullptr);
  EXPECT_EQ(*buffer.latest(), 50);
  buffer.put(2, 99);  // a late, older sample does not become the latest
  EXPECT_EQ(buffer.latest_cycle(), 5U);
}
