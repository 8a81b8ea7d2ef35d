// G31 skip (spec dafeng L5210-5316): the move it emits, its input, the read-ahead barrier, the
// skip position (#5061..) and R's flag as the channel reports them, and the alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

// A macro value that is not null.
double number_of(Interpreter& in, int variable) {
  const macro::VariableRead v = in.variables().read(variable);
  EXPECT_FALSE(v.value.is_null()) << "#" << variable << " is null";
  return v.value.number();
}

TEST(InterpSkip, EmitsAFeedMoveOnItsInputThatStopsTheReadAhead) {
  const RunResult r = run_ok("G98 G00 X20 Z5\nG31 W-30 F300 L13\nG31 U10 K13\nG31 W5 I-7\nM30\n");
  const auto moves = r.of(Op::linear);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_TRUE(moves[0].skip);
  EXPECT_TRUE(moves[0].barrier);
  EXPECT_TRUE(moves[0].exact_stop);
  EXPECT_EQ(moves[0].input, 13);
  EXPECT_TRUE(moves[0].input_on);
  EXPECT_NEAR(moves[0].to[kZ], -25.0, 1e-12);
  EXPECT_NEAR(moves[0].to[kX], 10.0, 1e-12);  // the radius of X20
  EXPECT_NEAR(moves[0].feed, 300.0, 1e-12);
  EXPECT_EQ(moves[1].input, 13);
  EXPECT_FALSE(moves[1].input_on);  // K: the input going off
  EXPECT_NEAR(moves[1].to[kX], 15.0, 1e-12);
  EXPECT_EQ(moves[2].input, 7);
  EXPECT_FALSE(moves[2].input_on);  // I < 0: off
}

// G31 P1-P8 (format 4, L5233): the PLC's signal G0014.(P-1) going on, whatever param 5510 says.
TEST(InterpSkip, PNamesThePlcsSkipSignal) {
  const RunResult r = run_ok("G98 G00 X20 Z5\nG31 W-30 F300 P3 R7\nG31 U4 P8\nM30\n");
  const auto moves = r.of(Op::linear);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_TRUE(moves[0].skip);
  EXPECT_TRUE(moves[0].barrier);
  EXPECT_EQ(moves[0].skip_signal, 3);
  EXPECT_EQ(moves[0].input, 0);  // no probe input
  EXPECT_TRUE(moves[0].input_on);
  EXPECT_NEAR(moves[0].to[kZ], -25.0, 1e-12);
  EXPECT_EQ(moves[1].skip_signal, 8);
  // The G31's P is the signal, never the `S_ P` spindle address.
  const RunResult s = run_ok("G98 S500 G31 W-3 F300 P2\nM30\n");
  EXPECT_EQ(s.of(Op::linear).at(0).skip_signal, 2);
}

TEST(InterpSkip, WithoutAWordTheInputOfParam5510) {
  InterpreterConfig c = lathe();
  c.skip_input = 4;
  const RunResult r = run_ok("G98 G31 W-10 F100\nM30\n", c);
  ASSERT_EQ(r.of(Op::linear).size(), 1u);
  EXPECT_EQ(r.of(Op::linear)[0].input, 4);
  EXPECT_TRUE(r.of(Op::linear)[0].input_on);
  // Param 5510 = 0 is an alarm (spec L5284).
  run_alarm("G98 G31 W-10 F100\nM30\n", alarm::kSkipInput, 1);
}

