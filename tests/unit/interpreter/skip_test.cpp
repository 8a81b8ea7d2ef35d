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
      {"G98 G31 W-5 F100 P3\nM30\n", alarm::kNotInThisVersion, 1},
      {"G98 G31 W-5 F100 P98\nM30\n", alarm::kNotInThisVersion, 1},
      {"G98 G31 W-5 F100 P20\nM30\n", alarm::kBadWordValue, 1},
      {"G98 G31 F100 L13\nM30\n", alarm::kWordNotAllowed, 1},
      {"G98 G31 W-5 F100 L13 R0.5\nM30\n", alarm::kBadWordValue, 1},
  };
  expect_alarms(cases);
}

}  // namespace
}  // namespace mcnc::interp::test
