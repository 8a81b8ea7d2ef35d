// G10 L14 P7/P8 (spec dafeng L4895-5093): the drilling and rigid tapping cycles' in-feeds
// marked for the channel's overload watch (loads, J, R, where R lies, what follows an overload
// by params 5100/5200), the channel's answer (#R counted, the block ended at R), and the
// alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

// The watched in-feeds of a run, in order.
std::vector<Command> watched(const RunResult& r) {
  std::vector<Command> out;
  for (const Command& c : r.commands) {
    if (c.overload_axes != 0) {
      out.push_back(c);
    }
  }
  return out;
}

// The spec's drilling example (L4965-4993): Z watched at 100 % in each G83 hole's feed to the
// bottom, R 11 mm back from it; the rapids are not watched; G10 L14 P7 alone cancels.
TEST(InterpOverload, TheDrillingExampleWatchesZInEachHoleUntilCancelled) {
  InterpreterConfig c = lathe();
  c.cycles.drill_overload = OverloadParams{true, false, true, 0};  // 5100.2 = 1, .3 = 0, .4 = 1
  const RunResult r = run_ok(
      "G00 X0 Z10\nG10 L14 P7 Z100\nG98 G83 X0 R1 Z-10 F100\nX50\nX100\nG80\nG10 L14 P7\n"
      "G00 X0 Z10\nG83 X0 R1 Z-10 F100\nG80\nM30\n",
      c);
  const auto in = watched(r);
  ASSERT_EQ(in.size(), 3u);  // the three holes before the cancel, none after
  for (std::size_t k = 0; k < in.size(); ++k) {
    EXPECT_EQ(in[k].op, Op::linear);
    EXPECT_EQ(in[k].line, 3 + static_cast<int>(k));
    EXPECT_EQ(in[k].overload_axes, 1U << kZ);
    EXPECT_EQ(in[k].overload_loads[kZ], 100.0);
    EXPECT_NEAR(in[k].to[kZ], -10.0, 1e-12);
    EXPECT_NEAR(in[k].overload_retract, 11.0, 1e-12);  // back to R1
    EXPECT_EQ(in[k].overload_outcome, Command::Overload::alarm);
    EXPECT_EQ(in[k].overload_p, 7);
    EXPECT_TRUE(in[k].barrier);  // the channel answers before anything after it is read
  }
  EXPECT_NEAR(in[1].to[kX], 25.0, 1e-12);  // X50: the radius
  EXPECT_NE(in[0].overload_block, in[1].overload_block);
  for (const Command& m : r.of(Op::rapid)) {
    EXPECT_EQ(m.overload_axes, 0U);
  }
}

// Each peck's feed is an in-feed of its own, R as far back from each one's end.
TEST(InterpOverload, EachPeckIsWatchedWithRBehindIt) {
  const RunResult r = run_ok(
      "G00 X0 Z10\nG10 L14 P7 Z80 J0.5 R100\nG98 G83 X0 R1 Z-10 Q4 F100\n"
      "G80\nM30\n");
  const auto in = watched(r);
  ASSERT_EQ(in.size(), 3u);
  const double ends[] = {-3.0, -7.0, -10.0};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(in[k].to[kZ], ends[k], 1e-12);
    EXPECT_NEAR(in[k].overload_retract, 1.0 - ends[k], 1e-12);
    EXPECT_EQ(in[k].overload_filter_s, 0.5);
    EXPECT_EQ(in[k].overload_variable, 100);
    EXPECT_EQ(in[k].overload_outcome, Command::Overload::stop);  // 5100.2 = 0: no retract
    EXPECT_EQ(in[k].overload_block, in[0].overload_block);       // one block
  }
}

TEST(InterpOverload, TheParamBitsChooseWhatFollows) {
  struct Case {
    OverloadParams params;
    Command::Overload then;
  };
  const Case cases[] = {
      {{false, true, true, 0}, Command::Overload::stop},  // no retract: nothing else
      {{true, false, true, 0}, Command::Overload::alarm},
      {{true, false, false, 0}, Command::Overload::go_on},
      {{true, true, true, 0}, Command::Overload::retry},
  };
  for (const Case& k : cases) {
    InterpreterConfig c = lathe();
    c.cycles.drill_overload = k.params;
    c.cycles.drill_overload.variable = 120;  // param 5113: the variable without R
    const auto in =
        watched(run_ok("G00 X0 Z10\nG10 L14 P7 Z90\nG98 G83 X0 R1 Z-10 F100\nG80\nM30\n", c));
    ASSERT_EQ(in.size(), 1u);
    EXPECT_EQ(in[0].overload_outcome, k.then);
    EXPECT_EQ(in[0].overload_variable, 120);
  }
}

