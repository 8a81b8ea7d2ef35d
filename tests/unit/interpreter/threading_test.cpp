// Threading G32/G34/G32.1/G32.2/G32.3 and the single cycles G90/G92/G94 (spec dafeng §2.2
// L850-1203 and §2.5 L2199-2376; gsk A.6.26-A.6.28, A.6.37-A.6.40, D2-1..D2-5, D2-33, D2-34).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

TEST(InterpThreading, G32LeadFromFOrThreadsPerInch) {
  RunResult r = run_ok("G00 X20 Z5\nG32 W-20 F1.5\nG00 U10\nG00 Z5\nG32 X20 W-20 I8\nM30\n");
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].lead, 1.5);
  EXPECT_AT(t[0], 10, -15);
  EXPECT_DOUBLE_EQ(t[1].lead, 25.4 / 8);
  EXPECT_FALSE(t[0].continuous);
  EXPECT_FALSE(t[1].continuous);  // a rapid in between: the thread waits for the signal again
}

TEST(InterpThreading, InchLead) {
  RunResult r = run_ok("G20\nG00 X1 Z0.2\nG32 W-1 F0.1\nM30\n");
  EXPECT_NEAR(r.of(Op::thread)[0].lead, 2.54, 1e-12);
}

TEST(InterpThreading, StartAngleDegreesDafengThousandthsGsk) {
  RunResult d = run_ok("G00 X20 Z5\nG32 W-10 F1 Q450\nM30\n");
  EXPECT_DOUBLE_EQ(d.of(Op::thread)[0].start_angle, 90.0);  // modulo 360 (spec L869)
  RunResult g = run_ok("G00 X20 Z5\nG32 W-10 F1 Q90000\nM30\n", gsk());
  EXPECT_DOUBLE_EQ(g.of(Op::thread)[0].start_angle, 90.0);
}

// gsk D2-33: two G32 blocks join; only the first block's Q matters to the control, which the
// continuous flag tells it.
TEST(InterpThreading, ContinuousThreadJoinsBlocksWithoutMotionBetween) {
  RunResult r = run_ok("G00 X50 Z5\nG32 Z-20 F2 Q0\n#1=1\nG32 X40 Z-30 F2 Q90000\nM30\n", gsk());
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_FALSE(t[0].continuous);
  EXPECT_TRUE(t[1].continuous);
}

TEST(InterpThreading, NonMotionBlockBetweenThreadsBreaksContinuity) {
  // spec L915-917: a G04, M, S or T block makes the next G32 wait for the one-rev signal.
  RunResult r = run_ok("G00 X50 Z5\nG32 W-10 F2\nM08\nG32 W-10\nM30\n");
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_FALSE(t[1].continuous);
  EXPECT_DOUBLE_EQ(t[1].lead, 2.0);  // the lead is modal
}

TEST(InterpThreading, LeadAlarms) {
  run_alarm("G00 X20 Z5\nG32 W-10\nM30\n", alarm::kThreadLead, 2);
  run_alarm("G00 X20 Z5\nG32 W-10 F1 I8\nM30\n", alarm::kWordNotAllowed, 2);
  run_alarm("G00 X20 Z5\nG32 W-10 I0\nM30\n", alarm::kThreadLead, 2);
}

TEST(InterpThreading, G34LeadChangeAndItsLimit) {
  RunResult r = run_ok("G00 X30 Z0\nG34 W-30 F4 K0.2\nM30\n");
  EXPECT_DOUBLE_EQ(r.of(Op::thread)[0].lead_change, 0.2);
  // gsk D2-34: F2 reaches lead 0 after 4 mm, the thread is 10 long.
  run_alarm("G00 X30 Z0\nG34 W-10 F2 R-0.5\nM30\n", alarm::kThreadLead, 2, -1, gsk());
  run_alarm("G00 X30 Z0\nG34 W-10 F2\nM30\n", alarm::kWordNotAllowed, 2);
}

TEST(InterpThreading, G32_1NeedsSpeedAndHasNoStartAngle) {
  RunResult r = run_ok("G00 X20 Z5\nG32.1 W-20 F20 S30\nM30\n");
  EXPECT_DOUBLE_EQ(r.of(Op::thread)[0].rpm, 30.0);
  run_alarm("G00 X20 Z5\nG32.1 W-20 F20\nM30\n", alarm::kWordNotAllowed, 2);
  run_alarm("G00 X20 Z5\nG32.1 W-20 F20 S30 Q10\nM30\n", alarm::kWordNotAllowed, 2);
}

