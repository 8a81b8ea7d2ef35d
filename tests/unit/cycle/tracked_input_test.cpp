#include "common/cycle/tracked_input.hpp"

#include <gtest/gtest.h>

namespace mcnc::cycle {
namespace {

using Input = TrackedInput<int, 8>;

Input::WriterId writer(std::uint8_t k) {
  Input::WriterId id{};
  id[15] = k;
  return id;
}

TEST(TrackedInput, ACycleRunsWithTheSampleStampedTheCycleBefore) {
  LockstepGate gate(2);
  Input in(1);
  EXPECT_FALSE(in.heard());
  EXPECT_EQ(in.for_cycle(5, true), nullptr);
  in.on_sample(40, 4, 0, writer(1), gate);
  in.on_sample(50, 5, 0, writer(1), gate);
  EXPECT_TRUE(in.heard());
  ASSERT_NE(in.for_cycle(5, true), nullptr);
  EXPECT_EQ(*in.for_cycle(5, true), 40);
  EXPECT_EQ(*in.for_cycle(6, true), 50);
  // Lockstep never takes another cycle's sample; realtime takes the latest when its is not in.
  EXPECT_EQ(in.for_cycle(9, true), nullptr);
  EXPECT_EQ(*in.for_cycle(9, false), 50);
  EXPECT_EQ(in.for_cycle(0, true), nullptr);
  EXPECT_EQ(in.gate_input(), 1U);
}

TEST(TrackedInput, TheGateHearsItsSamplesAndEventsOnItsOwnSlot) {
  LockstepGate gate(2);
  Input a(0);
  Input b(1);
  a.on_sample(1, 0, 0, writer(1), gate);
  EXPECT_FALSE(gate.may_run(1));          // b's sample stamped 0 is missing
  b.on_sample(2, 0, 2, writer(2), gate);  // announcing events 1 and 2
  EXPECT_FALSE(gate.may_run(1));
  b.on_event(1, gate);
  b.on_event(2, gate);
  EXPECT_TRUE(gate.may_run(1));
}

TEST(TrackedInput, OnlyItsOwnWriterLeavingLosesIt) {
  LockstepGate gate(1);
  Input in(0);
  EXPECT_FALSE(in.on_unmatched(writer(1), gate)) << "not heard yet: nothing to lose";
  in.on_sample(7, 0, 0, writer(1), gate);
  EXPECT_FALSE(in.on_unmatched(writer(2), gate)) << "another writer of the topic";
  EXPECT_FALSE(in.lost());
  EXPECT_FALSE(gate.may_run(2));
  EXPECT_TRUE(in.on_unmatched(writer(1), gate));
  EXPECT_TRUE(in.lost());
  EXPECT_TRUE(gate.may_run(2)) << "a lost input is no longer awaited";
  ASSERT_NE(in.for_cycle(1, true), nullptr) << "a lost input keeps its last samples";
  EXPECT_EQ(*in.for_cycle(1, true), 7);
  EXPECT_TRUE(in.loss_pending());
  EXPECT_TRUE(in.take_loss());
  EXPECT_FALSE(in.loss_pending());
  EXPECT_FALSE(in.take_loss()) << "its loss is told once";
}

TEST(TrackedInput, AnInputLostForAnotherReasonIsNoLongerAwaited) {
  LockstepGate gate(1);
  Input in(0);
  in.lose(gate);
  EXPECT_TRUE(in.lost());
  EXPECT_TRUE(gate.may_run(3));
  EXPECT_TRUE(in.take_loss());
}

}  // namespace
}  // namespace mcnc::cycle
