// G04 I and G04 PS blocks: the machine state each reads, and the alarms of a missing input or
// spindle and of a condition that never comes.
#include "channel/coordination/condition_block.hpp"

#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

namespace mcnc::coordination {
namespace {

constexpr ConditionSetup kSetup{10.0, 0.005, 0.001};  // 5-cycle speed timeout

ConditionSpec input(int port, bool on, double timeout_s = -1.0, double dwell_s = -1.0) {
  ConditionSpec s;
  s.input = true;
  s.port = port;
  s.on = on;
  s.timeout_s = timeout_s;
  s.dwell_s = dwell_s;
  return s;
}

ConditionSpec speed(int spindle, double rpm, double dwell_s = -1.0) {
  ConditionSpec s;
  s.input = false;
  s.spindle = spindle;
  s.rpm = rpm;
  s.dwell_s = dwell_s;
  return s;
}

TEST(ConditionBlock, AnInputEndsTheBlockWhenItsBitIsInTheWantedState) {
  ConditionBlock on(input(3, true), kSetup);
  ConditionInputs in;
  in.input_bit = 12;
  EXPECT_EQ(on.step(in), ConditionStep::waiting);
  in.plc_inputs = std::uint64_t{1} << 12;
  EXPECT_EQ(on.step(in), ConditionStep::done);
  ConditionBlock off(input(3, false), kSetup);
  EXPECT_EQ(off.step(in), ConditionStep::waiting);
  in.plc_inputs = 0;
  EXPECT_EQ(off.step(in), ConditionStep::done);
}

TEST(ConditionBlock, APortThePlcLacksOrThePlcGoneIsAnAlarm) {
  ConditionBlock block(input(3, false), kSetup);
  ConditionInputs in;
  ASSERT_EQ(block.step(in), ConditionStep::alarm);
  EXPECT_EQ(block.alarm().number, interp::alarm::kInputPort);
  EXPECT_STREQ(block.alarm().text.data(), "G04 I-3: the PLC has no input with this port");
  in.input_bit = 2;
  in.plc_gone = true;
  ASSERT_EQ(block.step(in), ConditionStep::alarm);
  EXPECT_STREQ(block.alarm().text.data(), "G04 I-3: the PLC node is gone");
}

TEST(ConditionBlock, ATimeoutIsAnAlarmUnlessADwellEndsTheBlock) {
  ConditionInputs in;
  in.input_bit = 0;
  ConditionBlock alarm(input(1, true, 0.003), kSetup);
  EXPECT_EQ(alarm.step(in), ConditionStep::waiting);
  EXPECT_EQ(alarm.step(in), ConditionStep::waiting);
  ASSERT_EQ(alarm.step(in), ConditionStep::alarm);
  EXPECT_EQ(alarm.alarm().number, kAlarmInputTimeout);
  EXPECT_STREQ(alarm.alarm().text.data(), "G04 I1: input 1 not on within 0.003 s (J)");
  ConditionBlock dwell(input(1, true, 0.003, 0.010), kSetup);
  EXPECT_EQ(dwell.step(in), ConditionStep::waiting);
  EXPECT_EQ(dwell.step(in), ConditionStep::waiting);
  EXPECT_EQ(dwell.step(in), ConditionStep::done);  // timed out, the dwell ends it
}

TEST(ConditionBlock, ASpindleSpeedWithinTheArrivalWidthInEitherDirectionEndsTheBlock) {
  ConditionBlock block(speed(1, 1000.0), kSetup);
  ConditionInputs in;
  in.spindle_present = true;
  in.spindle_vel = -6000.0 * 0.9;  // 900 rpm, reverse
  EXPECT_EQ(block.step(in), ConditionStep::waiting);
  in.spindle_vel = -6000.0 * 0.99;  // 990 rpm: within 10
  EXPECT_EQ(block.step(in), ConditionStep::done);
}

TEST(ConditionBlock, ASpindleWithoutFeedbackOrNeverAtSpeedIsAnAlarm) {
  ConditionBlock missing(speed(2, 500.0), kSetup);
  ASSERT_EQ(missing.step(ConditionInputs{}), ConditionStep::alarm);
  EXPECT_EQ(missing.alarm().number, interp::alarm::kNoSuchSpindle);
  ConditionBlock slow(speed(1, 500.0), kSetup);
  ConditionInputs in;
  in.spindle_present = true;
  for (int n = 1; n < 5; ++n) {
    ASSERT_EQ(slow.step(in), ConditionStep::waiting) << n;
  }
  ASSERT_EQ(slow.step(in), ConditionStep::alarm);
  EXPECT_EQ(slow.alarm().number, kAlarmSpeedTimeout);
}

}  // namespace
}  // namespace mcnc::coordination