// P8 watches rigid tapping only (M29: the spindle stands and follows the tap, L4902); a
// turning spindle's follow tapping is not watched, nor is drilling.
TEST(InterpOverload, P8WatchesTheRigidTapsWayIn) {
  const RunResult rigid = run_ok(
      "G00 X50 Z10\nG10 L14 P8 Z120 R1\nG84 X50 R1 Z-10 F1.25\nG83 X0 R1 Z-10 F100\nG80\nM30\n");
  const auto in = watched(rigid);
  ASSERT_EQ(in.size(), 1u);  // the tap's way in; not its way out, nor the G83
  EXPECT_EQ(in[0].op, Op::thread);
  EXPECT_EQ(in[0].overload_p, 8);
  EXPECT_NEAR(in[0].to[kZ], -10.0, 1e-12);
  EXPECT_EQ(in[0].overload_loads[kZ], 120.0);
  EXPECT_EQ(in[0].overload_variable, 1);
  const RunResult follow =
      run_ok("G00 X50 Z10\nM03 S300\nG10 L14 P8 Z120\nG84 X50 R1 Z-10 F1.25\nG80\nM30\n");
  EXPECT_TRUE(watched(follow).empty());
}

// The channel's answers: each overload adds 1 to #R (L4900); "go on" (case 2, L4913) ends the
// block at R, so the next command pulled is the next block's.
TEST(InterpOverload, TheChannelsAnswerCountsAndEndsTheBlock) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start(
      "G00 X0 Z10\n#100=0\nG10 L14 P7 Z100 R100\nG98 G83 X0 R1 Z-10 Q4 F100\nX50\nG80\nM30\n",
      "t.nc"));
  std::optional<Command> first;
  while (!first) {
    auto x = in.next();
    ASSERT_TRUE(x && std::holds_alternative<Command>(*x));
    const Command& c = std::get<Command>(*x);
    if (c.overload_axes != 0) {
      first = c;
    }
  }
  EXPECT_EQ(first->line, 4);
  // A retried in-feed that got through after two overloads: counted, the block goes on.
  in.overload_result(2, 0, AxisVector{0.0, -3.0});
  auto x = in.next();
  ASSERT_TRUE(x && std::holds_alternative<Command>(*x));
  const Command& after = std::get<Command>(*x);
  EXPECT_EQ(after.line, 4);  // the peck's back-off
  EXPECT_NEAR(in.variables().read(100).value.number(), 2.0, 0.0);
  // The next peck overloads and the block ends at R.
  std::optional<Command> second;
  while (!second) {
    auto y = in.next();
    ASSERT_TRUE(y && std::holds_alternative<Command>(*y));
    if (std::get<Command>(*y).overload_axes != 0) {
      second = std::get<Command>(*y);
    }
  }
  in.overload_result(1, second->overload_block, AxisVector{0.0, 1.0});
  EXPECT_NEAR(in.variables().read(100).value.number(), 3.0, 0.0);
  const RunResult rest = drain(in);
  ASSERT_FALSE(rest.alarm.has_value());
  ASSERT_FALSE(rest.commands.empty());
  EXPECT_EQ(rest.commands[0].line, 5);  // X50's hole, from R
  EXPECT_EQ(rest.commands[0].op, Op::rapid);
  EXPECT_NEAR(rest.commands[0].to[kX], 25.0, 1e-12);
  EXPECT_NEAR(rest.commands[0].to[kZ], 1.0, 1e-12);  // it starts where the tool retracted to
}

TEST(InterpOverload, Alarms) {
  const ExpectedAlarm cases[] = {
      {"G10 L14 P7 W80\nM30\n", alarm::kWordNotAllowed, 1},  // absolute addresses only
      {"G10 L14 P8 Z1001\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P7 Z100 J-1\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P7 Z100 J3601\nM30\n", alarm::kBadWordValue, 1},
      {"G10 L14 P7 Z100 R0\nM30\n", alarm::kBadWordValue, 1},  // R names a variable
      {"G10 L14 P7 Z100 R1.5\nM30\n", alarm::kBadWordValue, 1},
  };
  expect_alarms(cases, lathe());
}

}  // namespace
}  // namespace mcnc::interp::test
