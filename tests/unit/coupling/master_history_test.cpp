// The positions a G51.4 slave reads its master's increments from: by cycle, not waited for once
// the master is gone or has run further ahead than the history keeps.
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
  EXPECT_FALSE(h.latest(1).has_value());
  for (std::uint64_t c = 0; c < 6; ++c) {
    h.put(1, c, 10.0 + static_cast<double>(c));
  }
  EXPECT_EQ(h.at(1, 5).lookup, Lookup::found);
  EXPECT_DOUBLE_EQ(h.at(1, 5).cmd, 15.0);
  EXPECT_DOUBLE_EQ(h.at(1, 2).cmd, 12.0);
  EXPECT_EQ(h.at(1, 1).lookup, Lookup::unavailable);  // overwritten by cycle 5
  EXPECT_EQ(h.at(1, 6).lookup, Lookup::not_yet);
  EXPECT_DOUBLE_EQ(*h.latest(1), 15.0);
  EXPECT_EQ(h.at(3, 0).lookup, Lookup::not_yet);  // another master: its own history
  EXPECT_EQ(h.at(2, 0).lookup, Lookup::unavailable);
}

TEST(MasterHistory, AGoneMasterIsNotWaitedFor) {
  const std::array<std::uint32_t, 1> masters{4};
  MasterHistory h(masters, 8);
  h.put(4, 0, 1.0);
  h.gone(4);
  EXPECT_EQ(h.at(4, 0).lookup, Lookup::found);  // what came before it left still counts
  EXPECT_EQ(h.at(4, 1).lookup, Lookup::unavailable);
}

TEST(MasterHistory, ALateSampleDoesNotMoveTheNewest) {
  const std::array<std::uint32_t, 1> masters{1};
  MasterHistory h(masters, 8);
  h.put(1, 7, 7.0);
  h.put(1, 6, 6.0);  // out of order
  EXPECT_DOUBLE_EQ(*h.latest(1), 7.0);
  EXPECT_EQ(h.at(1, 6).lookup, Lookup::found);
}

}  // namespace
}  // namespace mcnc::coupling
