// Operator commands wait for their cycle; commands of another run are dropped.
#include "common/operator/operator_inbox.hpp"

#include <gtest/gtest.h>

namespace mcnc::process {
namespace {

OperatorRequest request(std::uint64_t seq, std::uint64_t cycle, std::uint64_t generation = 0,
                        OperatorActionKind action = OperatorActionKind::reset) {
  OperatorRequest r;
  r.seq = seq;
  r.cycle = cycle;
  r.generation = generation;
  r.action = action;
  return r;
}

TEST(OperatorInbox, ACommandTakesEffectAtItsCycleNotBefore) {
  OperatorInbox inbox;
  ASSERT_TRUE(inbox.put(request(1, 3000)));
  EXPECT_FALSE(inbox.take_due(2999, 1).has_value());
  const auto due = inbox.take_due(3000, 1);
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(due->seq, 1U);
  EXPECT_FALSE(inbox.take_due(3001, 1).has_value());  // once
}

TEST(OperatorInbox, CycleZeroMeansTheNextCycleAndLateOnesComeAtOnce) {
  OperatorInbox inbox;
  inbox.put(request(1, 0));
  inbox.put(request(2, 10));
  EXPECT_EQ(inbox.take_due(50, 1)->seq, 1U);
  EXPECT_EQ(inbox.take_due(50, 1)->seq, 2U);
  EXPECT_EQ(inbox.size(), 0U);
}

TEST(OperatorInbox, DueCommandsComeInArrivalOrderPastOnesThatWait) {
  OperatorInbox inbox;
  inbox.put(request(1, 100));
  inbox.put(request(2, 5, 0, OperatorActionKind::cycle_start));
  inbox.put(request(3, 5));
  EXPECT_EQ(inbox.take_due(5, 1)->seq, 2U);
  EXPECT_EQ(inbox.take_due(5, 1)->seq, 3U);
  EXPECT_FALSE(inbox.take_due(5, 1).has_value());
  EXPECT_EQ(inbox.take_due(100, 1)->seq, 1U);
}

TEST(OperatorInbox, CommandsOfAnotherRunAreDropped) {
  OperatorInbox inbox;
  inbox.put(request(1, 10, 1));
  inbox.put(request(2, 10, 2));
  inbox.put(request(3, 10, 0));  // whichever run
  EXPECT_EQ(inbox.take_due(10, 2)->seq, 2U);
  EXPECT_EQ(inbox.take_due(10, 2)->seq, 3U);
  EXPECT_FALSE(inbox.take_due(10, 2).has_value());
  EXPECT_EQ(inbox.size(), 0U);
}

TEST(OperatorInbox, AFullInboxRefusesAndKeepsWhatItHas) {
  OperatorInbox inbox;
  for (std::uint64_t i = 0; i < OperatorInbox::kSlots; ++i) {
    ASSERT_TRUE(inbox.put(request(i + 1, 1000)));
  }
  EXPECT_FALSE(inbox.put(request(99, 1)));
  EXPECT_EQ(inbox.take_due(1000, 1)->seq, 1U);
}

TEST(OperatorRequest, ConcernsItsChannelOrTheWholeMachine) {
  OperatorRequest r;
  EXPECT_TRUE(r.concerns(2));
  r.channel = 2;
  EXPECT_TRUE(r.concerns(2));
  EXPECT_FALSE(r.concerns(1));
}

}  // namespace
}  // namespace mcnc::process
