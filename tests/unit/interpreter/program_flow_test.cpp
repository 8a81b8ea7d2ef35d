// Program flow and macros of the ISO interpreter: IF/ELIF/ELSE/ENDIF, WHILE/BREAK/CONTINUE,
// GOTO/GOTOF/GOTOB, computed GOTO, #[expr], M98/M99, G65/G66 and their nesting limits
// (spec dafeng §4.4-§4.12, §5.10).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <string>

namespace mcnc::interp::test {
namespace {

// Z of every rapid, in order.
std::vector<double> rapid_z(const RunResult& r) {
  std::vector<double> z;
  for (const Command& c : r.of(Op::rapid)) {
    z.push_back(c.to[1]);
  }
  return z;
}

TEST(InterpFlow, IfElifElseTakesExactlyOneBranch) {
  for (int v = 1; v <= 4; ++v) {
    const std::string prog = "#1=" + std::to_string(v) +
                             "\n"
                             "IF[#1==1]\n"
                             "G00 Z10\n"
                             "ELIF[#1==2]\n"
                             "G00 Z20\n"
                             "ELSEIF[#1==3]\n"
                             "G00 Z30\n"
                             "ELSE\n"
                             "G00 Z40\n"
                             "ENDIF\n"
                             "G00 Z99\n"
                             "M30\n";
    RunResult r = run_ok(prog);
    EXPECT_EQ(rapid_z(r), (std::vector<double>{10.0 * v, 99})) << "#1=" << v;
  }
}

TEST(InterpFlow, IfWithoutElseSkipsBody) {
  RunResult r = run_ok("#1=0\nIF[#1==1]\nG00 Z10\nENDIF\nG00 Z5\nM30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{5}));
}

TEST(InterpFlow, NestedIfBlocks) {
  RunResult r = run_ok(
      "#1=1\n#2=2\n"
      "IF[#1==1]\n"
      "  IF[#2==1]\n  G00 Z1\n  ELSE\n  G00 Z2\n  ENDIF\n"
      "  G00 Z3\n"
      "ELSE\n"
      "  G00 Z4\n"
      "ENDIF\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{2, 3}));
}

TEST(InterpFlow, IfThenAndOneLineForms) {
  RunResult r = run_ok(
      "#1=5\n"
      "IF[#1 GT 3] THEN #2=7\n"
      "IF[#1 LT 3] THEN #2=9\n"
      "IF[#2==7] G00 Z[#2]\n"
      "IF[#2==9] G00 Z100\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{7}));
}

std::string nested_ifs(int depth) {
  std::string p = "#1=1\n";
  for (int i = 0; i < depth; ++i) {
    p += "IF[#1==1]\n";
  }
  p += "G00 Z1\n";
  for (int i = 0; i < depth; ++i) {
    p += "ENDIF\n";
  }
  return p + "M30\n";
}

TEST(InterpFlow, IfNestingTenLevelsIsAllowed) {
  RunResult r = run_ok(nested_ifs(10));
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1}));
}

TEST(InterpFlow, IfNestingElevenLevelsIsAnAlarm) {
  // The 11th IF (line 12) is one level too deep (spec L7036: nesting up to 10 levels).
  run_alarm(nested_ifs(11), alarm::kNestingTooDeep, 12);
}

TEST(InterpFlow, ElseWithoutIfIsAnAlarm) {
  run_alarm("G00 Z1\nELSE\nG00 Z2\nENDIF\nM30\n", alarm::kStructureMismatch, 2);
}

TEST(InterpFlow, IfWithoutEndifIsAnAlarm) {
  RunResult r = run("#1=1\nIF[#1==1]\nG00 Z1\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kStructureMismatch);
  EXPECT_TRUE(r.commands.empty()) << "a structure error is found when the program is loaded";
}

TEST(InterpFlow, WhileSumsOneToTen) {
  RunResult r =
      run_ok("#1=0\n#2=1\nWHILE[#2 LE 10]DO 1\n#1=#1+#2\n#2=#2+1\nEND 1\nG00 Z[#1]\nM30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{55}));
}

TEST(InterpFlow, WhileFalseAtStartRunsNever) {
  RunResult r = run_ok("#1=5\nWHILE[#1 LT 3]DO1\nG00 Z[#1]\nEND1\nG00 Z9\nM30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{9}));
}

TEST(InterpFlow, BreakAndContinue) {
  // Odd #1 are skipped by CONTINUE, the loop ends at #1 = 7 by BREAK.
  RunResult r = run_ok(
      "#1=0\n"
      "WHILE[#1 LT 100]DO1\n"
      "#1=#1+1\n"
      "IF[#1 EQ 7] BREAK\n"
      "IF[[#1 MOD 2] EQ 1] CONTINUE\n"
      "G00 Z[#1]\n"
      "END1\n"
      "G00 Z[100+#1]\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{2, 4, 6, 107}));
}

TEST(InterpFlow, AbbreviationsBrkAndCont) {
  RunResult r = run_ok(
      "#1=0\nWHILE[1]DO2\n#1=#1+1\nIF[#1 LT 3] CONT\nIF[#1 GE 3] BRK\nG00 Z50\nEND2\n"
      "G00 Z[#1]\nM30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{3}));
}

TEST(InterpFlow, BreakLeavesOnlyTheInnerLoop) {
  RunResult r = run_ok(
      "#1=0\n#3=0\n"
      "WHILE[#1 LT 3]DO1\n"
      "#1=#1+1\n#2=0\n"
      "WHILE[1]DO2\n"
      "#2=#2+1\n"
      "IF[#2 GE #1] BREAK\n"
      "END2\n"
      "#3=#3+#2\n"
      "END1\n"
      "G00 Z[#3]\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{6}));  // 1 + 2 + 3
}

std::string nested_whiles(int depth) {
  std::string p;
  for (int i = 1; i <= depth; ++i) {
    p += "#" + std::to_string(i) + "=0\n";
  }
  for (int i = 1; i <= depth; ++i) {
    p += "WHILE[#" + std::to_string(i) + " LT 1]DO" + std::to_string(i) + "\n#" +
         std::to_string(i) + "=1\n";
  }
  p += "#100=#100+1\n";
  for (int i = depth; i >= 1; --i) {
    p += "END" + std::to_string(i) + "\n";
  }
  return p + "G00 Z[#100]\nM30\n";
}

TEST(InterpFlow, WhileNestingFiveLevelsIsAllowed) {
  RunResult r = run_ok(nested_whiles(5));
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1}));
}

TEST(InterpFlow, WhileNestingSixLevelsIsAnAlarm) {
  // Lines 1-6 are the assignments, the WHILEs are lines 7, 9, 11, 13, 15 and 17.
  run_alarm(nested_whiles(6), alarm::kNestingTooDeep, 17);
}

TEST(InterpFlow, BreakOutsideWhileIsAnAlarm) {
  run_alarm("G00 Z1\nBREAK\nM30\n", alarm::kLoopControl, 2);
}

TEST(InterpFlow, EndWithoutWhileIsAnAlarm) {
  RunResult r = run("G00 Z1\nEND1\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_TRUE(r.alarm->number == alarm::kStructureMismatch ||
              r.alarm->number == alarm::kLoopControl)
      << r.alarm->number;
  EXPECT_EQ(r.alarm->line, 2);
}

TEST(InterpFlow, CrossedLoopsAreAnAlarm) {
  RunResult r = run("#1=0\nWHILE[#1 LT 1]DO1\nWHILE[#1 LT 1]DO2\n#1=1\nEND1\nEND2\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kStructureMismatch);
  EXPECT_EQ(r.alarm->line, 5);
  EXPECT_TRUE(r.commands.empty());
}

TEST(InterpFlow, GotoSearchesForwardThenWrapsAround) {
  RunResult r = run_ok(
      "#1=0\n"
      "N10 #1=#1+1\n"
      "G00 Z[#1]\n"
      "IF[#1 GE 3] GOTO 30\n"
      "GOTO 10\n"
      "N30 G00 Z100\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 2, 3, 100}));
}

TEST(InterpFlow, GotofOnlySearchesForward) {
  run_alarm("N10 G00 Z1\nGOTOF 10\nM30\n", alarm::kSequenceNotFound, 2);
  RunResult r = run_ok("GOTOF 20\nG00 Z1\nN20 G00 Z2\nM30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{2}));
}

TEST(InterpFlow, GotobSearchesBackward) {
  RunResult r =
      run_ok("#1=0\nN10 #1=#1+1\nG00 Z[#1]\nIF[#1 LT 2] GOTOB 10\nG00 Z50\nM30\nN10 G00 Z99\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 2, 50}));
}

TEST(InterpFlow, GotoMissingTargetIsAnAlarmAtItsLine) {
  RunResult r = run_alarm("G00 Z1\nGOTO 77\nG00 Z2\nM30\n", alarm::kSequenceNotFound, 2);
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1}));
}

TEST(InterpFlow, ComputedGoto) {
  RunResult r = run_ok(
      "#1=2\n"
      "GOTO[#1*10]\n"
      "N10 G00 Z10\n"
      "N20 G00 Z20\n"
      "#2=40\n"
      "GOTO #2\n"
      "N30 G00 Z30\n"
      "N40 G00 Z40\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{20, 40}));
}

TEST(InterpFlow, IndirectVariableNumbers) {
  RunResult r = run_ok(
      "#1=3\n"
      "#[#1+100]=7\n"
      "#[#[#1+100]*2]=5\n"
      "G00 Z[#103]\n"
      "G00 Z[#14]\n"
      "G00 Z[#[100+#1]]\n"
      "M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{7, 5, 7}));
}

TEST(InterpFlow, M98RepeatCountWithL) {
  RunResult r = run_ok("O0001\nM98 P1234 L4\nM30\nO1234\nG01 W-1 F100\nM99\n");
  auto l = r.of(Op::linear);
  ASSERT_EQ(l.size(), 4u);
  EXPECT_NEAR(l[3].to[1], -4, 1e-9);
}

TEST(InterpFlow, M98PackedCountLeadingDigitsBeforeFourDigitProgram) {
  // D24 (docs/dialect.md): more than 4 digits = count (leading) + program (last 4), as GSK
  // D2-20 (P30010 = O0010 three times). Spec dafeng L6326's "P30001234 = three times"
  // contradicts that rule; by it P30001234 is 3000 times.
  RunResult r = run_ok(
      "O0001\nM98 P31234\nM98 P20010\nM30\nO1234\nG01 W-1 F100\nM99\n"
      "O0010\nG01 U2 F100\nM99\n");
  auto l = r.of(Op::linear);
  ASSERT_EQ(l.size(), 5u);
  EXPECT_NEAR(l[2].to[1], -3, 1e-9);
  EXPECT_NEAR(l[4].to[0], 2, 1e-9);
  RunResult big = run_ok("O0001\nM98 P30001234\nM30\nO1234\nG01 W-1 F100\nM99\n");
  EXPECT_EQ(big.of(Op::linear).size(), 3000u);
}

TEST(InterpFlow, M98QStartsAtSequenceOfCurrentProgram) {
  // Mirror example L4254-4276: M98 Q100 runs N100 .. M99 of this program.
  RunResult r = run_ok(
      "M98 Q100\n"
      "G00 Z50\n"
      "M30\n"
      "N100 G00 Z1\n"
      "G00 Z2\n"
      "M99\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 2, 50}));
}

TEST(InterpFlow, M99PReturnsToSequenceNumber) {
  RunResult r =
      run_ok("O0001\nN10 M98 P1000\nN20 G00 Z20\nN30 G00 Z30\nM30\nO1000\nG00 Z1\nM99 P30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 30}));
}

TEST(InterpFlow, SubprogramWithoutM99IsAnAlarm) {
  RunResult r = run("O0001\nM98 P1000\nM30\nO1000\nG00 Z1\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kSubprogramEndMissing);
}

// A chain O1001 -> O1002 -> ... -> O(1000 + depth), each M98-calling the next.
std::string m98_chain(int depth) {
  std::string p = "O0001\nM98 P1001\nG00 Z[#100]\nM30\n";
  for (int i = 1; i <= depth; ++i) {
    p += "O" + std::to_string(1000 + i) + "\n#100=#100+1\n";
    if (i < depth) {
      p += "M98 P" + std::to_string(1001 + i) + "\n";
    }
    p += "M99\n";
  }
  return p;
}

TEST(InterpFlow, M98NestingSixteenLevelsIsAllowed) {
  RunResult r = run_ok(m98_chain(16));
  EXPECT_EQ(rapid_z(r), (std::vector<double>{16}));
}

TEST(InterpFlow, M98NestingSeventeenLevelsIsAnAlarm) {
  RunResult r = run(m98_chain(17));
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kCallNestingTooDeep);
  // The 17th call is the M98 P1017 in O1016.
  EXPECT_EQ(r.alarm->line, 4 + 15 * 4 + 3);
  EXPECT_TRUE(r.commands.empty());
}

std::string g65_chain(int depth) {
  std::string p = "O0001\nG65 P9001 A1\nG00 Z[#100]\nM30\n";
  for (int i = 1; i <= depth; ++i) {
    p += "O" + std::to_string(9000 + i) + "\n#100=#100+#1\n";
    if (i < depth) {
      p += "G65 P" + std::to_string(9001 + i) + " A[#1+1]\n";
    }
    p += "M99\n";
  }
  return p;
}

TEST(InterpFlow, G65NestingFiveLevelsIsAllowed) {
  RunResult r = run_ok(g65_chain(5));
  EXPECT_EQ(rapid_z(r), (std::vector<double>{15}));  // 1+2+3+4+5
}

TEST(InterpFlow, G65NestingSixLevelsIsAnAlarm) {
  RunResult r = run(g65_chain(6));
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kCallNestingTooDeep);
  EXPECT_EQ(r.alarm->line, 4 + 4 * 4 + 3);  // G65 P9006 in O9005
}

TEST(InterpFlow, G65LocalsAreNewAndRestored) {
  RunResult r = run_ok(
      "O0001\n#1=5\n#2=6\nG65 P9000 A1\nG00 Z[#1*10+#2]\nM30\n"
      "O9000\nIF[#2 NE #0] #3000=1(B NOT NULL)\nG00 Z[#1]\n#1=99\nM99\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 56}));
}

TEST(InterpFlow, G65RepeatCount) {
  RunResult r = run_ok("O0001\nG65 P9000 L3 A2\nM30\nO9000\n#100=#100+#1\nG00 Z[#100]\nM99\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{2, 4, 6}));
}

TEST(InterpFlow, G65TypeTwoArguments) {
  // A B C then I/J/K groups: I1 #4 J1 #5 K1 #6 I2 #7 J2 #8 K2 #9.
  RunResult r = run_ok(
      "O0001\nG65 P9000 A1 I4 J5 K6 I7 K9\nM30\n"
      "O9000\nG00 Z[#1*100000+#4*10000+#5*1000+#6*100+#7*10+#9]\n"
      "IF[#8 NE #0] #3000=1(J2 NOT NULL)\nM99\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{145679}));
}

TEST(InterpFlow, G66CallsAfterEveryMotionBlockUntilG67) {
  RunResult r = run_ok(
      "O0001\nG66 P9000 A3\nG00 X10\nG04 X1\nG01 X20 F100\n#1=1\nG67\nG00 X30\nM30\n"
      "O9000\nG00 Z[#1]\nG00 Z0\nM99\n");
  // Motion blocks 3 and 5 each call: Z3, Z0.
  ASSERT_EQ(r.commands.size(), 9u);
  EXPECT_EQ(r.commands[0].line, 3);
  EXPECT_EQ(r.commands[1].line, 11);
  EXPECT_NEAR(r.commands[1].to[1], 3, 1e-9);
  EXPECT_EQ(r.commands[3].op, Op::dwell);
  EXPECT_EQ(r.commands[4].line, 5);
  EXPECT_EQ(r.commands[5].line, 11);
  EXPECT_EQ(r.commands[7].line, 8);  // after G67: no call
  EXPECT_EQ(r.commands[8].op, Op::end);
}

TEST(InterpFlow, StatementLimitStopsAnEndlessLoopWithoutMotion) {
  InterpreterConfig c = lathe();
  c.statement_limit = 10000;
  RunResult r = run("G00 Z1\nN10 #1=#1+1\nGOTO 10\nM30\n", c);
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kStatementLimit);
  ASSERT_EQ(r.commands.size(), 1u);
}

TEST(InterpFlow, UserAlarmNumberAndLine) {
  RunResult r = run_alarm("G00 Z1\n#1=2\nIF[#1==2] #3000=12(BAD VALUE)\nG00 Z2\nM30\n",
                          alarm::kUserAlarmBase + 12, 3);
  EXPECT_NE(r.alarm->text.find("BAD VALUE"), std::string::npos) << r.alarm->text;
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1}));
}

// FANUC 0i: #3000 = n takes n = 0-200 (alarm 3000 + n); 201 is out of its range.
TEST(InterpFlow, UserAlarmOutOfRange) {
  run_alarm("G00 Z1\n#3000=201(X)\nM30\n", alarm::kUserAlarmRange, 2);
  RunResult r = run_alarm("G00 Z1\n#3000=150(CHECK TOOL)\nM30\n", alarm::kUserAlarmBase + 150, 2);
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->text, "CHECK TOOL");
}

// ISO code's `:1234` is the program number O1234: the program runs and M98 finds it.
TEST(InterpFlow, IsoColonProgramNumbers) {
  RunResult r = run_ok("%\n:0001 (MAIN)\nG00 Z1\nM98 P1234\nM30\n:1234\nG00 Z7\nM99\n%\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 7}));
}

TEST(InterpFlow, MainProgramM99Loops) {
  RunResult r = run_ok("#100=#100+1\nG00 Z[#100]\nIF[#100 GE 4] GOTO 9\nM99\nN9 M30\n");
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 2, 3, 4}));
}

TEST(InterpFlow, BlockSkip) {
  InterpreterConfig c = lathe();
  c.block_skip[1] = true;
  RunResult r = run_ok("G00 Z1\n/G00 Z2\n/2 G00 Z3\nG00 Z4\nM30\n", c);
  EXPECT_EQ(rapid_z(r), (std::vector<double>{1, 3, 4}));
  RunResult r2 = run_ok("G00 Z1\n/G00 Z2\n/2 G00 Z3\nG00 Z4\nM30\n");
  EXPECT_EQ(rapid_z(r2), (std::vector<double>{1, 2, 3, 4}));
}

}  // namespace
}  // namespace mcnc::interp::test
