// G10 L14 P9 (spec dafeng L5094-5142): the torque limits it emits, per axis named, modal; G10
// L14 P0/P1 (L4770-4849): the loads watched; P2-P5 and P20-P51: the load timers started and
// read, #R from the channel's answer; P10-P12 (L5143-5209): torque mode; and the alarms.
#include "channel/interp/interpreter_source.hpp"
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
      {"G10 L14 P9\nM30\n", alarm::kCycleWordMissing, 1},  // no axis: nothing to limit
      {"G10 L14 P1 Z80 J-1\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P0 U80\nM30\n", alarm::kWordNotAllowed, 1},
      {"G10 L14 P1 Z1200\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P13 Z80\nM30\n", alarm::kBadWordValue, 1},  // no such torque function
  };
  expect_alarms(cases, lathe());
}

// The spec's drill check (L4868-4893): timers 2 and 3 started on Z at 80 % and 10 % in G01
// moves, then P21 and P30 compare them with 15 s, each a read-ahead stop with its variable.
TEST(InterpLoadTimers, TheDrillCheckExampleStartsTwoTimersAndReadsThem) {
  const RunResult r = run_ok(
      "G10 P2 L14 Z80\nG10 P3 L14 Z10\nG00 X0 Z0\nG98 G01 W-10 F30\nG00 Z0\n#100=0\n"
      "G10 P21 L14 Z15 R100\n#101=0\nG10 P30 L14 Z15 R101\nM30\n");
  const auto starts = r.of(Op::load_watch);
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_EQ(starts[0].load_timer, 2);
  EXPECT_FALSE(starts[0].every_move);  // P2/P3: G01 moves
  EXPECT_EQ(starts[0].torque_data_axes, 1U << kZ);
  EXPECT_EQ(starts[0].torque_data[kZ], 80.0);
  EXPECT_EQ(starts[1].load_timer, 3);
  EXPECT_EQ(starts[1].torque_data[kZ], 10.0);
  const auto checks = r.of(Op::load_timer_check);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_EQ(checks[0].load_timer, 2);
  EXPECT_TRUE(checks[0].timer_longer);
  EXPECT_EQ(checks[0].timer_variable, 100);
  EXPECT_EQ(checks[0].torque_data_axes, 1U << kZ);
  EXPECT_EQ(checks[0].torque_data[kZ], 15.0);  // seconds
  EXPECT_TRUE(checks[0].barrier);
  EXPECT_EQ(checks[0].line, 7);
  EXPECT_EQ(checks[1].load_timer, 3);
  EXPECT_FALSE(checks[1].timer_longer);
  EXPECT_EQ(checks[1].timer_variable, 101);
}

TEST(InterpLoadTimers, P4AndP5TimeEveryMove) {
  const RunResult r = run_ok("G10 L14 P4 X50\nG10 L14 P5 Z60 J1\nM30\n");
  const auto starts = r.of(Op::load_watch);
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_TRUE(starts[0].every_move);
  EXPECT_EQ(starts[0].load_timer, 4);
  EXPECT_EQ(starts[1].load_timer, 5);
  EXPECT_EQ(starts[1].filter_s, 1.0);
}

// The channel's answer goes to #R as the axes' bits; none met leaves #R as it was; without the
// answer (a dry run) #R is not written.
TEST(InterpLoadTimers, TheChannelsAnswerGoesToRAsTheAxesBits) {
  const char* program = "G10 L14 P4 X50 Z80\n#100=-1\nG10 L14 P41 X1 Z1 R100\n#101=#100\nM30\n";
  for (const std::uint32_t answer : {0U, 1U << kZ, (1U << kX) | (1U << kZ)}) {
    Interpreter in(lathe());
    ASSERT_FALSE(in.start(program, "t.nc"));
    std::optional<InterpResult> c;
    do {
      c = in.next();
      ASSERT_TRUE(c && std::holds_alternative<Command>(*c));
    } while (std::get<Command>(*c).op != Op::load_timer_check);
    in.load_timer_result(answer);
    while (in.next()) {
    }
    EXPECT_EQ(in.variables().read(101).value.number(),
              answer == 0 ? -1.0 : static_cast<double>(answer))
        << answer;
  }
  Interpreter dry(lathe());
  ASSERT_FALSE(dry.start(program, "t.nc"));
  while (dry.next()) {
  }
  EXPECT_EQ(dry.variables().read(101).value.number(), -1.0);
}

TEST(InterpLoadTimers, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G10 L14 P21 Z15 R100\nM30\n", alarm::kCycleWordMissing, 1},  // no P2 before it
      {"G10 L14 P2 X80\nG10 L14 P21 Z15 R100\nM30\n", alarm::kCycleWordMissing, 2},  // Z untimed
      {"G10 L14 P2 Z80\nG10 L14 P31 Z15 R100\nM30\n", alarm::kCycleWordMissing, 2},  // timer 3
      {"G10 L14 P2 Z80\nG10 L14 P21 R100\nM30\n", alarm::kCycleWordMissing, 2},      // no axis
      {"G10 L14 P2 Z80\nG10 L14 P21 W15 R100\nM30\n", alarm::kWordNotAllowed, 2},
      {"G10 L14 P2 Z80\nG10 L14 P21 Z-1 R100\nM30\n", alarm::kBadWordValue, 2},
      {"G10 L14 P2 Z80\nG10 L14 P21 Z15 R0.5\nM30\n", alarm::kBadWordValue, 2},
      {"G10 L14 P2 Z1200\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P2 W80\nM30\n", alarm::kWordNotAllowed, 1},
      {"G10 L14 P22 Z15 R100\nM30\n", alarm::kBadWordValue, 1},  // no such form
      {"G10 L14 P2 Z80\nG10 L14 P2\nG10 L14 P21 Z15 R100\nM30\n", alarm::kCycleWordMissing,
       3},  // P2 without axes stopped the timer
  };
  expect_alarms(cases, lathe());
}

