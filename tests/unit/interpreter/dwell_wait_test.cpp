// G04 PSn= (spec dafeng L2747-2782): the wait for a spindle's actual speed the interpreter
// emits, its forms (n omitted: spindle 1; with a dwell time), its read-ahead barrier and its
// alarms; G04 I beside it.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

TEST(InterpDwellWait, PsWaitsForTheSpindlesSpeedAndStopsTheReadAhead) {
  const RunResult r = run_ok("M03 S3000\nG04 PS3000\nG04 PS2=0 X1.5\nG04 PS1=500 P200\nM30\n");
  const auto waits = r.of(Op::wait_spindle);
  ASSERT_EQ(waits.size(), 3u);
  EXPECT_EQ(waits[0].spindle, 1);
  EXPECT_NEAR(waits[0].rpm, 3000.0, 1e-12);
  EXPECT_LT(waits[0].dwell_s, 0.0);  // no dwell: only the speed ends it
  EXPECT_TRUE(waits[0].barrier);
  EXPECT_EQ(waits[1].spindle, 2);
  EXPECT_NEAR(waits[1].rpm, 0.0, 1e-12);  // PS0: wait for the stop
  EXPECT_NEAR(waits[1].dwell_s, 1.5, 1e-12);
  EXPECT_EQ(waits[2].spindle, 1);
  EXPECT_NEAR(waits[2].dwell_s, 0.2, 1e-12);  // P in ms
  EXPECT_TRUE(r.of(Op::dwell).empty());
}

TEST(InterpDwellWait, PsAlarms) {
  run_alarm("G04 PS-5\nM30\n", alarm::kBadWordValue, 1);
  run_alarm("G04 PS500 I2\nM30\n", alarm::kGroupConflict, 1);
  InterpreterConfig one = lathe();
  one.spindles = 1;
  run_alarm("G04 PS2=500\nM30\n", alarm::kNoSuchSpindle, 1, -1, one);
}

TEST(InterpDwellWait, InputWaitStillEmitsWaitInput) {
  const RunResult r = run_ok("G04 I-3 J2 K0.5\nM30\n");
  const auto waits = r.of(Op::wait_input);
  ASSERT_EQ(waits.size(), 1u);
  EXPECT_EQ(waits[0].input, 3);
  EXPECT_FALSE(waits[0].input_on);
  EXPECT_NEAR(waits[0].timeout_s, 2.0, 1e-12);
  EXPECT_NEAR(waits[0].width_s, 0.5, 1e-12);
}

}  // namespace
}  // namespace mcnc::interp::test
