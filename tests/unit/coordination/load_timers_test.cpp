// G10 L14 P2-P5 and P20-P51 (spec dafeng L4770-4849): the load timers count, per axis, the
// cycles its load stays above the reference over the moves each timer times, and format ②
// compares them with its seconds.
#include "channel/coordination/load_timers.hpp"

#include "tests/unit/coordination/xz_loads.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::coordination {
namespace {

constexpr std::uint32_t kX = 1U << 0;
constexpr std::uint32_t kZ = 1U << 1;
constexpr double kCycle = 0.001;

using test::loads;
using test::xz;

LoadTimers::Values values(double x, double z) {
  LoadTimers::Values v{};
  v[0] = x;
  v[1] = z;
  return v;
}

void steps(LoadTimers& t, int n, double x, double z, const MoveUnderWay& move) {
  for (int i = 0; i < n; ++i) {
    ASSERT_TRUE(t.step(loads(x, z), move));
  }
}

TEST(LoadTimers, P2CountsTheG01CyclesAboveTheReferenceOnly) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(2, kZ, values(0, 80), 1);
  const MoveUnderWay feed{kZ, true};
  steps(t, 5, 0, 85, feed);
  steps(t, 3, 0, 80, feed);                      // 80 is not above 80
  steps(t, 4, 0, -90, feed);                     // either way the axis turns
  steps(t, 7, 0, 200, MoveUnderWay{kZ, false});  // G00: P2 times G01 moves only
  steps(t, 6, 0, 200, MoveUnderWay{kX, true});   // a G01 that does not move Z
  steps(t, 2, 200, 0, feed);                     // X is not timed
  EXPECT_EQ(t.cycles(2, 1), 9u);
  EXPECT_EQ(t.cycles(2, 0), 0u);
  EXPECT_EQ(t.cycles(3, 1), 0u);  // the other timers were not started
}

TEST(LoadTimers, P4TimesEveryMoveAndEachTimerHasItsOwnReference) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(4, kZ, values(0, 50), 1);
  t.start(5, kZ, values(0, 100), 1);
  t.start(3, kZ, values(0, 10), 1);
  steps(t, 10, 0, 60, MoveUnderWay{kZ, false});  // a G00 at 60 %
  EXPECT_EQ(t.cycles(4, 1), 10u);
  EXPECT_EQ(t.cycles(5, 1), 0u);
  EXPECT_EQ(t.cycles(3, 1), 0u);  // P3: G01 moves only
}

TEST(LoadTimers, ARunCountsOnceItLastedTheFilterTimeThenInFull) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(2, kZ, values(0, 80), 4);
  const MoveUnderWay feed{kZ, true};
  steps(t, 3, 0, 90, feed);  // three cycles: shorter than J, never counts
  steps(t, 1, 0, 0, feed);
  EXPECT_EQ(t.cycles(2, 1), 0u);
  steps(t, 4, 0, 90, feed);
  EXPECT_EQ(t.cycles(2, 1), 4u);  // J reached: its four cycles count
  steps(t, 2, 0, 90, feed);
  EXPECT_EQ(t.cycles(2, 1), 6u);
}

TEST(LoadTimers, AStartBeginsFromZeroAndNoAxesStopsTheTimer) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(2, kZ, values(0, 80), 1);
  steps(t, 5, 0, 90, MoveUnderWay{kZ, true});
  t.start(2, kZ, values(0, 80), 1);
  EXPECT_EQ(t.cycles(2, 1), 0u);
  steps(t, 2, 0, 90, MoveUnderWay{kZ, true});
  EXPECT_EQ(t.cycles(2, 1), 2u);
  t.start(2, 0, {}, 1);
  steps(t, 2, 0, 90, MoveUnderWay{kZ, true});
  EXPECT_EQ(t.cycles(2, 1), 0u);
  t.start(4, kZ, values(0, 10), 1);
  steps(t, 2, 0, 90, MoveUnderWay{kZ, true});
  t.clear();
  EXPECT_EQ(t.cycles(4, 1), 0u);
}

// The spec's drill check (L4868-4893): Z above 80 % for 16 s of its feed is "more than 15 s",
// above 10 % for 20 s is not "less than 15 s"; the bits of the axes that meet the condition.
TEST(LoadTimers, FormatTwoComparesEachAxisTimeWithItsSeconds) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(2, kZ, values(0, 80), 1);
  t.start(3, kX | kZ, values(10, 10), 1);
  steps(t, 4000, 0, 50, MoveUnderWay{kZ, true});
  steps(t, 16000, 0, 85, MoveUnderWay{kZ, true});
  EXPECT_EQ(t.check(2, true, kZ, values(0, 15), kCycle, true), kZ);
  EXPECT_EQ(t.check(2, false, kZ, values(0, 15), kCycle, true), 0u);
  EXPECT_EQ(t.check(3, false, kZ, values(0, 15), kCycle, true), 0u);  // 20 s
  // X never moved: its 0 s is less than 15 s (a broken drill).
  EXPECT_EQ(t.check(3, false, kX | kZ, values(15, 15), kCycle, true), kX);
  EXPECT_EQ(t.alarm().number, 0);
}

TEST(LoadTimers, FormatTwoWithoutRIsAnAlarmWhenAnAxisMeetsIt) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(2, kZ, values(0, 80), 1);
  steps(t, 1500, 0, 85, MoveUnderWay{kZ, true});
  EXPECT_EQ(t.check(2, false, kZ, values(0, 1), kCycle, false), 0u);
  EXPECT_EQ(t.alarm().number, 0);
  EXPECT_EQ(t.check(2, true, kZ, values(0, 1), kCycle, false), kZ);
  EXPECT_EQ(t.alarm().number, kAlarmLoadTime);
  EXPECT_EQ(t.alarm().axis, 2);
  EXPECT_EQ(std::string(t.alarm().text.data()),
            "G10 L14 P21: the load of axis Z was above 80 % for 1.500 s, more than 1 s");
}

TEST(LoadTimers, ATimedAxisWithoutItsLoadIsAnAlarm) {
  const auto slots = xz();
  LoadTimers t(slots);
  t.start(5, kZ, values(0, 80), 1);
  auto f = loads(0, 0);
  EXPECT_TRUE(t.step(f, MoveUnderWay{kX, false}));  // Z does not move: not timed
  f[1].load_known = false;
  EXPECT_TRUE(t.step(f, MoveUnderWay{kX, false}));
  EXPECT_FALSE(t.step(f, MoveUnderWay{kZ, false}));
  EXPECT_EQ(t.alarm().number, kAlarmLoadTime);
  EXPECT_EQ(std::string(t.alarm().text.data()),
            "G10 L14 P5: the drive of axis Z does not report its load");
}

}  // namespace
}  // namespace mcnc::coordination