TEST(InterpSkip, TheChannelsResultSetsTheSkipPositionTheFlagAndWhereTheNextBlockStarts) {
  Interpreter in(lathe());
  ASSERT_FALSE(
      in.start("G98 G00 X40 Z10\nG31 W-50 F200 L13 R100\n#101=#5061\n#102=#5062\n"
               "G01 W-1\nM30\n",
               "t.nc"));
  auto first = in.next();
  auto g31 = in.next();
  ASSERT_TRUE(g31 && std::holds_alternative<Command>(*g31));
  ASSERT_TRUE(std::get<Command>(*g31).skip);
  // The signal came at Z = -12.5 (X at radius 20, diameter 40); the axes stopped at Z = -13.
  AxisVector skip_at{20.0, -12.5};
  AxisVector stop_at{20.0, -13.0};
  in.skip_result(true, skip_at, stop_at);
  auto next = in.next();
  ASSERT_TRUE(next && std::holds_alternative<Command>(*next));
  const Command& after = std::get<Command>(*next);
  EXPECT_NEAR(after.to[kZ], -14.0, 1e-12);  // W-1 from where the axes stopped
  EXPECT_NEAR(number_of(in, 100), 1.0, 0.0);
  EXPECT_NEAR(number_of(in, 101), 40.0, 1e-12);  // X as a diameter, as #5001 reads it
  EXPECT_NEAR(number_of(in, 102), -12.5, 1e-12);
  (void)first;
}

TEST(InterpSkip, NoSignalSetsTheFlagToZeroAndTheEndPoint) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G98 G31 W-5 F200 L13 R100\n#101=#5062\nM30\n", "t.nc"));
  auto g31 = in.next();
  ASSERT_TRUE(g31 && std::holds_alternative<Command>(*g31));
  in.skip_result(false, AxisVector{0.0, -5.0}, AxisVector{0.0, -5.0});
  (void)in.next();
  EXPECT_NEAR(number_of(in, 100), 0.0, 0.0);
  EXPECT_NEAR(number_of(in, 101), -5.0, 1e-12);
}

// A dry run (and `mcnc interp`) takes the signal as coming at the end point: the spec's example
// O9010 (L5296-5315), which raises its alarm when the signal does not come, runs through.
TEST(InterpSkip, WithoutTheRuntimeTheSignalComesAtTheEndPoint) {
  const RunResult r = run_ok(
      "G98\nG31 UA-400 F300 L13\nG31 UA-20 K13\nG01 UA-3\nG31 UA30 F50 L13 R100\n"
      "IF[#100==0]\n#3000=1(NOT DETECTED)\nENDIF\nG50 A0\nM30\n",
      [] {
        InterpreterConfig c = lathe();
        c.axes.push_back(AxisConfig{'A', false, true});
        return c;
      }());
  EXPECT_EQ(r.of(Op::linear).size(), 4u);
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G98 G31 W-5 F200 L13\n#101=#5062\nM30\n", "t.nc"));
  drain(in);
  EXPECT_NEAR(number_of(in, 101), -5.0, 1e-12);
}

TEST(InterpSkip, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G98 G31 W-5 F100 L13 K13\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31 W-5 F100 L0\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31 W-5 F100 P3 L13\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31 W-5 F100 P0\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31 W-5 F100 P2.5\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31 W-5 F100 P98\nM30\n", alarm::kCycleWordMissing, 1},  // no load ratio
      {"G98 G31 W-5 F100 P20\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31 F100 L13\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31 W-5 F100 L13 R0.5\nM30\n", alarm::kBadWordValue, 1},
  };
  expect_alarms(cases);
}

InterpreterConfig lathe_with_a() {
  InterpreterConfig c = lathe();
  c.axes.push_back(AxisConfig{'A', false, true});
  return c;
}

// G31.8 (L5317-5354): a feed move that goes on past each signal of its input; the example's
// tooth count (L5346-5354) without the runtime: Q signals evenly along the move, the last at its
// end, their machine positions in #500-#504 and the count in #1 (decision 93).
TEST(InterpMultiSkip, StoresQPositionsAndTheCountWithoutTheRuntime) {
  Interpreter in(lathe_with_a());
  ASSERT_FALSE(in.start("G98 G00 X20 Z0 A0\nG31.8 UA360 F100 I1 P500 Q5 R1\n#2=#1\nM30\n", "t.nc"));
  const auto moves = drain(in).of(Op::linear);
  ASSERT_EQ(moves.size(), 1u);
  const Command& g = moves[0];
  EXPECT_EQ(g.op, Op::linear);
  EXPECT_TRUE(g.skip);
  EXPECT_TRUE(g.multi_skip);
  EXPECT_TRUE(g.barrier);
  EXPECT_EQ(g.input, 1);
  EXPECT_TRUE(g.input_on);
  EXPECT_EQ(g.max_signals, 5);
  EXPECT_NEAR(g.to[2], 360.0, 1e-12);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(number_of(in, 500 + k), 72.0 * (k + 1), 1e-9) << k;
  }
  EXPECT_NEAR(number_of(in, 2), 5.0, 0.0);
}

