// Tools: T words, geometry and wear offsets from the config and from G10 P, the tool variables
// #2001.. and T calls (spec dafeng §2.8, §4.13).
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

TEST(InterpTools, TWordSplitsToolAndOffset) {
  RunResult r = run_ok("T0203\nT5\nM30\n");
  auto t = r.of(Op::tool);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].tool, 2);
  EXPECT_EQ(t[0].offset, 3);
  EXPECT_EQ(t[1].tool, 0);
  EXPECT_EQ(t[1].offset, 5);
}

TEST(InterpTools, OffsetShiftsTheMachinePosition) {
  InterpreterConfig c = lathe();
  c.tool_geometry[1] = {20, 5};  // X as a diameter
  c.tool_wear[1] = {0.2, -0.1};
  RunResult r = run_ok("T0101\nG00 X100 Z10\nT0100\nG00 X100 Z10\nM30\n", c);
  auto m = r.of(Op::rapid);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_AT(m[0], (100 + 20.2) / 2, 10 + 4.9);
  EXPECT_AT(m[1], 50, 10);  // offset 0 cancels
}

TEST(InterpTools, TNeverMovesTheAxes) {
  InterpreterConfig c = lathe();
  c.tool_geometry[1] = {20, 5};
  RunResult r = run_ok("G00 X100 Z10\nT0101\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_EQ(r.commands[1].op, Op::tool);
}

TEST(InterpTools, G10PWritesWearAndGeometry) {
  RunResult r = run_ok(
      "G10 P10001 X10 Z2\n"
      "G10 P1 U0.4 W-0.2\n"
      "G10 P1 U0.1\n"
      "T0101\nG00 X0 Z0\n"
      "IF[#2701 NE 10] #3000=1(GEOMETRY X)\n"
      "IF[ABS[#2001-0.5] GT 0.0001] #3000=2(WEAR X)\n"
      "IF[#2801 NE 2] #3000=3(GEOMETRY Z)\n"
      "M30\n");
  auto m = r.of(Op::rapid);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_AT(m[0], (10 + 0.5) / 2, 2 - 0.2);
}

TEST(InterpTools, ToolVariablesAreWritable) {
  RunResult r = run_ok("#2701=30\n#2801=7\nT0101\nG00 X0 Z0\nM30\n");
  EXPECT_AT(r.of(Op::rapid)[0], 15, 7);
}

TEST(InterpTools, OffsetNumberOutOfRangeIsAnAlarm) {
  run_alarm("G00 X1\nT0165\nM30\n", alarm::kBadWordValue, 2);
}

TEST(InterpTools, ToolNumberAboveMaxIsAnAlarm) {
  InterpreterConfig c = lathe();
  c.max_tool = 8;
  run_alarm("T0801\nT0901\nM30\n", alarm::kBadWordValue, 2, -1, c);
}

TEST(InterpTools, TCallPassesTheTValue) {
  InterpreterConfig c = lathe();
  c.calls.t_program = 9010;
  RunResult r = run_ok("O0001\nT0202\nM30\nO9010\nG00 Z[#149]\nT#149\nM99\n", c);
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_AT(r.commands[0], 0, 202);
  EXPECT_EQ(r.commands[1].op, Op::tool);
  EXPECT_EQ(r.commands[1].tool, 2);
  EXPECT_EQ(r.commands[1].offset, 2);
}

TEST(InterpTools, TCodeCancelsNothingElse) {
  InterpreterConfig c = lathe();
  c.work_offsets[1] = {5, 5};
  RunResult r = run_ok("G00 X0 Z0\nT0100\nG00 X0 Z0\nM30\n", c);
  auto m = r.of(Op::rapid);
  EXPECT_AT(m[0], 5, 5);
  EXPECT_AT(m[1], 5, 5);
}

}  // namespace
}  // namespace mcnc::interp::test
