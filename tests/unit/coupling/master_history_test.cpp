// The positions a G51.4 slave reads its master's increments from: by cycle, not waited for once
// the master is gone or has run further ahead than the history keeps, and extrapolated to the
// slave's cycle across late samples and skipped cycles.
#include "axisnode/coupling/master_history.hpp"

#include <gtest/gtest.h>

#include <array>

namespace mcnc::coupling {
namespace {

using Lookup = MasterHistory::Lookup;

TEST(MasterHistory, FindsACycleUntilTheRingHasPassedIt) {
  const std::array<std::uint32_t, 2> masters{1, 3};
  MasterHistory h(masters, 4);
  EXPECT_TRUE(h.may_lead(3));
  EXPECT_FALSE(h.may_lead(2));
  EXPECT_EQ(h.at(1, 0).lookup, Lookup::not_yet);
  for (std::uint64_t c = 0; c < 6; ++c) {
    h.put(1, c, 10.0 + static_cast<double>(c), true);
  }
  EXPECT_EQ(h.at(1, 5).lookup, Lookup::found);
  EXPECT_DOUBLE_EQ(h.at(1, 5).cmd, 15.0);
  EXPECT_DOUBLE_EQ(h.at(1, 2).cmd, 12.0);
  EXPECT_EQ(h.at(1, 1).lookup, Lookup::unavailable);  // overwritten by cycle 5
  EXPECT_EQ(h.at(1, 6).lookup, Lookup::not_yet);
  EXPECT_EQ(h.at(3, 0).lookup, Lookup::not_yet);  // another master: its own history
  EXPECT_EQ(h.at(2, 0).lookup, Lookup::unavailable);
}

TEST(MasterHistory, AGoneMasterIsNotWaitedFor) {
  const std::array<std::uint32_t, 1> masters{4};
  MasterHistory h(masters, 8);
  h.put(4, 0, 1.0, true);
  h.gone(4);
  EXPECT_EQ(h.at(4, 0).lookup, Lookup::found);  // what came before it left still counts
  EXPECT_EQ(h.at(4, 1).lookup, Lookup::unavailable);
  EXPECT_EQ(h.estimate(4, 2, true).lookup, Lookup::unavailable);
}

TEST(MasterHistory, LockstepEstimatesTheCycleFromTheLastTwo) {
  const std::array<std::uint32_t, 1> masters{1};
  MasterHistory h(masters, 16);
  EXPECT_EQ(h.estimate(1, 1, true).lookup, Lookup::not_yet);
  h.put(1, 0, 2.0, true);
  EXPECT_DOUBLE_EQ(h.estimate(1, 1, true).cmd, 2.0);  // one sample: standing
  h.put(1, 1, 2.5, true);
  EXPECT_DOUBLE_EQ(h.estimate(1, 2, true).cmd, 3.0);
  EXPECT_TRUE(h.estimate(1, 2, true).operating);
  EXPECT_EQ(h.estimate(1, 3, true).lookup, Lookup::not_yet);  // waits for the sample of 2
  // Out of operation: reported so, and its jump (a homing) is no speed for the next sample.
  h.put(1, 2, 90.0, false);
  EXPECT_FALSE(h.estimate(1, 3, true).operating);
  h.put(1, 3, 90.0, true);
  EXPECT_DOUBLE_EQ(h.estimate(1, 4, true).cmd, 90.0);
}

TEST(MasterHistory, RealtimeExtrapolatesOverLateSamplesAndSkippedCycles) {
  const std::array<std::uint32_t, 1> masters{1};
  MasterHistory h(masters, 16);
  h.put(1, 10, 1.0, true);
  h.put(1, 11, 1.2, true);
  EXPECT_NEAR(h.estimate(1, 12, false).cmd, 1.4, 1e-12);
  // The sample of 12 is late: cycle 13 runs from 11's, two cycles on.
  EXPECT_NEAR(h.estimate(1, 13, false).cmd, 1.6, 1e-12);
  // The master skipped cycles 12 and 13: the speed is over the three cycles between.
  h.put(1, 14, 1.8, true);
  EXPECT_NEAR(h.estimate(1, 15, false).cmd, 2.0, 1e-12);
  // A sample that arrives late does not move the newest back.
  h.put(1, 13, 1.6, true);
  EXPECT_NEAR(h.estimate(1, 15, false).cmd, 2.0, 1e-12);
}

}  // namespace
}  // namespace mcnc::coupling