// The positions are machine positions (D27), as #5021 reads them: X as a diameter, without the
// coordinate system G50 set. Without Q: one signal, at the end; the command may take up to 100.
TEST(InterpMultiSkip, MachinePositionsAndNoQ) {
  Interpreter in(lathe());
  ASSERT_FALSE(
      in.start("G98 G50 X20 Z0\nG50 U-4\nG31.8 U10 F100 L3 P500 Q2\n"
               "G31.8 W-6 F100 K3 P510\nM30\n",
               "t.nc"));
  const auto cmds = drain(in);
  (void)cmds;
  // X programmed 16 -> 26 (diameter) in the system G50 set where the machine stands at 0: the
  // machine goes 0 -> 10, the signals at 5 and 10 (the work positions would be 21 and 26).
  EXPECT_NEAR(number_of(in, 500), 5.0, 1e-9);
  EXPECT_NEAR(number_of(in, 501), 10.0, 1e-9);
  EXPECT_NEAR(number_of(in, 510), -6.0, 1e-9);
  EXPECT_TRUE(in.variables().read(511).value.is_null());
  const RunResult r = run_ok("G98 G31.8 W-6 F100 K3 P510\nM30\n");
  ASSERT_EQ(r.of(Op::linear).size(), 1u);
  EXPECT_EQ(r.of(Op::linear)[0].max_signals, kMaxMultiSkipSignals);
  EXPECT_FALSE(r.of(Op::linear)[0].input_on);
}

TEST(InterpMultiSkip, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G98 G31.8 W-5 F100 L1 Q5\nM30\n", alarm::kCycleWordMissing, 1},  // no P (L5344)
      {"G98 G31.8 U2 W-5 F100 L1 P500\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31.8 W-5 F100 L1 I1 P500\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31.8 W-5 F100 L1 P500 Q0\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31.8 W-5 F100 L1 P500 Q101\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31.8 W-5 F100 L1 P0.5\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31.8 W-5 F100 P500\nM30\n", alarm::kSkipInput, 1},  // param 5510 = 0
      {"G98 G31.8 F100 L1 P500\nM30\n", alarm::kWordNotAllowed, 1},
  };
  expect_alarms(cases);
}

// G160 (L5355-5428): the probe example (L5396-5404) without the runtime: the skip at the end
// point, #5061 the X there (a diameter).
TEST(InterpTorqueSkip, TheProbeExampleEmitsATorqueLimitedFeedMove) {
  Interpreter in(lathe());
  ASSERT_FALSE(
      in.start("G98 G00 X50 Z100\nG160 X40 P80 F20\n#100=#5061\n"
               "G160 X50 P80 F500\nM30\n",
               "t.nc"));
  const auto moves = drain(in).of(Op::linear);
  ASSERT_EQ(moves.size(), 2u);
  const Command& g = moves[0];
  EXPECT_EQ(g.op, Op::linear);
  EXPECT_TRUE(g.torque_skip);
  EXPECT_FALSE(g.skip);  // no input: the torque and the following error
  EXPECT_TRUE(g.barrier);
  EXPECT_NEAR(g.torque_limit, 80.0, 0.0);
  EXPECT_NEAR(g.deviation, 0.0, 0.0);  // param 5516's default
  EXPECT_NEAR(g.to[kX], 20.0, 1e-12);
  EXPECT_NEAR(g.feed, 20.0, 1e-12);
  EXPECT_NEAR(number_of(in, 100), 40.0, 1e-12);
}

