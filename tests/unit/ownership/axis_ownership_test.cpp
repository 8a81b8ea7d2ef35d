// G140/G141/G142 as the axis node decides them (spec dafeng §3.3): one owner at any time.
#include "axisnode/ownership/axis_ownership.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

namespace mcnc::ownership {
namespace {

using Kind = OwnershipRequestKind;

OwnershipRequest req(Kind kind, std::uint32_t channel, bool force = false,
                     std::uint64_t cycle = 0) {
  return OwnershipRequest{kind, channel, force, cycle};
}

OwnershipAnswer answer_of(const AxisOwnership& o, std::uint32_t channel) {
  for (std::size_t i = 0; i < o.answer_count(); ++i) {
    if (o.answers()[i].channel == channel) {
      return o.answers()[i].answer;
    }
  }
  return OwnershipAnswer::none;
}

TEST(AxisOwnership, OnlyTheOwnerReleasesAndAFreeAxisGoesToTheFirstToAsk) {
  AxisOwnership a(1);
  EXPECT_EQ(a.owner(), 1U);
  a.request(req(Kind::release, 2));
  EXPECT_FALSE(a.decide(true).changed);
  EXPECT_EQ(answer_of(a, 2), OwnershipAnswer::refused);
  a.request(req(Kind::release, 1));
  const OwnershipChange c = a.decide(true);
  EXPECT_TRUE(c.changed);
  EXPECT_EQ(c.owner, 0U);
  EXPECT_EQ(a.released_by(), 1U);
  // Two channels ask in the same cycle: the lower number wins, the other waits its turn.
  a.request(req(Kind::acquire, 3, false, 10));
  a.request(req(Kind::acquire, 2, false, 10));
  EXPECT_EQ(a.decide(true).owner, 2U);
  EXPECT_EQ(answer_of(a, 2), OwnershipAnswer::granted);
  EXPECT_EQ(answer_of(a, 3), OwnershipAnswer::none);
  EXPECT_TRUE(a.waiting(3));
  EXPECT_EQ(a.decide(true).owner, 2U);  // still 2's
  a.request(req(Kind::release, 2));
  EXPECT_EQ(a.decide(true).owner, 3U);  // released and taken by the waiting one at once
  EXPECT_EQ(answer_of(a, 3), OwnershipAnswer::granted);
}

TEST(AxisOwnership, AnEarlierRequestWinsOverALowerChannelNumber) {
  AxisOwnership a(1);
  a.request(req(Kind::release, 1));
  a.decide(true);
  a.request(req(Kind::acquire, 3, false, 5));
  a.request(req(Kind::acquire, 2, false, 6));
  EXPECT_EQ(a.decide(true).owner, 3U);
}

TEST(AxisOwnership, AReleaseGoesToTheFirstInLineAndAFreshGrantIsNotTakenAtOnce) {
  AxisOwnership a(1);
  a.request(req(Kind::acquire, 4, false, 10));
  a.decide(true);
  ASSERT_TRUE(a.waiting(4));
  a.request(req(Kind::release, 1, false, 20));
  a.request(req(Kind::acquire, 3, false, 20));
  EXPECT_EQ(a.decide(true).owner, 4U);  // waiting since cycle 10: before CH3
  EXPECT_TRUE(a.waiting(3));
  // CH4 releases and takes again in one cycle; CH5's forced acquire cannot undo that grant.
  a.request(req(Kind::release, 4, false, 30));
  a.request(req(Kind::acquire, 4, false, 30));
  a.request(req(Kind::acquire, 5, true, 30));
  const OwnershipChange c = a.decide(true);
  EXPECT_NE(c.owner, 5U);
  EXPECT_FALSE(c.forced);
}

TEST(AxisOwnership, AForcedAcquireTakesTheAxisOnlyAtRest) {
  AxisOwnership a(1);
  a.request(req(Kind::acquire, 2, true));
  EXPECT_EQ(a.decide(false).owner, 1U);  // the owner's move goes on
  EXPECT_TRUE(a.waiting(2));
  const OwnershipChange c = a.decide(true);
  EXPECT_TRUE(c.changed);
  EXPECT_TRUE(c.forced);
  EXPECT_EQ(c.previous, 1U);
  EXPECT_EQ(c.owner, 2U);
  EXPECT_EQ(a.released_by(), 1U);  // CH1 may restore it
}

// CT-G140-01 (spec dafeng §3.3): A (exchange 14) is CH1's; CH2 takes it after CH1's G140 and
// both give it back with G142.
TEST(AxisOwnership, TheSpecExchangeExample) {
  AxisOwnership a(1);
  a.request(req(Kind::restore, 1));  // step 3, both channels: nothing to restore
  a.request(req(Kind::restore, 2));
  EXPECT_FALSE(a.decide(true).changed);
  EXPECT_EQ(answer_of(a, 1), OwnershipAnswer::granted);
  EXPECT_EQ(answer_of(a, 2), OwnershipAnswer::granted);
  a.request(req(Kind::acquire, 2));  // the negative case: G141 before the release waits
  a.decide(true);
  EXPECT_EQ(a.owner(), 1U);
  a.request(req(Kind::release, 1));     // step 9
  EXPECT_EQ(a.decide(true).owner, 2U);  // step 11: the waiting G141 gets it
  a.request(req(Kind::release, 1));     // CH1 no longer has a say
  a.decide(true);
  EXPECT_EQ(answer_of(a, 1), OwnershipAnswer::refused);
  // Step 16: both restore; CH2 is still moving A, so the restore waits until it stands.
  a.request(req(Kind::restore, 1));
  a.request(req(Kind::restore, 2));
  EXPECT_EQ(a.decide(false).owner, 2U);
  const OwnershipChange c = a.decide(true);
  EXPECT_EQ(c.owner, 1U);
  EXPECT_EQ(a.released_by(), 0U);
  EXPECT_EQ(a.waiting_count(), 0U);
}

TEST(AxisOwnership, AChannelWithNoSayCannotRestoreAndAGoneChannelStopsWaiting) {
  AxisOwnership a(1);
  a.request(req(Kind::release, 1));
  a.decide(true);
  a.request(req(Kind::acquire, 2));
  a.decide(true);
  a.request(req(Kind::restore, 3));
  a.decide(true);
  EXPECT_EQ(answer_of(a, 3), OwnershipAnswer::refused);
  EXPECT_EQ(a.owner(), 2U);
  a.request(req(Kind::acquire, 3));
  a.decide(true);
  EXPECT_TRUE(a.waiting(3));
  a.channel_gone(3);
  EXPECT_FALSE(a.waiting(3));
  a.request(req(Kind::release, 2));
  EXPECT_EQ(a.decide(true).owner, 0U);  // nobody left to take it
}

// The asker hears a refusal from the node's feedback: the bit stays until its next request is
// decided, so that a channel that reads only the newest feedback cannot miss it.
TEST(AxisOwnership, ARefusalStaysForItsAskerUntilItsNextRequestIsDecided) {
  AxisOwnership a(1);
  a.request(req(Kind::release, 2));
  a.decide(true);
  EXPECT_EQ(a.refused_channels(), std::uint64_t{1} << 1);
  EXPECT_EQ(a.full_channels(), 0U);
  a.decide(true);
  a.decide(true);
  EXPECT_EQ(a.refused_channels(), std::uint64_t{1} << 1);  // nothing new from channel 2
  a.request(req(Kind::release, 3));  // another channel's refusal adds its own bit
  a.decide(true);
  EXPECT_EQ(a.refused_channels(), (std::uint64_t{1} << 1) | (std::uint64_t{1} << 2));
  a.request(req(Kind::acquire, 2));  // granted? no: 1 owns it, so 2 waits; not refused
  a.decide(true);
  EXPECT_TRUE(a.waiting(2));
  EXPECT_EQ(a.refused_channels(), std::uint64_t{1} << 2);
}

// More requests in one cycle than the node takes: the one that does not fit is answered `full`
// once the cycle is decided, even when an earlier request of the same channel was taken.
TEST(AxisOwnership, ARequestThatDoesNotFitInACycleIsAnsweredFull) {
  AxisOwnership a(1);
  for (std::uint32_t c = 2; c <= 64; ++c) {
    ASSERT_TRUE(a.request(req(Kind::acquire, c, false, 1)));
  }
  ASSERT_TRUE(a.request(req(Kind::restore, 2, false, 1)));
  EXPECT_FALSE(a.request(req(Kind::restore, 3, false, 1)));  // the 65th of the cycle
  a.decide(false);
  EXPECT_EQ(a.full_channels(), std::uint64_t{1} << 2);
  EXPECT_TRUE(a.waiting(3));  // its acquire was taken
  a.request(req(Kind::withdraw, 3, false, 2));
  a.decide(false);
  EXPECT_EQ(a.full_channels(), 0U);
}

// The waiting line is full: a request that would wait is answered `full` instead.
TEST(AxisOwnership, ARequestThatWouldWaitInAFullLineIsAnsweredFull) {
  AxisOwnership a(1);
  a.request(req(Kind::release, 1));
  a.decide(true);
  a.request(req(Kind::acquire, 2));
  a.decide(true);
  ASSERT_EQ(a.owner(), 2U);
  std::uint64_t cycle = 10;
  for (std::uint32_t c = 3; c <= 64; ++c) {  // 62 wait for channel 2's axis
    a.request(req(Kind::acquire, c, false, ++cycle));
  }
  a.decide(false);
  a.request(req(Kind::restore, 2, false, ++cycle));  // its owner: waits for the axis at rest
  a.decide(false);
  a.request(req(Kind::restore, 1, false, ++cycle));  // the home channel: waits as well
  a.decide(false);
  ASSERT_EQ(a.waiting_count(), AxisOwnership::kMaxWaiting);
  EXPECT_EQ(a.full_channels(), 0U);
  a.request(req(Kind::acquire, 1, false, ++cycle));
  a.decide(false);
  EXPECT_EQ(answer_of(a, 1), OwnershipAnswer::full);
  EXPECT_EQ(a.full_channels(), std::uint64_t{1});
  EXPECT_EQ(a.owner(), 2U);
}

TEST(AxisOwnership, AWithdrawEndsOnlyThatChannelsWait) {
  AxisOwnership a(1);
  a.request(req(Kind::acquire, 2));
  a.request(req(Kind::acquire, 3));
  EXPECT_FALSE(a.decide(true).changed);
  EXPECT_TRUE(a.waiting(2));
  a.request(req(Kind::withdraw, 2));  // channel 2 was reset while it waited
  a.decide(true);
  EXPECT_FALSE(a.waiting(2));
  EXPECT_TRUE(a.waiting(3));
  a.request(req(Kind::release, 1));
  EXPECT_EQ(a.decide(true).owner, 3U);  // the release goes to the one still waiting
  a.request(req(Kind::withdraw, 3));    // withdrawing after the grant changes nothing
  EXPECT_EQ(a.decide(true).owner, 3U);
}

TEST(AxisOwnership, TheHomeChannelTakesItsAxisBackFromAnyone) {
  AxisOwnership a(1);
  a.request(req(Kind::release, 1));
  a.decide(true);
  a.request(req(Kind::acquire, 2));
  a.decide(true);
  a.request(req(Kind::release, 2));  // the borrower lets it go to nobody
  a.decide(true);
  EXPECT_EQ(a.released_by(), 2U);
  a.request(req(Kind::restore, 1));
  EXPECT_EQ(a.decide(true).owner, 1U);
  a.request(req(Kind::acquire, 3, true));  // taken by force ...
  a.decide(true);
  a.request(req(Kind::restore, 1));  // ... and back, once the axis stands
  EXPECT_FALSE(a.decide(false).changed);
  EXPECT_EQ(a.decide(true).owner, 1U);
}

TEST(AxisOwnership, AWithdrawGoesBeforeTheWaitingLineIsServed) {
  AxisOwnership a(1);
  a.request(req(Kind::acquire, 2, true));
  a.decide(false);  // a forced acquire waits while the axis moves
  EXPECT_TRUE(a.waiting(2));
  a.request(req(Kind::withdraw, 2));  // channel 2 was reset; the axis stands now
  EXPECT_FALSE(a.decide(true).changed);
  EXPECT_EQ(a.owner(), 1U);
}

// 1 000 races (issue 7): channels acquire, hold for a while and release, some with force; what
// every channel believes (from its answers and the changes) never has two owners, and every
// acquire is answered in the end.
TEST(AxisOwnership, RandomRacesNeverHaveTwoOwners) {
  std::mt19937 rng(20261201);
  constexpr std::uint32_t kChannels = 6;
  for (int trial = 0; trial < 1000; ++trial) {
    AxisOwnership a(1);
    std::map<std::uint32_t, int> holding;  // channel -> cycles left while it believes it owns
    holding[1] = 3;                        // the home channel owns it by configuration
    std::map<std::uint32_t, bool> asked;
    int granted = 0;
    int asks = 0;
    for (std::uint64_t cycle = 1; cycle < 400; ++cycle) {
      for (std::uint32_t ch = 1; ch <= kChannels; ++ch) {
        const bool owns = holding.count(ch) != 0;
        if (owns && --holding[ch] <= 0) {
          a.request(req(Kind::release, ch, false, cycle));
        } else if (!owns && !asked[ch] && cycle < 300 && rng() % 8 == 0) {
          a.request(req(Kind::acquire, ch, rng() % 5 == 0, cycle));
          asked[ch] = true;
          ++asks;
        }
      }
      const OwnershipChange c = a.decide(rng() % 3 != 0);
      for (std::size_t i = 0; i < a.answer_count(); ++i) {
        const auto& ans = a.answers()[i];
        if (ans.kind == Kind::acquire && ans.answer == OwnershipAnswer::granted) {
          holding[ans.channel] = 1 + static_cast<int>(rng() % 6);
          asked[ans.channel] = false;
          ++granted;
        } else if (ans.kind == Kind::release && ans.answer == OwnershipAnswer::released) {
          holding.erase(ans.channel);
        }
      }
      if (c.forced) {
        holding.erase(c.previous);  // the channel learns it lost the axis
      }
      if (c.changed && c.previous != 0 && !c.forced) {
        ASSERT_EQ(holding.count(c.previous), 0U) << "trial " << trial;
      }
      ASSERT_LE(holding.size(), 1U) << "trial " << trial << " cycle " << cycle;
      ASSERT_EQ(holding.empty() ? 0U : holding.begin()->first, a.owner())
          << "trial " << trial << " cycle " << cycle;
    }
    // Owners hold for at most a few cycles: everyone who asked got the axis in the end.
    EXPECT_EQ(granted, asks) << "trial " << trial;
    EXPECT_EQ(a.waiting_count(), 0U) << "trial " << trial;
  }
}

}  // namespace
}  // namespace mcnc::ownership
