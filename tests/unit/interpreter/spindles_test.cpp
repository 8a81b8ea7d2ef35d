// Spindles: S, Sn=, S P, M03/M04/M05/M19 of spindles 1-3, M05 PA/PN, G96/G97/G50 S, SP
// (spec dafeng §2.7, GSK D2-22).
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

TEST(InterpSpindles, FormsOfSpindleOneAreEqual) {
  for (const char* block : {"M03 S500", "M03 S1=500", "M03 S500 P1", "S500 M03"}) {
    RunResult r = run_ok(std::string(block) + "\nM30\n");
    auto s = r.of(Op::spindle);
    ASSERT_EQ(s.size(), 1u) << block;
    EXPECT_EQ(s[0].spindle, 1) << block;
    EXPECT_EQ(s[0].channel, 0) << block;
    EXPECT_EQ(s[0].spindle_direction, SpindleDirection::cw) << block;
    EXPECT_NEAR(s[0].rpm, 500, 1e-9) << block;
  }
}

TEST(InterpSpindles, MCodesOfSpindlesTwoAndThree) {
  RunResult r = run_ok("M103 S2=1500\nM204 S3=50\nM205\nM104 S1500 P2\nM30\n");
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].spindle, 2);
  EXPECT_EQ(s[0].spindle_direction, SpindleDirection::cw);
  EXPECT_NEAR(s[0].rpm, 1500, 1e-9);
  EXPECT_EQ(s[1].spindle, 3);
  EXPECT_EQ(s[1].spindle_direction, SpindleDirection::ccw);
  EXPECT_NEAR(s[1].rpm, 50, 1e-9);
  EXPECT_EQ(s[2].spindle, 3);
  EXPECT_EQ(s[2].spindle_direction, SpindleDirection::stop);
  EXPECT_EQ(s[3].spindle, 2);
  EXPECT_EQ(s[3].spindle_direction, SpindleDirection::ccw);
}

TEST(InterpSpindles, SpeedChangeOfATurningSpindleIsEmitted) {
  RunResult r = run_ok("M03 S500\nS800\nM05\nS900\nM30\n");
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 3u);  // S900 of a stopped spindle is only remembered
  EXPECT_NEAR(s[1].rpm, 800, 1e-9);
  EXPECT_EQ(s[1].spindle_direction, SpindleDirection::cw);
  EXPECT_EQ(s[2].spindle_direction, SpindleDirection::stop);
}

TEST(InterpSpindles, SpeedOfAnotherChannelsSpindle) {
  // S_ Paab: aa = channel 2, b = spindle 1.
  RunResult r = run_ok("S700 P21\nM30\n");
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].channel, 2);
  EXPECT_EQ(s[0].spindle, 1);
  EXPECT_EQ(s[0].spindle_direction, SpindleDirection::keep);
  EXPECT_NEAR(s[0].rpm, 700, 1e-9);
}

TEST(InterpSpindles, MCodeAndPNamingDifferentSpindlesIsAnAlarm) {
  run_alarm("M03 S500\nM103 S500 P3\nM30\n", alarm::kBadWordValue, 2);
}

TEST(InterpSpindles, OrientedStop) {
  RunResult r = run_ok("M03 S100\nM05 PA45\nM03\nM05 PN4\nM30\n");
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_TRUE(s[1].has_angle);
  EXPECT_NEAR(s[1].angle, 45, 1e-9);
  EXPECT_EQ(s[3].divisions, 4);
}

TEST(InterpSpindles, ConstantSurfaceSpeedWithClamp) {
  RunResult r = run_ok("G50 S2000\nG96 S150 M03\nG97 S800\nM30\n", gsk());
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_TRUE(s[0].css);
  EXPECT_NEAR(s[0].surface, 150, 1e-9);
  EXPECT_NEAR(s[0].max_rpm, 2000, 1e-9);
  EXPECT_FALSE(s[1].css);
  EXPECT_NEAR(s[1].rpm, 800, 1e-9);
  EXPECT_EQ(s[1].spindle_direction, SpindleDirection::cw);
}