TEST(InterpTorqueSkip, ParamsStandInForPAndQAndPMinusOneCancels) {
  InterpreterConfig c = lathe();
  c.torque_skip_percent = 50.0;
  c.torque_skip_deviation = 0.5;
  const RunResult r = run_ok("G98 G160 W-5 F100\nG160 W-5 Q2 F100\nG160 W5 P-1\nM30\n", c);
  const auto moves = r.of(Op::linear);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_NEAR(moves[0].torque_limit, 50.0, 0.0);
  EXPECT_NEAR(moves[0].deviation, 0.5, 0.0);
  EXPECT_NEAR(moves[1].deviation, 2.0, 0.0);
  EXPECT_NEAR(moves[2].torque_limit, -1.0, 0.0);
  // Group 00: G01 after G160 is no torque skip.
  const RunResult g01 = run_ok("G98 G160 W-5 P50 F100\nG01 W-1\nM30\n");
  ASSERT_EQ(g01.of(Op::linear).size(), 2u);
  EXPECT_FALSE(g01.of(Op::linear)[1].torque_skip);
}

TEST(InterpTorqueSkip, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G98 G160 U2 W-5 P50 F100\nM30\n", alarm::kWordNotAllowed, 1},  // one axis only
      {"G98 G160 W-5 F100\nM30\n", alarm::kCycleWordMissing, 1},       // param 5515 = 0
      {"G98 G160 W-5 P0 F100\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G160 W-5 P-2 F100\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G160 W-5 P50 Q-1 F100\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G160 P50 F100\nM30\n", alarm::kWordNotAllowed, 1},
  };
  expect_alarms(cases);
}

// G31 P98 (format 5, L5246-5249): the load ratios of G10 L14 P6, else of param 5511, on the
// axes the move moves; no input. P99 (format 6, L5251-5252): the input (L, K, I or param 5510)
// or the load (decision 116).
TEST(InterpLoadSkip, P98TakesTheRatiosOfG10L14P6OnTheAxesItMoves) {
  InterpreterConfig c = lathe();
  c.axes[kX].skip_load = 30.0;  // param 5511
  c.axes[kZ].skip_load = 20.0;
  const RunResult r = run_ok(
      "G98 G00 X20 Z5\nG31 W-30 F300 P98 R7\nG10 L14 P6 Z45\nG31 U4 W-2 F300 P98\n"
      "G10 L14 P6 Z0\nG31 W-1 F300 P98\nG10 L14 P6 X60 Z70\nG10 L14 P6\nG31 U2 F300 P98\n"
      "M30\n",
      c);
  const auto moves = r.of(Op::linear);
  ASSERT_EQ(moves.size(), 4u);
  const Command& g = moves[0];
  EXPECT_TRUE(g.load_skip);
  EXPECT_FALSE(g.skip);  // the load alone
  EXPECT_FALSE(g.torque_skip);
  EXPECT_TRUE(g.barrier);
  EXPECT_TRUE(g.exact_stop);
  EXPECT_EQ(g.input, 0);
  EXPECT_NEAR(g.load_ratio[kZ], 20.0, 0.0);  // param 5511
  EXPECT_NEAR(g.load_ratio[kX], 0.0, 0.0);   // X does not move
  EXPECT_NEAR(g.to[kZ], -25.0, 1e-12);
  EXPECT_NEAR(moves[1].load_ratio[kZ], 45.0, 0.0);  // G10 L14 P6
  EXPECT_NEAR(moves[1].load_ratio[kX], 30.0, 0.0);  // X has none of G10: param 5511
  EXPECT_NEAR(moves[2].load_ratio[kZ], 20.0, 0.0);  // Z0: back to param 5511
  EXPECT_NEAR(moves[3].load_ratio[kX], 30.0, 0.0);  // G10 L14 P6 without axes: all back
}

