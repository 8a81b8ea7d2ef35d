// SYNC at a fixed offset inside each cycle; a late producer skips instead of bursting.
#include "canopen/sync_schedule.hpp"

#include <gtest/gtest.h>

namespace mcnc::canopen {
namespace {

TEST(SyncSchedule, EachSyncIsDueAtItsOffsetInsideItsCycle) {
  const SyncSchedule s(1'000'000, 1'000'000, 400'000);  // 1 ms cycle, SYNC at 0.4 ms
  EXPECT_EQ(s.due(0), 1'400'000);
  EXPECT_EQ(s.due(1), 2'400'000);
  EXPECT_EQ(s.due(1000), 1'001'400'000);
}

TEST(SyncSchedule, NothingIsSentBeforeItsTime) {
  const SyncSchedule s(0, 1'000'000, 500'000);
  std::uint64_t index = 99;
  EXPECT_FALSE(s.to_send(499'999, 0, index));
  EXPECT_EQ(index, 99U);
  ASSERT_TRUE(s.to_send(500'000, 0, index));
  EXPECT_EQ(index, 0U);
  EXPECT_FALSE(s.to_send(1'499'999, 1, index));
  ASSERT_TRUE(s.to_send(1'500'100, 1, index));  // woke 100 ns late: still SYNC 1
  EXPECT_EQ(index, 1U);
}

TEST(SyncSchedule, AProducerThatWokeCyclesLateSendsOnlyTheLatestDue) {
  const SyncSchedule s(0, 1'000'000, 500'000);
  std::uint64_t index = 0;
  // Next unsent is 3; it woke at 6.7 ms: SYNCs 3, 4 and 5 are past, 6 is due: send 6 only.
  ASSERT_TRUE(s.to_send(6'700'000, 3, index));
  EXPECT_EQ(index, 6U);
}

// The host's estimate of the machine's clock is refined during the run: the SYNCs after it are
// due by the new start, earlier or later, reached by steps of at most 1 % of the period (10 us
// of 1 ms), and none is sent twice.
TEST(SyncSchedule, TheSyncsFollowAStartThatMovesByBoundedSteps) {
  SyncSchedule s(0, 1'000'000, 500'000);
  std::uint64_t index = 0;
  ASSERT_TRUE(s.to_send(2'500'000, 2, index));
  EXPECT_EQ(index, 2U);
  s.follow_start(7'000);  // 7 us later: reached at once
  EXPECT_EQ(s.due(3), 3'507'000);
  EXPECT_FALSE(s.to_send(3'506'999, 3, index));
  ASSERT_TRUE(s.to_send(3'507'000, 3, index));
  EXPECT_EQ(index, 3U);
  s.follow_start(-23'000);  // 30 us earlier than that: 10 us a SYNC
  EXPECT_EQ(s.due(4), 4'497'000);
  ASSERT_TRUE(s.to_send(4'497'000, 4, index));
  EXPECT_EQ(index, 4U);  // 3 is not repeated
  s.follow_start(-23'000);
  EXPECT_EQ(s.due(5), 5'487'000);
  s.follow_start(-23'000);
  EXPECT_EQ(s.due(6), 6'477'000);
  s.follow_start(-23'000);
  EXPECT_EQ(s.start_ns(), -23'000);  // there, and it stays
}

}  // namespace
}  // namespace mcnc::canopen