// Dafeng L1143-1157: G32.3 W-10 R20 F2 from X30 Z5, a CCW arc thread.
TEST(InterpThreading, ArcThreadCarriesItsCentre) {
  RunResult r = run_ok("G00 X30 Z5\nG32.3 W-10 R20 F2\nM30\n");
  const Command t = r.of(Op::thread)[0];
  EXPECT_TRUE(t.thread_arc);
  EXPECT_EQ(t.direction, ArcDirection::ccw);
  EXPECT_AT(t, 15, -5);
  // Chord along -Z from (Z5, X15) to (Z-5, X15), R20 CCW: centre left of the chord.
  const double h = std::sqrt(400.0 - 25.0);
  EXPECT_NEAR(t.center[0], 0.0, 1e-9);
  EXPECT_NEAR(t.center[1], 15.0 - h, 1e-9);
}

TEST(InterpThreading, GskRunOutOverTheLastK) {
  // G32 W-20 F2 J1 K3 from X20 Z0: thread to Z-17, then the run-out to Z-20 rising 1 (radius).
  RunResult r = run_ok("G00 X20 Z0\nG32 W-20 F2 J1 K3\nM30\n", gsk());
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_AT(t[0], 10, -17);
  EXPECT_AT(t[1], 11, -20);
  EXPECT_TRUE(t[1].continuous);
}

TEST(InterpThreading, DafengPullOutJIsNotYetAvailable) {
  run_alarm("G00 X20 Z0\nG32 W-20 F2 J1\nM30\n", alarm::kNotInThisVersion, 2);
}

// ---- single cycles

TEST(InterpSingleCycles, G92MultiStartRepeatsPerStart) {
  RunResult r = run_ok("G00 X60 Z5\nG92 X48 Z-30 F4 L2\nM30\n");
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].start_angle, 0.0);
  EXPECT_DOUBLE_EQ(t[1].start_angle, 180.0);
  EXPECT_EQ(r.of(Op::rapid).size(), 1u + 6u);
}

TEST(InterpSingleCycles, G92ChamferOutFromParameterAndJ) {
  InterpreterConfig c = lathe();
  c.thread_chamfer_leads = 1.0;
  RunResult r = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2\nM30\n", c);
  auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_AT(t[0], 24, -28);  // the chamfer starts one lead before the end
  EXPECT_AT(t[1], 26, -30);  // and rises one lead at 45 degrees
  EXPECT_TRUE(t[1].continuous);
  RunResult j = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2 J3\nM30\n");
  t = j.of(Op::thread);
  EXPECT_AT(t[0], 24, -27);
  EXPECT_AT(t[1], 27, -30);
  // GSK: J the rise (radius), K the length along Z.
  RunResult g = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2 J1 K4\nM30\n", gsk());
  t = g.of(Op::thread);
  EXPECT_AT(t[0], 24, -26);
  EXPECT_AT(t[1], 25, -30);
}

TEST(InterpSingleCycles, G92Alarms) {
  run_alarm("G00 X60 Z5\nG92 X48 Z-30 F2 J40\nM30\n", alarm::kCycleValue, 2);
  run_alarm("G00 X60 Z5\nG92 X48 Z-30 F2 L0\nM30\n", alarm::kCycleValue, 2);
  run_alarm("G00 X60 Z5\nG92 X48 Z-30\nM30\n", alarm::kThreadLead, 2);
}

// GSK G92.1 (gsk A.6.29): the G92 cycle with the spindle interpolated at S, no chamfer-out (the
// feed and the spindle stop together), one pass per start; modal like G92.
TEST(InterpSingleCycles, GskG92_1InterpolatesTheSpindle) {
  InterpreterConfig c = gsk();
  c.thread_chamfer_leads = 1.0;  // not G92.1's
  RunResult r = run_ok("G00 X60 Z5\nG92.1 X48 Z-30 F2 L2 S300\nX47\nM30\n", c);
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 3u);  // two starts, then the modal block's one
  for (const Command& th : t) {
    EXPECT_NEAR(th.rpm, 300, 1e-12);
    EXPECT_NEAR(th.lead, 2, 1e-12);
    EXPECT_NEAR(th.to[1], -30, 1e-12);
  }
  EXPECT_AT(t[0], 24, -30);
  EXPECT_DOUBLE_EQ(t[1].start_angle, 180.0);
  EXPECT_AT(t[2], 23.5, -30);  // the modal block X47
}