TEST(InterpLoadSkip, P99SkipsOnItsInputOrTheLoad) {
  InterpreterConfig c = lathe();
  c.axes[kZ].skip_load = 25.0;
  c.skip_input = 4;
  const RunResult r = run_ok("G98 G31 W-10 F100 P99 L13\nG31 W-1 F100 P99\nM30\n", c);
  const auto moves = r.of(Op::linear);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_TRUE(moves[0].skip);
  EXPECT_TRUE(moves[0].load_skip);
  EXPECT_EQ(moves[0].input, 13);
  EXPECT_TRUE(moves[0].input_on);
  EXPECT_EQ(moves[0].skip_signal, 0);
  EXPECT_NEAR(moves[0].load_ratio[kZ], 25.0, 0.0);
  EXPECT_EQ(moves[1].input, 4);  // param 5510
  // Without the runtime the skip comes at the end point, as for every G31.
  Interpreter in(c);
  ASSERT_FALSE(in.start("G98 G00 X20 Z0\nG31 W-5 F200 P98 R100\n#101=#5062\nM30\n", "t.nc"));
  drain(in);
  EXPECT_NEAR(number_of(in, 100), 1.0, 0.0);
  EXPECT_NEAR(number_of(in, 101), -5.0, 1e-12);
}

TEST(InterpLoadSkip, Alarms) {
  InterpreterConfig c = lathe();
  c.axes[kZ].skip_load = 25.0;
  const ExpectedAlarm cases[] = {
      {"G98 G31 U4 F100 P98\nM30\n", alarm::kCycleWordMissing, 1},     // X has no ratio
      {"G98 G31 W-5 F100 P98 L13\nM30\n", alarm::kWordNotAllowed, 1},  // P98: no input
      {"G98 G31 W-5 F100 P99\nM30\n", alarm::kSkipInput, 1},           // P99 on param 5510 = 0
      {"G98 G31 W-5 F100 P99 L13 K13\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G10 L14 P6 W40\nM30\n", alarm::kWordNotAllowed, 1},  // absolute addresses only
      {"G98 G10 L14 P6 Z1001\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G10 L14 P6 Z-1\nM30\n", alarm::kBadWordValue, 1},
  };
  expect_alarms(cases, c);
}

// GSK's G31 (gsk A.6.20): P1-P4 select the skip signals of params 148-151, and the skip
// position also goes to #995-#999 (axis 1-5 in order: X as a diameter, as #5061 reads it).
TEST(InterpSkipGsk, PSelectsOneOfFourSignalsAndTheResultGoesTo995) {
  Interpreter in(gsk());
  ASSERT_FALSE(in.start("G98 G00 X40 Z10\nG31 W-50 F200 P2\n#101=#995\nG01 W-1\nM30\n", "t.nc"));
  (void)in.next();
  auto g31 = in.next();
  ASSERT_TRUE(g31 && std::holds_alternative<Command>(*g31));
  EXPECT_EQ(std::get<Command>(*g31).skip_signal, 2);
  // Without the channel the signal counts at the end point.
  EXPECT_NEAR(number_of(in, 996), -40.0, 1e-12);
  in.skip_result(true, AxisVector{20.0, -12.5}, AxisVector{20.0, -13.0});
  (void)in.next();
  EXPECT_NEAR(number_of(in, 995), 40.0, 1e-12);
  EXPECT_NEAR(number_of(in, 996), -12.5, 1e-12);
  EXPECT_NEAR(number_of(in, 101), 40.0, 1e-12);
  // Dafeng keeps #995 as a common variable.
  Interpreter d(lathe());
  ASSERT_FALSE(d.start("G98 G31 W-5 F200 P2\nM30\n", "t.nc"));
  (void)d.next();
  EXPECT_TRUE(d.variables().read(995).value.is_null());
}

TEST(InterpSkipGsk, APOtherThanOneToFourIsAnAlarm) {
  const InterpreterConfig c = gsk();
  for (const char* p : {"P5", "P0", "P98", "P99", "P1.5"}) {
    const RunResult r = run("G98 G31 W-5 F200 " + std::string(p) + "\nM30\n", c);
    ASSERT_TRUE(r.alarm.has_value()) << p;
    EXPECT_EQ(r.alarm->number, alarm::kBadWordValue) << p;
    EXPECT_NE(r.alarm->text.find("1-4"), std::string::npos) << r.alarm->text;
    EXPECT_TRUE(r.of(Op::linear).empty()) << p;
  }
}

}  // namespace
}  // namespace mcnc::interp::test
