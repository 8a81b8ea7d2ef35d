// The clock offset from two-way exchanges: exact with symmetric delays, within its stated error
// whatever the delays, from the shortest round trip, following a clock that moved, and held
// through a while of long, lopsided round trips.
#include "common/clock/clock_offset.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>

using mcnc::clock::ClockExchange;
using mcnc::clock::ClockOffsetFilter;

namespace {

// An exchange between a host whose clock reads `offset` ahead of machine time and the
// reference, sent at machine time `t`, with one-way delays `there` and `back` and the
// reference's own `turn` between receiving and answering.
ClockExchange exchange(std::int64_t t, std::int64_t offset, std::int64_t there, std::int64_t back,
                       std::int64_t turn = 20'000) {
  ClockExchange e;
  e.t1_ns = t + offset;
  e.t2_ns = t + there;
  e.t3_ns = e.t2_ns + turn;
  e.t4_ns = e.t3_ns + back + offset;
  return e;
}

}  // namespace

TEST(ClockOffset, SymmetricDelaysGiveTheOffsetExactly) {
  ClockOffsetFilter filter;
  for (int i = 0; i < 7; ++i) {
    ASSERT_TRUE(filter.add(exchange(1'000'000'000 + i * 50'000'000, 3'000'000, 60'000, 60'000)));
    EXPECT_FALSE(filter.estimate()) << "no estimate from " << i + 1 << " exchanges";
  }
  ASSERT_TRUE(filter.add(exchange(2'000'000'000, 3'000'000, 60'000, 60'000)));
  const auto est = filter.estimate();
  ASSERT_TRUE(est);
  EXPECT_EQ(est->offset_ns, 3'000'000);
  EXPECT_EQ(est->error_ns, 60'000);
  EXPECT_EQ(est->samples, 8U);
}

TEST(ClockOffset, ANegativeOffsetAndLargeClockValues) {
  ClockOffsetFilter filter;
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(filter.add(
        exchange(9'000'000'000'000'000'000 + i * 1'000'000, -7'000'000, 40'000, 40'000)));
  }
  EXPECT_EQ(filter.estimate()->offset_ns, -7'000'000);
}

TEST(ClockOffset, TheShortestRoundTripWinsAndTheTruthIsWithinTheError) {
  std::mt19937_64 rng(22);
  std::exponential_distribution<double> queueing(1.0 / 200'000.0);  // mean 200 us
  std::uniform_int_distribution<std::int64_t> offsets(-50'000'000, 50'000'000);
  for (int run = 0; run < 500; ++run) {
    const std::int64_t offset = offsets(rng);
    ClockOffsetFilter filter;
    std::int64_t best_round_trip = std::numeric_limits<std::int64_t>::max();
    for (int i = 0; i < 40; ++i) {
      const auto there = 30'000 + static_cast<std::int64_t>(queueing(rng));
      const auto back = 30'000 + static_cast<std::int64_t>(queueing(rng));
      ASSERT_TRUE(filter.add(exchange(5'000'000'000 + i * 50'000'000, offset, there, back)));
      if (i >= 40 - static_cast<int>(ClockOffsetFilter::kWindow)) {
        best_round_trip = std::min(best_round_trip, there + back);
      }
    }
    const auto est = filter.estimate();
    ASSERT_TRUE(est);
    EXPECT_LE(std::abs(est->offset_ns - offset), est->error_ns) << "run " << run;
    // The held estimate bounds the offset at least as tightly as the last window's best.
    EXPECT_LE(est->error_ns, (best_round_trip + 1) / 2) << "run " << run;
    EXPECT_EQ(est->samples, ClockOffsetFilter::kWindow);
  }
}

TEST(ClockOffset, ExchangesThatCannotBeAreRefused) {
  ClockOffsetFilter filter;
  ClockExchange before_probe = exchange(1'000'000'000, 0, 50'000, 50'000);
  before_probe.t4_ns = before_probe.t1_ns - 1;
  EXPECT_FALSE(filter.add(before_probe));
  ClockExchange answered_first = exchange(1'000'000'000, 0, 50'000, 50'000);
  answered_first.t3_ns = answered_first.t2_ns - 1;
  EXPECT_FALSE(filter.add(answered_first));
  ClockExchange longer_than_trip = exchange(1'000'000'000, 0, 50'000, 50'000, 900'000'000);
  longer_than_trip.t4_ns = longer_than_trip.t1_ns + 1'000;
  EXPECT_FALSE(filter.add(longer_than_trip));
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(filter.add(exchange(2'000'000'000 + i * 1'000'000, 1'000, 50'000, 50'000)));
  }
  EXPECT_EQ(filter.estimate()->offset_ns, 1'000) << "the refused ones left no trace";
  EXPECT_EQ(filter.estimate()->samples, 8U);
}

TEST(ClockOffset, AClockThatMovedIsFollowedWithinAWindow) {
  ClockOffsetFilter filter;
  // A lucky exchange with the old offset, then a slower link with the new one.
  ASSERT_TRUE(filter.add(exchange(1'000'000'000, 2'000'000, 10'000, 10'000)));
  for (std::size_t i = 1; i < ClockOffsetFilter::kWindow; ++i) {
    ASSERT_TRUE(filter.add(exchange(1'000'000'000 + static_cast<std::int64_t>(i) * 50'000'000,
                                    2'100'000, 80'000, 80'000)));
  }
  EXPECT_EQ(filter.estimate()->offset_ns, 2'000'000) << "the shortest round trip still in it";
  ASSERT_TRUE(filter.add(exchange(3'000'000'000, 2'100'000, 80'000, 80'000)));
  EXPECT_EQ(filter.estimate()->offset_ns, 2'100'000) << "out of the window";
}

// A starved launcher: for a second every exchange waits milliseconds on one side only, which
// would put the offset off by half of that. The good estimate from before is held; once the
// drift allowance since it has grown past the long round trips' bound, they may replace it.
TEST(ClockOffset, LongLopsidedRoundTripsDoNotDisplaceAGoodEstimate) {
  ClockOffsetFilter filter;
  std::int64_t t = 1'000'000'000;
  for (int i = 0; i < 16; ++i, t += 50'000'000) {
    ASSERT_TRUE(filter.add(exchange(t, 3'000'000, 40'000, 40'000)));
  }
  ASSERT_EQ(filter.estimate()->offset_ns, 3'000'000);
  for (int i = 0; i < 20; ++i, t += 50'000'000) {
    ASSERT_TRUE(filter.add(exchange(t, 3'000'000, 40'000, 4'700'000)));  // the answer waits
  }
  EXPECT_EQ(filter.estimate()->offset_ns, 3'000'000) << "held through a second of them";
  EXPECT_EQ(filter.estimate()->error_ns, 40'000);
  // Some 30 s on, the allowance (100 ppm: 3 ms) exceeds their bound (2.37 ms): they count.
  for (int i = 0; i < 16; ++i, t += 2'000'000'000) {
    ASSERT_TRUE(filter.add(exchange(t, 3'000'000, 40'000, 4'700'000)));
  }
  EXPECT_LE(std::abs(filter.estimate()->offset_ns - 3'000'000), filter.estimate()->error_ns);
  EXPECT_GT(filter.estimate()->error_ns, 40'000);
}
