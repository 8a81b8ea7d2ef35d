// G10 L14 P0/P1 (spec dafeng L4770-4849): the load of the watched axes against their
// reference, over the moves P0 or P1 watch, with the filter time in cycles.
#include "channel/coordination/load_monitor.hpp"

#include "tests/unit/coordination/xz_loads.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::coordination {
namespace {

constexpr std::uint32_t kX = 1U << 0;
constexpr std::uint32_t kZ = 1U << 1;

using test::loads;
using test::xz;

LoadMonitor::Percent reference(double x, double z) {
  LoadMonitor::Percent r{};
  r[0] = x;
  r[1] = z;
  return r;
}

TEST(LoadMonitor, P1AlarmsOnAG01WhoseLoadPassesTheReference) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::feed_moves, kZ, reference(0, 80), 1);
  const MoveUnderWay feed{kZ, true};
  EXPECT_FALSE(m.step(loads(0, 79.9), feed));
  EXPECT_FALSE(m.step(loads(500, 80.0), feed));  // X not watched; 80 is not above 80
  EXPECT_TRUE(m.step(loads(0, -80.5), feed));    // either way the axis turns
  EXPECT_EQ(m.alarm().number, kAlarmOverload);
  EXPECT_EQ(m.alarm().axis, 2);
  EXPECT_EQ(std::string(m.alarm().text.data()),
            "G10 L14 P1: the load of axis Z, 80.5 %, is above 80 % (overload)");
}

TEST(LoadMonitor, P1DoesNotWatchRapidsNorBlocksThatDoNotMoveTheAxis) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::feed_moves, kZ, reference(0, 80), 1);
  EXPECT_FALSE(m.step(loads(0, 200), MoveUnderWay{kZ, false}));  // G00
  EXPECT_FALSE(m.step(loads(0, 200), MoveUnderWay{kX, true}));   // a G01 of X alone
  EXPECT_FALSE(m.step(loads(0, 200), MoveUnderWay{0, false}));   // a dwell
}

TEST(LoadMonitor, P0WatchesEveryMoveOfTheAxis) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::every_move, kX | kZ, reference(50, 80), 1);
  EXPECT_TRUE(m.step(loads(60, 0), MoveUnderWay{kX | kZ, false}));
  EXPECT_EQ(m.alarm().axis, 1);
  EXPECT_EQ(std::string(m.alarm().text.data()),
            "G10 L14 P0: the load of axis X, 60 %, is above 50 % (overload)");
}

// J (L4860: "above for 2 s, then the alarm"): the load above the reference for the filter's
// cycles in a row; a cycle below starts again.
TEST(LoadMonitor, TheFilterNeedsTheLoadAboveForItsCyclesInARow) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::feed_moves, kX, reference(80, 0), 3);
  const MoveUnderWay feed{kX, true};
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_FALSE(m.step(loads(70, 0), feed));  // below: from the start again
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_FALSE(m.step(loads(90, 0), MoveUnderWay{kX, false}));  // a G00 between: not watched
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_FALSE(m.step(loads(90, 0), feed));
  EXPECT_TRUE(m.step(loads(90, 0), feed));
}

// L4860-4866: a new P1 replaces the set ("cancel Z, set X"); P1 without axes cancels all.
TEST(LoadMonitor, ANewSetReplacesTheOldAndNoAxesCancels) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::feed_moves, kZ, reference(0, 80), 1);
  m.set(LoadWatch::feed_moves, kX, reference(80, 0), 1);
  EXPECT_FALSE(m.step(loads(0, 200), MoveUnderWay{kX | kZ, true}));
  m.set(LoadWatch::feed_moves, 0, {}, 1);
  EXPECT_EQ(m.watch(), LoadWatch::off);
  EXPECT_FALSE(m.step(loads(200, 200), MoveUnderWay{kX | kZ, true}));
}

TEST(LoadMonitor, AWatchedAxisWhoseDriveDoesNotReportItsLoadIsAnAlarm) {
  const auto slots = xz();
  LoadMonitor m(slots);
  m.set(LoadWatch::every_move, kZ, reference(0, 80), 1);
  auto f = loads(0, 0);
  f[1].load_known = false;
  EXPECT_TRUE(m.step(f, MoveUnderWay{kZ, false}));
  EXPECT_EQ(std::string(m.alarm().text.data()),
            "G10 L14 P0: the drive of axis Z does not report its load");
}

}  // namespace
}  // namespace mcnc::coordination
