// G31 with the drives' touch probes: arming (all probes on the input, in time), the latch that
// stops the move and the position it reports.
#include "channel/coordination/skip_probe.hpp"

#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

#include <array>

namespace mcnc::coordination {
namespace {

constexpr std::uint32_t kXandZ = 0b101;  // axes 0 and 2 have their probes on the input

std::array<AxisFeedbackView, 4> feedback() {  // three axes and a spindle
  std::array<AxisFeedbackView, 4> f{};
  for (std::size_t i = 0; i < f.size(); ++i) {
    f[i].act = 10.0 * static_cast<double>(i + 1);
  }
  return f;
}

TEST(SkipProbe, TheMoveStartsOnlyOnceEveryProbeOnTheInputIsArmed) {
  SkipProbe skip(3, 200);
  skip.begin(2);
  auto f = feedback();
  EXPECT_EQ(skip.arm(f, kXandZ), SkipArming::waiting);
  f[0].probe = ProbeSeen::armed;
  EXPECT_EQ(skip.arm(f, kXandZ), SkipArming::waiting);
  f[1].probe = ProbeSeen::armed;  // not on the input: does not count
  EXPECT_EQ(skip.arm(f, kXandZ), SkipArming::waiting);
  f[2].probe = ProbeSeen::armed;
  EXPECT_EQ(skip.arm(f, kXandZ), SkipArming::armed);
  EXPECT_EQ(skip.phase(), SkipPhase::arming);
}

TEST(SkipProbe, NoProbeOnTheInputOrOneThatDoesNotArmIsAnAlarm) {
  SkipProbe skip(3, 5);
  skip.begin(4);
  const auto f = feedback();
  ASSERT_EQ(skip.arm(f, 0), SkipArming::alarm);
  EXPECT_EQ(skip.alarm().number, interp::alarm::kSkipInput);
  EXPECT_STREQ(skip.alarm().text.data(),
               "G31: no axis this channel commands has its touch probe on input 4");
  skip.begin(4);
  for (int n = 0; n < 5; ++n) {
    ASSERT_EQ(skip.arm(f, kXandZ), SkipArming::waiting) << n;
  }
  ASSERT_EQ(skip.arm(f, kXandZ), SkipArming::alarm);
  EXPECT_EQ(skip.alarm().number, kAlarmProbeNotArmed);
}

TEST(SkipProbe, TheFirstLatchStopsTheMoveWhereTheDriveLatched) {
  SkipProbe skip(3, 200);
  skip.begin(1);
  auto f = feedback();
  EXPECT_FALSE(skip.watch(f, kXandZ));  // not moving yet
  skip.start_moving();
  f[1].probe = ProbeSeen::latched;  // not on the input
  EXPECT_FALSE(skip.watch(f, kXandZ));
  f[2].probe = ProbeSeen::latched;
  f[2].probe_pos = 29.5;
  ASSERT_TRUE(skip.watch(f, kXandZ));
  EXPECT_EQ(skip.phase(), SkipPhase::stopping);
  EXPECT_TRUE(skip.skipped());
  const SkipProbe::Position end{1.0, 2.0, 3.0};
  const SkipProbe::Position at = skip.where(end);
  EXPECT_DOUBLE_EQ(at[0], 10.0);
  EXPECT_DOUBLE_EQ(at[1], 20.0);
  EXPECT_DOUBLE_EQ(at[2], 29.5);
  EXPECT_DOUBLE_EQ(at[3], 0.0);         // the spindle's feedback is no axis of the move
  EXPECT_FALSE(skip.watch(f, kXandZ));  // once
}

TEST(SkipProbe, WithoutTheSignalTheMoveEndsWhereItWasProgrammed) {
  SkipProbe skip(3, 200);
  skip.begin(1);
  skip.start_moving();
  EXPECT_FALSE(skip.watch(feedback(), kXandZ));
  const SkipProbe::Position end{1.0, 2.0, 3.0};
  EXPECT_FALSE(skip.skipped());
  EXPECT_EQ(skip.where(end), end);
}

// G31 P (decision 92): the PLC's skip signal. It must be seen off before the move starts; the
// first cycle it is on stops the move where the feedback stands; the PLC gone stops it too,
// with an alarm and no skip.
TEST(SkipProbe, APlcSignalStopsTheMoveWhereTheFeedbackStandsWhenItIsSeen) {
  SkipProbe skip(3, 2);
  skip.begin_signal(3);
  auto f = feedback();
  EXPECT_EQ(skip.arm_signal(true, false), SkipArming::waiting);
  EXPECT_EQ(skip.arm_signal(true, false), SkipArming::waiting);
  ASSERT_EQ(skip.arm_signal(true, false), SkipArming::alarm);
  EXPECT_EQ(skip.alarm().number, kAlarmProbeNotArmed);
  EXPECT_STREQ(skip.alarm().text.data(),
               "G31 P3: the PLC's skip signal G0014.2 is on before the move");
  skip.begin_signal(3);
  ASSERT_EQ(skip.arm_signal(false, false), SkipArming::armed);
  skip.start_moving();
  EXPECT_FALSE(skip.watch_signal(f, false, false));
  f[1].act = -12.5;
  ASSERT_TRUE(skip.watch_signal(f, true, false));
  EXPECT_EQ(skip.phase(), SkipPhase::stopping);
  EXPECT_TRUE(skip.skipped());
  EXPECT_FALSE(skip.lost());
  const SkipProbe::Position at = skip.where(SkipProbe::Position{});
  EXPECT_EQ(at[0], 10.0);
  EXPECT_EQ(at[1], -12.5);
  EXPECT_EQ(at[2], 30.0);
  EXPECT_EQ(at[3], 0.0);                            // not an axis of the channel
  EXPECT_FALSE(skip.watch_signal(f, true, false));  // once
}

TEST(SkipProbe, ThePlcGoneUnderAG31PStopsItWithAnAlarm) {
  SkipProbe skip(3, 200);
  skip.begin_signal(1);
  ASSERT_EQ(skip.arm_signal(false, true), SkipArming::alarm);
  EXPECT_EQ(skip.alarm().number, interp::alarm::kSkipInput);
  skip.begin_signal(1);
  ASSERT_EQ(skip.arm_signal(false, false), SkipArming::armed);
  skip.start_moving();
  ASSERT_TRUE(skip.watch_signal(feedback(), false, true));
  EXPECT_TRUE(skip.lost());
  EXPECT_FALSE(skip.skipped());
  EXPECT_EQ(skip.alarm().number, interp::alarm::kSkipInput);
  EXPECT_STREQ(skip.alarm().text.data(), "G31 P1: the PLC node is gone");
}

}  // namespace
}  // namespace mcnc::coordination
