#include "hmi_bridge/core/meeting_tracker.hpp"

#include <gtest/gtest.h>

namespace mcnc::hmi {
namespace {

TEST(MeetingTracker, PartnersMeetWhenTheLastArrivesInTheSameRound) {
  MeetingTracker t;
  EXPECT_FALSE(t.arrive(2, 1, 1, 0b011, 100));
  const auto m = t.arrive(1, 1, 1, 0b011, 140);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->p, 1);
  EXPECT_EQ(m->channels, 0b011U);
  EXPECT_EQ(m->cycle, 140U);
  // The next round at the same mark is a new meeting.
  EXPECT_FALSE(t.arrive(1, 1, 2, 0b011, 300));
  EXPECT_TRUE(t.arrive(2, 1, 2, 0b011, 290));
}

TEST(MeetingTracker, OtherMarksAndRoundsDoNotCompleteAMeeting) {
  MeetingTracker t;
  EXPECT_FALSE(t.arrive(1, 1, 1, 0b111, 10));
  EXPECT_FALSE(t.arrive(2, 2, 1, 0b111, 11));  // another mark
  EXPECT_FALSE(t.arrive(3, 1, 2, 0b111, 12));  // another round
  EXPECT_FALSE(t.arrive(2, 1, 1, 0b111, 13));
  const auto m = t.arrive(3, 1, 1, 0b111, 14);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->cycle, 14U);
  EXPECT_FALSE(t.arrive(99, 1, 1, 0b1, 15));  // not a channel number
}

}  // namespace
}  // namespace mcnc::hmi
