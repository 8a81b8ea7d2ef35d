// Events take effect from the cycle after they were sent, in the order they arrived; a full
// queue refuses instead of growing.
#include "common/cycle/pending_events.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mcnc::cycle {
namespace {

TEST(PendingEvents, HandsOverWhatWasSentBeforeTheCycleInArrivalOrder) {
  PendingEvents<int, 4> q;
  EXPECT_TRUE(q.push(1, 10));
  EXPECT_TRUE(q.push(2, 12));
  EXPECT_TRUE(q.push(3, 9));  // sent earlier, arrived later
  std::vector<int> seen;
  q.peek_due(11, [&](int e) { seen.push_back(e); });
  EXPECT_EQ(seen, (std::vector<int>{1, 3}));
  EXPECT_EQ(q.size(), 3U);  // peeking leaves them
  seen.clear();
  q.take_due(10, [&](int e) { seen.push_back(e); });
  EXPECT_EQ(seen, (std::vector<int>{3}));  // not yet the one sent at 10
  seen.clear();
  q.take_due(13, [&](int e) { seen.push_back(e); });
  EXPECT_EQ(seen, (std::vector<int>{1, 2}));
  EXPECT_EQ(q.size(), 0U);
}

TEST(PendingEvents, AFullQueueRefuses) {
  PendingEvents<int, 2> q;
  EXPECT_TRUE(q.push(1, 0));
  EXPECT_TRUE(q.push(2, 0));
  EXPECT_FALSE(q.push(3, 0));
  int sum = 0;
  q.take_due(1, [&](int e) { sum += e; });
  EXPECT_EQ(sum, 3);
  EXPECT_TRUE(q.push(3, 0));
}

}  // namespace
}  // namespace mcnc::cycle
