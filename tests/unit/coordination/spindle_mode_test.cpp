// M18 / M17: position control takes the spindle over only at rest, from C within one turn; a
// spindle that never rests, a following spindle and one without C axis are alarms.
#include "channel/coordination/spindle_mode.hpp"

#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

namespace mcnc::coordination {
namespace {

constexpr double kWidth = 0.01;
constexpr double kDt = 0.001;

SpindleModeInputs at(double act) {
  return SpindleModeInputs{true, act, false};
}

TEST(SpindleMode, TakesTheSpindleOverAfterFiveStillCyclesFromCWithinOneTurn) {
  SpindleMode mode(kWidth, kDt);
  mode.begin(true);
  for (int n = 1; n <= SpindleMode::kStillCycles; ++n) {
    ASSERT_EQ(mode.step(at(725.0)), SpindleModeStep::waiting) << n;
  }
  ASSERT_EQ(mode.step(at(725.0)), SpindleModeStep::done);
  EXPECT_TRUE(mode.position_control());
  EXPECT_DOUBLE_EQ(mode.c_base(), 720.0);
  EXPECT_DOUBLE_EQ(mode.c_start(), 5.0);
  // Negative positions: whole turns below.
  SpindleMode back(kWidth, kDt);
  back.begin(true);
  SpindleModeStep s = SpindleModeStep::waiting;
  for (int n = 0; n < 10 && s == SpindleModeStep::waiting; ++n) {
    s = back.step(at(-10.0));
  }
  ASSERT_EQ(s, SpindleModeStep::done);
  EXPECT_DOUBLE_EQ(back.c_base(), -360.0);
  EXPECT_DOUBLE_EQ(back.c_start(), 350.0);
}

TEST(SpindleMode, ACoastingSpindleStartsTheCountAgain) {
  SpindleMode mode(kWidth, kDt);
  mode.begin(true);
  double act = 0.0;
  for (int n = 0; n < 4; ++n) {
    ASSERT_EQ(mode.step(at(act)), SpindleModeStep::waiting);
  }
  act += 0.5;  // it moved more than the width in one cycle
  ASSERT_EQ(mode.step(at(act)), SpindleModeStep::waiting);
  for (int n = 1; n < SpindleMode::kStillCycles; ++n) {
    ASSERT_EQ(mode.step(at(act)), SpindleModeStep::waiting) << n;
  }
  EXPECT_EQ(mode.step(at(act)), SpindleModeStep::done);
}

TEST(SpindleMode, ASpindleThatNeverRestsIsAnAlarmAfterTenSeconds) {
  SpindleMode mode(kWidth, kDt);
  mode.begin(true);
  const int limit = static_cast<int>(SpindleMode::kRestTimeout / kDt);
  for (int n = 0; n < limit; ++n) {
    ASSERT_EQ(mode.step(at(n * 1.0)), SpindleModeStep::waiting) << n;
  }
  ASSERT_EQ(mode.step(at(limit * 1.0)), SpindleModeStep::alarm);
  EXPECT_EQ(mode.alarm().number, kAlarmSpindleNotAtRest);
  EXPECT_FALSE(mode.position_control());
}

TEST(SpindleMode, AFollowingSpindleOrNoCAxisIsAnAlarm) {
  SpindleMode mode(kWidth, kDt);
  mode.begin(true);
  ASSERT_EQ(mode.step(SpindleModeInputs{true, 0.0, true}), SpindleModeStep::alarm);
  EXPECT_EQ(mode.alarm().number, kAlarmSlaveSpindle);
  mode.begin(false);  // M17 too needs the C axis
  ASSERT_EQ(mode.step(SpindleModeInputs{false, 0.0, false}), SpindleModeStep::alarm);
  EXPECT_EQ(mode.alarm().number, interp::alarm::kSpindleControl);
}

TEST(SpindleMode, M17EndsPositionControlAndM18UnderItEndsAtOnce) {
  SpindleMode mode(kWidth, kDt);
  mode.begin(true);
  SpindleModeStep s = SpindleModeStep::waiting;
  for (int n = 0; n < 10 && s == SpindleModeStep::waiting; ++n) {
    s = mode.step(at(90.0));
  }
  ASSERT_TRUE(mode.position_control());
  mode.begin(true);
  EXPECT_EQ(mode.step(at(4000.0)), SpindleModeStep::done);  // no wait, no new base
  EXPECT_DOUBLE_EQ(mode.c_base(), 0.0);
  mode.begin(false);
  EXPECT_EQ(mode.step(at(90.0)), SpindleModeStep::done);
  EXPECT_FALSE(mode.position_control());
}

}  // namespace
}  // namespace mcnc::coordination