// The electric tailstock (L5185-5209): B's speed (P11), torque mode at 50 % (P10), back to
// position mode with a 50 % limit (P12); P10 and P12 stop the read-ahead (the axis stands where
// the torque left it), P11 does not.
TEST(InterpTorqueMode, TheTailstockExampleSetsSpeedTorqueAndTheLimitAfter) {
  InterpreterConfig c = lathe();
  AxisConfig b;
  b.name = 'B';
  c.axes.push_back(b);
  const RunResult r = run_ok(
      "G10 L14 P11 B300\nG10 L14 P10 B50\nG04 X2\nG10 L14 P12 B50\nG10 L14 P10 B-20\n"
      "G10 L14 P10 B0\nG10 L14 P12 B-1\nM30\n",
      c);
  const auto modes = r.of(Op::torque_mode);
  ASSERT_EQ(modes.size(), 6u);
  EXPECT_EQ(modes[0].torque_mode_p, 11);
  EXPECT_EQ(modes[0].torque_data_axes, 1U << 2);
  EXPECT_EQ(modes[0].torque_data[2], 300.0);
  EXPECT_FALSE(modes[0].barrier);
  EXPECT_EQ(modes[1].torque_mode_p, 10);
  EXPECT_EQ(modes[1].torque_data[2], 50.0);
  EXPECT_TRUE(modes[1].barrier);
  EXPECT_EQ(modes[2].torque_mode_p, 12);
  EXPECT_EQ(modes[2].torque_data[2], 50.0);
  EXPECT_TRUE(modes[2].barrier);
  EXPECT_EQ(modes[3].torque_data[2], -20.0);  // the sign turns the motor the other way
  EXPECT_EQ(modes[4].torque_data[2], 0.0);    // back to position mode
  EXPECT_EQ(modes[5].torque_data[2], 0.0);    // -1: no limit after
}

TEST(InterpTorqueMode, Alarms) {
  InterpreterConfig c = lathe();
  AxisConfig b;
  b.name = 'B';
  c.axes.push_back(b);
  const ExpectedAlarm cases[] = {
      {"G10 L14 P10 B50\nM30\n", alarm::kCycleWordMissing, 1},  // no speed: P11 or param 5521
      {"G10 L14 P11 B300\nG10 L14 P10 B1001\nM30\n", alarm::kBadWordValue, 2},
      {"G10 L14 P11 B0\nM30\n", alarm::kBadWordValue, 1},  // a speed above 0
      {"G10 L14 P11 B-300\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P12 B1200\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P11 UB300\nM30\n", alarm::kWordNotAllowed, 1},
      {"G10 L14 P10\nM30\n", alarm::kCycleWordMissing, 1},
  };
  expect_alarms(cases, c);
  // Param 5521 stands in for P11.
  c.axes[2].torque_mode_speed = 500.0;
  run_ok("G10 L14 P10 B50\nM30\n", c);
}

// What the channel's source takes before a run: the load timers' checks run (Z reports its
// torque); torque mode runs on an axis with torque_mode and is 1157 at its line on one without
// (decision 153).
TEST(InterpTorqueMode, TheChannelTakesTheTimersAndTorqueModeOnlyOfAnAxisThatHasIt) {
  InterpreterConfig c = lathe();
  c.axes[kZ].torque_skip = true;
  AxisConfig b;
  b.name = 'B';
  b.torque_skip = true;
  b.torque_mode_speed = 300.0;
  c.axes.push_back(b);
  const CheckedProgram timers = InterpreterSource::check(
      c, "G10 L14 P2 Z80\nG01 W-1 F30\nG10 L14 P21 Z15 R100\nM30\n", "T.nc", false);
  EXPECT_FALSE(timers.alarm.has_value()) << timers.alarm->text;
  const std::string program = "G00 Z1\nG10 L14 P10 B50\nG10 L14 P12 B-1\nM30\n";
  const CheckedProgram without = InterpreterSource::check(c, program, "M.nc", false);
  ASSERT_TRUE(without.alarm.has_value());
  EXPECT_EQ(without.alarm->number, alarm::kSkipInput);
  EXPECT_EQ(without.alarm->line, 2);
  EXPECT_NE(without.alarm->text.find("G10 L14 P10: the drive of axis B has no torque mode"),
            std::string::npos)
      << without.alarm->text;
  c.axes.back().torque_mode = true;
  const CheckedProgram with = InterpreterSource::check(c, program, "M.nc", false);
  EXPECT_FALSE(with.alarm.has_value()) << with.alarm->text;
}

}  // namespace
}  // namespace mcnc::interp::test