TEST(InterpSpindles, G96WithoutClamp) {
  RunResult r = run_ok("G96 S314 M03\nM30\n");
  auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_TRUE(s[0].css);
  EXPECT_NEAR(s[0].surface, 314, 1e-9);
  EXPECT_NEAR(s[0].max_rpm, 0, 1e-9);
}

TEST(InterpSpindles, SpindleSelect) {
  RunResult r = run_ok("SP2\nM30\n");
  auto s = r.of(Op::spindle_select);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].spindle, 2);
}

TEST(InterpSpindles, NegativeSIsAnAlarm) {
  run_alarm("M03 S100\nS-5\nM30\n", alarm::kBadWordValue, 2);
}

TEST(InterpSpindles, FeedPerRevolution) {
  RunResult r = run_ok("G99 G01 X10 F0.2\nG98 G01 X20 F100\nM30\n");
  auto l = r.of(Op::linear);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[0].feed_mode, FeedMode::per_rev);
  EXPECT_NEAR(l[0].feed, 0.2, 1e-12);
  EXPECT_EQ(l[1].feed_mode, FeedMode::per_min);
}

TEST(InterpSpindles, SystemBFeedCodes) {
  InterpreterConfig c = lathe();
  c.system = GCodeSystem::b;
  RunResult r = run_ok("G95 G01 X10 F0.2\nG94 G01 X20 F100\nM30\n", c);
  auto l = r.of(Op::linear);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[0].feed_mode, FeedMode::per_rev);
  EXPECT_EQ(l[1].feed_mode, FeedMode::per_min);
}

InterpreterConfig one_spindle() {
  InterpreterConfig c = lathe();
  c.spindles = 1;
  return c;
}

// A spindle of this channel named by a number it does not have is an alarm at the word that
// names it, whatever form names it (before, `S180 P4` was only remembered: no command, no alarm).
TEST(InterpSpindles, SpindleTheChannelDoesNotHave) {
  RunResult r = run_alarm("M03 S500\nS180 P4\nM30\n", alarm::kNoSuchSpindle, 2, 6, one_spindle());
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_NE(r.alarm->text.find("spindle 4"), std::string::npos) << r.alarm->text;
  run_alarm("G00 X10\nS4=180\nM30\n", alarm::kNoSuchSpindle, 2, 1, one_spindle());
  run_alarm("G00 X10\nM303 S180\nM30\n", alarm::kNoSuchSpindle, 2, 1, one_spindle());
  run_alarm("G00 X10\nSP2\nM30\n", alarm::kNoSuchSpindle, 2, 1, one_spindle());
  run_alarm("G00 X10\nM103\nM30\n", alarm::kNoSuchSpindle, 2, 1, one_spindle());
  InterpreterConfig none = lathe();
  none.spindles = 0;
  run_alarm("G00 X10\nS180 P1\nM30\n", alarm::kNoSuchSpindle, 2, 6, none);
}

TEST(InterpSpindles, SpindlesTheChannelHasAndOthersChannels) {
  InterpreterConfig two = lathe();
  two.spindles = 2;
  RunResult r = run_ok("M03 S500 P1\nM103 S2=800\nS180 P2\nSP2\nS300 P24\nM30\n", two);
  const auto s = r.of(Op::spindle);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[2].spindle, 2);
  EXPECT_NEAR(s[2].rpm, 180, 1e-9);
  EXPECT_EQ(s[3].channel, 2);  // another channel's spindle 4: that channel's to check
  EXPECT_EQ(s[3].spindle, 4);
  // Without a spindle count (`mcnc interp` without `spindles`) every number 1-9 is taken.
  run_ok("S180 P4\nM30\n");
}

}  // namespace
}  // namespace mcnc::interp::test
