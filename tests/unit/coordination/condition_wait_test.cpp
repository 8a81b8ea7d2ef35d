// The wait of G04 I and G04 PS, cycle by cycle: the condition with its width, the dwell time
// ORed with it, the timeout, and which wins when they fall in one cycle.
#include "channel/coordination/condition_wait.hpp"

#include <gtest/gtest.h>

namespace mcnc::coordination {
namespace {

constexpr double kDt = 0.001;

// Cycles until the wait ends, with the condition holding from cycle `from` on (1-based; 0:
// never); the outcome in `outcome`.
int cycles_to_end(ConditionWaitLimits limits, int from, WaitOutcome& outcome, int limit = 100000) {
  ConditionWait wait(limits, kDt);
  for (int n = 1; n <= limit; ++n) {
    outcome = wait.step(from > 0 && n >= from);
    if (outcome != WaitOutcome::waiting) {
      return n;
    }
  }
  return -1;
}

TEST(ConditionWait, EndsInTheFirstCycleTheConditionHolds) {
  WaitOutcome o{};
  EXPECT_EQ(cycles_to_end({}, 1, o), 1);
  EXPECT_EQ(o, WaitOutcome::met);
  EXPECT_EQ(cycles_to_end({}, 250, o), 250);
  EXPECT_EQ(o, WaitOutcome::met);
}

TEST(ConditionWait, TheConditionMustHoldForItsWidthInARow) {
  ConditionWaitLimits limits;
  limits.width_s = 0.05;  // 50 cycles
  WaitOutcome o{};
  EXPECT_EQ(cycles_to_end(limits, 10, o), 59);
  EXPECT_EQ(o, WaitOutcome::met);
  // A drop-out starts the width again.
  ConditionWait wait(limits, kDt);
  for (int n = 1; n <= 40; ++n) {
    ASSERT_EQ(wait.step(true), WaitOutcome::waiting);
  }
  ASSERT_EQ(wait.step(false), WaitOutcome::waiting);
  for (int n = 1; n < 50; ++n) {
    ASSERT_EQ(wait.step(true), WaitOutcome::waiting) << n;
  }
  EXPECT_EQ(wait.step(true), WaitOutcome::met);
}

TEST(ConditionWait, ADwellTimeEndsTheWaitAsTheConditionDoes) {
  ConditionWaitLimits limits;
  limits.dwell_s = 0.2;
  limits.timeout_s = 0.5;
  WaitOutcome o{};
  EXPECT_EQ(cycles_to_end(limits, 0, o), 200);
  EXPECT_EQ(o, WaitOutcome::dwell_over);
  EXPECT_EQ(cycles_to_end(limits, 120, o), 120);  // whichever comes first
  EXPECT_EQ(o, WaitOutcome::met);
}

TEST(ConditionWait, TimesOutAfterItsTimeoutAndStaysTimedOutUnlessTheConditionCameInTime) {
  ConditionWaitLimits limits;
  limits.timeout_s = 0.3;
  WaitOutcome o{};
  EXPECT_EQ(cycles_to_end(limits, 0, o), 300);
  EXPECT_EQ(o, WaitOutcome::timed_out);
  // The condition wins in the cycle the time runs out.
  EXPECT_EQ(cycles_to_end(limits, 300, o), 300);
  EXPECT_EQ(o, WaitOutcome::met);
  ConditionWait wait(limits, kDt);
  for (int n = 1; n <= 300; ++n) {
    (void)wait.step(false);
  }
  EXPECT_EQ(wait.step(true), WaitOutcome::timed_out);  // too late
  EXPECT_NEAR(wait.waited_s(), 0.3, 1e-12);
}

TEST(ConditionWait, WithoutATimeoutItWaitsForEver) {
  WaitOutcome o{};
  EXPECT_EQ(cycles_to_end({}, 0, o, 100000), -1);
  EXPECT_EQ(o, WaitOutcome::waiting);
}

}  // namespace
}  // namespace mcnc::coordination
