// G98.1 / G99.1 automatic chip breaking (spec dafeng L2548-2604) in the interpreter: the feed
// mode each selects, the breaks of the cutting moves, rapids left alone, G98/G99 ending it, and
// the alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

TEST(InterpChipBreaking, PerMinuteBreaksEveryQRevolutionsOfTheSpindle) {
  // F200 mm/min at S500: 0.4 mm per revolution, Q5 = 2 mm, P-1.5 = 0.6 mm back.
  RunResult r = run_ok("G98.1 P-1.5 Q5\nM03 S500\nG00 X50 Z0\nG01 W-10 F200\nG00 X60\nM30\n");
  const auto cuts = r.of(Op::linear);
  ASSERT_EQ(cuts.size(), 15u);
  const double z[] = {-2, -1.4, -2, -4, -3.4, -4, -6, -5.4, -6, -8, -7.4, -8, -10, -9.4, -10};
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    EXPECT_NEAR(cuts[i].to[1], z[i], 1e-9) << i;
    EXPECT_NEAR(cuts[i].to[0], 25, 1e-12) << i;
    EXPECT_NEAR(cuts[i].feed, 200, 1e-12);
  }
  EXPECT_EQ(r.of(Op::rapid).size(), 2u);  // rapids are not broken
}

TEST(InterpChipBreaking, PerRevolutionDwellsPRevolutions) {
  // 0.2 mm/rev, Q10 = 2 mm; P2: a dwell of 2 revolutions.
  RunResult r = run_ok("G99.1 P2 Q10\nM03 S100\nG00 X50 Z0\nG01 W-5 F0.2\nM30\n");
  const auto cuts = r.of(Op::linear);
  ASSERT_EQ(cuts.size(), 3u);
  EXPECT_NEAR(cuts[0].to[1], -2, 1e-9);
  EXPECT_NEAR(cuts[1].to[1], -4, 1e-9);
  EXPECT_NEAR(cuts[2].to[1], -5, 1e-9);
  EXPECT_EQ(cuts[0].feed_mode, FeedMode::per_rev);  // G99.1 selects feed per revolution
  const auto dwells = r.of(Op::dwell);
  ASSERT_EQ(dwells.size(), 2u);
  EXPECT_TRUE(dwells[0].in_revs);
  EXPECT_NEAR(dwells[0].seconds, 2, 1e-12);
}

TEST(InterpChipBreaking, WorksInsideTheSingleCyclesAndEndsWithG98OrG99) {
  // The spec's example (L2578-2591): G90 with breaks, then G98 X49 without.
  RunResult r =
      run_ok("G98.1 P-1.5 Q5\nM03 S500\nG00 X52 Z0\nG90 X50 W-10 F200\nX49.5\nG98 X49\nM30\n");
  std::size_t first = 0;
  std::size_t second = 0;
  std::size_t third = 0;
  for (const Command& c : r.of(Op::linear)) {
    first += c.line == 4 ? 1 : 0;
    second += c.line == 5 ? 1 : 0;
    third += c.line == 6 ? 1 : 0;
  }
  EXPECT_GT(first, 2u);  // the Z cut broken, the X retract too when its turn comes
  EXPECT_GT(second, 2u);
  EXPECT_EQ(third, 2u);  // G98: the cut and the retract only
  run_ok(
      "IF[#4013 NE 0] #3000=1\nG99.1 P1 Q3\nIF[#4013 NE 99.1] #3000=2\n"
      "IF[#4005 NE 99] #3000=3\nG98\nIF[#4013 NE 0] #3000=4\nM30\n");
}

TEST(InterpChipBreaking, PerMinuteUnderG96CountsTheSpeedAtEachRadius) {
  // G96 S100: 100 m/min, rpm = 100000 / (2 pi r). Along Z at X50 (r 25): 636.62 rpm, at F100
  // 0.15708 mm a revolution, Q5 = 0.785398 mm between the dwells of P1.
  RunResult r = run_ok("G50 S3000\nG98.1 P1 Q5\nG96 S100 M03\nG00 X50 Z0\nG01 W-2 F100\nM30\n");
  const auto cuts = r.of(Op::linear);
  ASSERT_EQ(cuts.size(), 3u);
  const double q = 5.0 * 100.0 * 2.0 * M_PI * 25.0 / 100000.0;
  EXPECT_NEAR(cuts[0].to[1], -q, 1e-9);
  EXPECT_NEAR(cuts[1].to[1], -2.0 * q, 1e-9);
  EXPECT_NEAR(cuts[2].to[1], -2.0, 1e-12);
  EXPECT_EQ(r.of(Op::dwell).size(), 2u);
  // Facing from X50 to X10: the speed rises as the radius falls. From r 25 the count is
  // (100000 / (2 pi F)) ln(25 / r): 5 revolutions at r = 25 exp(-5 F 2 pi / 100000), 10 at
  // 25 exp(-10 ...); below r = 5.305 (G50 S3000) the speed stays 3000.
  RunResult f = run_ok("G50 S3000\nG98.1 P1 Q5\nG96 S100 M03\nG00 X50 Z0\nG01 U-40 F100\nM30\n");
  const auto faces = f.of(Op::linear);
  ASSERT_GT(faces.size(), 10u);
  const double k = 2.0 * M_PI * 100.0 / 100000.0;  // F / (rpm r), per revolution
  EXPECT_NEAR(faces[0].to[0], 25.0 * std::exp(-5.0 * k), 1e-6);
  EXPECT_NEAR(faces[1].to[0], 25.0 * std::exp(-10.0 * k), 1e-6);
  // At the clamp: 3000 rpm, 1/30 mm a revolution, 1/6 mm between the last breaks.
  const std::size_t n = faces.size();
  EXPECT_NEAR(faces[n - 1].to[0], 5.0, 1e-12);
  EXPECT_NEAR(faces[n - 3].to[0] - faces[n - 2].to[0], 5.0 / 30.0, 1e-5);
}

TEST(InterpChipBreaking, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G98.1 P1\nM30\n", alarm::kCycleWordMissing, 1},
      {"G98.1 Q5\nM30\n", alarm::kCycleWordMissing, 1},
      {"G98.1 P1 Q0\nM30\n", alarm::kBadWordValue, 1},
      {"G98.1 P0 Q5\nM30\n", alarm::kBadWordValue, 1},
      {"G98.1 P1 Q5 X10\nM30\n", alarm::kWordNotAllowed, 1},
      // Per minute the spindle's speed makes the revolutions: none, or G96's changing one.
      {"G98.1 P1 Q5\nG01 W-5 F100\nM30\n", alarm::kCycleWordMissing, 2},
      // G96 needs the speed limit G50 S: at X0 its speed would have none.
      {"G98.1 P1 Q5\nG96 S100 M03\nG01 W-5 F100\nM30\n", alarm::kCycleWordMissing, 3},
      // F0.2 mm/min at 50810 rpm is 0.000004 mm a revolution: G94's 20 mm cut would break
      // a million times every 5 revolutions. An alarm, not gigabytes of pieces (the fuzzer's
      // input, tests/fuzz/crashes/chip_breaking_tiny_feed.nc).
      {"G98.1 P-1.5 Q5\nM03 S50810\nG94 X40 W-5 F0.2\nM30\n", alarm::kCycleValue, 3},
  };
  expect_alarms(cases);
}

}  // namespace
}  // namespace mcnc::interp::test
