// G10 L14 P9 (spec dafeng L5094-5142): the torque limits it emits, per axis named, modal; G10
// L14 P0/P1 (L4770-4849): the loads watched; and the alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

// The spec's friction welding (L5122-5140): Z limited to 135 % for the feed and its dwell, the
// limit cancelled by Z0 before and after; the moves between keep it (modal, L5107-5108).
TEST(InterpTorqueLimit, TheFrictionWeldingExampleLimitsZForItsFeed) {
  const RunResult r = run_ok(
      "G10 L14 P9 Z0\nG00 Z1\nG00 X0\nG10 L14 P9 Z135\nG09 G01 Z-20 F100\nG04 X1\n"
      "G01 Z100 F2000\nG10 L14 P9 Z0\nM30\n");
  const auto limits = r.of(Op::torque_limit);
  ASSERT_EQ(limits.size(), 3u);
  EXPECT_EQ(limits[0].torque_data_axes, 1U << kZ);
  EXPECT_EQ(limits[0].torque_data[kZ], 0.0);  // Z0 cancels
  EXPECT_EQ(limits[0].line, 1);
  EXPECT_EQ(limits[1].torque_data_axes, 1U << kZ);  // X is not named: it keeps its own
  EXPECT_EQ(limits[1].torque_data[kZ], 135.0);
  EXPECT_EQ(limits[1].line, 4);
  EXPECT_EQ(limits[2].torque_data[kZ], 0.0);
  EXPECT_EQ(limits[2].line, 8);
  // It moves nothing: the feed starts where the G00 left Z.
  const auto feeds = r.of(Op::linear);
  ASSERT_EQ(feeds.size(), 2u);
  EXPECT_NEAR(feeds[0].to[kZ], -20.0, 1e-12);
}

TEST(InterpTorqueLimit, NamesEachAxisItSets) {
  const RunResult r = run_ok("G10 L14 P9 X50 Z12.5\nM30\n");
  const auto limits = r.of(Op::torque_limit);
  ASSERT_EQ(limits.size(), 1u);
  EXPECT_EQ(limits[0].torque_data_axes, (1U << kX) | (1U << kZ));
  EXPECT_EQ(limits[0].torque_data[kX], 50.0);  // a percentage: no diameter halving
  EXPECT_EQ(limits[0].torque_data[kZ], 12.5);
}

// The spec's first example (L4850-4866): Z watched at 80 % in G01, then X at 80 % with J2 (Z
// no more: the set is replaced), then nothing.
TEST(InterpLoadWatch, TheG01LoadCheckExampleWatchesZThenXThenNothing) {
  const RunResult r = run_ok(
      "G10 P1 L14 Z80\nG00 X0 Z0\nG01 W-10 F20\nG00 Z0\nG10 P1 L14 X80 J2\nG01 U-10 F20\n"
      "G00 X0 Z0\nG10 P1 L14\nM30\n");
  const auto watches = r.of(Op::load_watch);
  ASSERT_EQ(watches.size(), 3u);
  EXPECT_FALSE(watches[0].every_move);
  EXPECT_EQ(watches[0].torque_data_axes, 1U << kZ);
  EXPECT_EQ(watches[0].torque_data[kZ], 80.0);
  EXPECT_EQ(watches[0].filter_s, 0.0);
  EXPECT_EQ(watches[1].torque_data_axes, 1U << kX);
  EXPECT_EQ(watches[1].torque_data[kX], 80.0);  // a percentage: no diameter halving
  EXPECT_EQ(watches[1].filter_s, 2.0);          // seconds (D15)
  EXPECT_EQ(watches[2].torque_data_axes, 0U);   // cancels every check
  EXPECT_EQ(watches[2].line, 8);
}

TEST(InterpLoadWatch, P0WatchesEveryMove) {
  const RunResult r = run_ok("G10 L14 P0 Z150 J0.5\nM30\n");
  const auto watches = r.of(Op::load_watch);
  ASSERT_EQ(watches.size(), 1u);
  EXPECT_TRUE(watches[0].every_move);
  EXPECT_EQ(watches[0].torque_data[kZ], 150.0);
  EXPECT_EQ(watches[0].filter_s, 0.5);
}

TEST(InterpTorqueLimit, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G00 X10\nG10 L14 P9 W40\nM30\n", alarm::kWordNotAllowed, 2},  // absolute addresses only
      {"G10 L14 P9 Z1001\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P9 Z-1\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P9\nM30\n", alarm::kCycleWordMissing, 1},       // no axis: nothing to limit
      {"G10 L14 P10 Z50\nM30\n", alarm::kNotInThisVersion, 1},  // torque mode
      {"G10 L14 P1 Z80 J-1\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P0 U80\nM30\n", alarm::kWordNotAllowed, 1},
      {"G10 L14 P1 Z1200\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P21 Z15 R100\nM30\n", alarm::kNotInThisVersion, 1},  // the timers' checks
      {"G10 L14 P7 R100 Z80\nM30\n", alarm::kNotInThisVersion, 1},   // drilling overload
  };
  expect_alarms(cases, lathe());
}

}  // namespace
}  // namespace mcnc::interp::test