// gsk A.6.29: F < 0 is a left-hand thread: the same moves at the lead |F|, the interpolated
// spindle turning the negative way. The hand is modal with the lead, and a positive F ends it.
TEST(InterpSingleCycles, GskG92_1NegativeLeadCutsALeftHandThread) {
  RunResult r =
      run_ok("G00 X60 Z5\nG92.1 X48 Z-30 F-2 L2 S300\nX47\nX46.5 F2\nG01 X60 F0.2\nM30\n", gsk());
  const auto t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 4u);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(t[i].lead, 2, 1e-12) << i;
    EXPECT_NEAR(t[i].rpm, 300, 1e-12) << i;
    EXPECT_EQ(t[i].left_hand, i < 3) << i;  // the block with F2 is right-hand again
  }
  EXPECT_AT(t[0], 24, -30);
  EXPECT_DOUBLE_EQ(t[1].start_angle, 180.0);
  EXPECT_AT(t[2], 23.5, -30);
  // G32.1 takes the signed F too (gsk A.6.39); G92 (the encoder follows the spindle) and G01 do
  // not.
  r = run_ok("G00 X20 Z5\nG32.1 W-20 F-1.5 S30\nM30\n", gsk());
  ASSERT_EQ(r.of(Op::thread).size(), 1u);
  EXPECT_TRUE(r.of(Op::thread)[0].left_hand);
  EXPECT_NEAR(r.of(Op::thread)[0].lead, 1.5, 1e-12);
  run_alarm("G00 X60 Z5\nG92 X48 Z-30 F-2\nM30\n", alarm::kNegativeFeed, 2, -1, gsk());
  run_alarm("G00 X60 Z5\nG01 X48 Z-30 F-2\nM30\n", alarm::kNegativeFeed, 2, -1, gsk());
}

TEST(InterpSingleCycles, GskG92_1Alarms) {
  const ExpectedAlarm cases[] = {
      {"G00 X60 Z5\nG92.1 X48 Z-30 F2\nM30\n", alarm::kWordNotAllowed, 2},
      {"G00 X60 Z5\nG92.1 X48 Z-30 F2 S300 K3\nM30\n", alarm::kWordNotAllowed, 2},
  };
  expect_alarms(cases, gsk());
  // The Dafeng manual has no G92.1 in system A (its G92.1 is system B's G50.3).
  run_alarm("G00 X60 Z5\nG92.1 X48 Z-30 F2 S300\nM30\n", alarm::kUnsupportedG, 2);
}

// Dafeng G92 P, "thread feed start height" (dafeng L2285): the spec's decision D29 ignores it
// with a warning (decision 87). The cycle is G92's without P, and the warning says where.
TEST(InterpSingleCycles, DafengG92PIsIgnoredWithAWarning) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G00 X60 Z5\nG92 X48 Z-30 F2 P1.5\nX47\nM30\n", "test.nc"));
  RunResult with_p = drain(in);
  ASSERT_FALSE(with_p.alarm.has_value()) << with_p.alarm->text;
  const std::vector<ProgramAlarm> warnings = in.take_warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].line, 2);
  EXPECT_EQ(warnings[0].column, 17);
  EXPECT_NE(warnings[0].text.find("G92 P1.5"), std::string::npos) << warnings[0].text;
  EXPECT_TRUE(in.take_warnings().empty());  // taken once
  RunResult without = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2\nX47\nM30\n");
  ASSERT_EQ(with_p.commands.size(), without.commands.size());
  for (std::size_t i = 0; i < without.commands.size(); ++i) {
    EXPECT_EQ(with_p.commands[i].op, without.commands[i].op) << i;
    EXPECT_EQ(with_p.commands[i].to, without.commands[i].to) << i;
  }
}

// GSK thread repair (gsk A.6.41, L1279-1312): the pass starts at the angle that puts the groove
// through the recorded Z and spindle angle.
InterpreterConfig gsk_repair(double z, double degrees) {
  InterpreterConfig c = gsk();
  c.thread_repair = true;
  c.thread_repair_recorded = true;
  c.thread_repair_z = z;
  c.thread_repair_degrees = degrees;
  return c;
}

TEST(InterpSingleCycles, GskThreadRepairPutsTheGrooveThroughTheRecordedPoint) {
  // From Z5 to the recorded Z-10.5 are 15.5 mm, 7.75 revolutions of lead 2: the thread starts
  // three quarters of a turn before the recorded 30 degrees.
  RunResult r = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2 P1\nX47\nM30\n", gsk_repair(-10.5, 30.0));
  std::vector<Command> t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0].start_angle, 120.0, 1e-9);
  EXPECT_NEAR(t[1].start_angle, 120.0, 1e-9);  // P1 only in the first block (rule 4)
  InterpreterConfig shifted = gsk_repair(-10.5, 30.0);
  // The recorded Z is a work coordinate (the absolute page's): a work offset moves it with the
  // program, and the phase stays (read as a machine Z it would be 210 degrees).
  shifted.work_offsets[1][1] = -0.5;
  r = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2 P1\nM30\n", shifted);
  EXPECT_NEAR(r.of(Op::thread)[0].start_angle, 120.0, 1e-9);
  // Off (no №174.4), P1 is ignored (rule 1).
  r = run_ok("G00 X60 Z5\nG92 X48 Z-30 F2 P1\nM30\n", gsk());
  EXPECT_NEAR(r.of(Op::thread)[0].start_angle, 0.0, 1e-9);
}

// A left-hand thread's spindle turns the other way: the groove reaches the recorded Z 7.75
// turns after the start, counting down, so the start lies 270 degrees above the recorded 30.
TEST(InterpSingleCycles, GskThreadRepairOfALeftHandThreadCountsTheAngleDown) {
  RunResult r = run_ok("G00 X60 Z5\nG92.1 X48 Z-30 F-2 S300 P1\nM30\n", gsk_repair(-10.5, 30.0));
  ASSERT_EQ(r.of(Op::thread).size(), 1u);
  EXPECT_NEAR(r.of(Op::thread)[0].start_angle, 300.0, 1e-9);
  EXPECT_TRUE(r.of(Op::thread)[0].left_hand);
}

TEST(InterpSingleCycles, GskThreadRepairAlarms) {
  InterpreterConfig none = gsk();
  none.thread_repair = true;  // on, nothing recorded (rule 3)
  run_alarm("G00 X60 Z5\nG92.1 X48 Z-30 F2 S300 P1\nM30\n", alarm::kThreadRepair, 2, -1, none);
  const ExpectedAlarm cases[] = {
      {"G00 X60 Z5\nG92 X48 Z-30 F2 P1\nM30\n", alarm::kThreadRepair, 2},  // Z-40: rule 5
      {"G00 X60 Z5\nG92 X48 Z-30 F2 P2\nM30\n", alarm::kBadWordValue, 2},
  };
  expect_alarms(cases, gsk_repair(-40.0, 0.0));
  // A face thread (longer along X): the recorded coordinate is Z's.
  run_alarm("G00 X100 Z5\nG92 X20 Z2 F2 P1\nM30\n", alarm::kThreadRepair, 2, -1,
            gsk_repair(3.0, 0.0));
}

// The four quadrants (spec L2230-2240): the signs of U/W/R relative to the start decide the
// direction of each leg; the cycle ends at the start in every case.
TEST(InterpSingleCycles, G90InAllFourQuadrants) {
  struct Case {
    const char* block;
    double cut_x, end_x, end_z;  // radius
  } cases[] = {
      {"G90 U-20 W-30 R-2 F1", 38, 40, -25},  // OD, towards the chuck, taper
      {"G90 U20 W-30 R2 F1", 62, 60, -25},    // ID (start inside the bore)
      {"G90 U-20 W30 R-2 F1", 38, 40, 35},    // OD, away from the chuck
      {"G90 U20 W30 R2 F1", 62, 60, 35},
  };
  for (const Case& k : cases) {
    RunResult r = run_ok(std::string("G00 X100 Z5\n") + k.block + "\nM30\n");
    const auto moves = r.at_line(2);
    ASSERT_EQ(moves.size(), 4u) << k.block;
    EXPECT_AT(moves[0], k.cut_x, 5);
    EXPECT_AT(moves[1], k.end_x, k.end_z);
    EXPECT_AT(moves[2], 50, k.end_z);
    EXPECT_AT(moves[3], 50, 5);
  }
}

TEST(InterpSingleCycles, G90NeedsFeedAndTheCodeAloneDoesNothing) {
  run_alarm("G00 X60 Z5\nG90 X50 Z-10\nM30\n", alarm::kFeedMissing, 2);
  RunResult r = run_ok("G00 X60 Z5\nG90\nM30\n");
  EXPECT_EQ(r.commands.size(), 2u);
}

TEST(InterpSingleCycles, AnotherGroupOneCodeEndsTheCycle) {
  RunResult r = run_ok("G00 X60 Z5\nG90 X50 Z-10 F100\nG00 X40\nM30\n");
  EXPECT_EQ(r.at_line(3).size(), 1u);
  EXPECT_AT(r.at_line(3)[0], 20, 5);
}

TEST(InterpSingleCycles, SystemBNamesThemG77G78G79) {
  InterpreterConfig c = lathe();
  c.system = GCodeSystem::b;
  RunResult r =
      run_ok("G00 X60 Z5\nG77 X50 Z-10 F100\nG79 X40 Z-2 F100\nG78 X48 Z-30 F2\nM30\n", c);
  EXPECT_EQ(r.at_line(2).size(), 4u);
  EXPECT_EQ(r.at_line(3).size(), 4u);
  EXPECT_EQ(r.of(Op::thread).size(), 1u);
}

}  // namespace
}  // namespace mcnc::interp::test
