// Program alarms: each number of channel/interp/program_alarms.hpp that the interpreter raises,
// with its line and column, and nothing of the failing block emitted. Line 1 of every program
// is a move, so the alarm of line 2 comes either before it (load time) or right after it.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <string>

namespace mcnc::interp::test {
namespace {

struct AlarmCase {
  const char* block;  // line 2
  int number;
  int column;
  const char* config = "dafeng";
};

class InterpAlarm : public ::testing::TestWithParam<AlarmCase> {};

TEST_P(InterpAlarm, NumberLineColumn) {
  const AlarmCase& a = GetParam();
  const std::string prog = std::string("O0001\nG00 Z1\n") + a.block + "\nG00 Z2\nM30\nO9000\nM99\n";
  InterpreterConfig c = std::string(a.config) == "gsk" ? gsk() : lathe();
  RunResult r = run_alarm(prog, a.number, 3, a.column == 0 ? -1 : a.column, c);
  for (const Command& cmd : r.commands) {
    EXPECT_EQ(cmd.line, 2) << "only the block before the failing one may be emitted";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Numbers, InterpAlarm,
    ::testing::Values(AlarmCase{"G00 X1 $", alarm::kUnexpectedCharacter, 8},
                      AlarmCase{"G00 X1.2.3", alarm::kMalformedNumber, 5},
                      AlarmCase{"N1.5 G00 X1", alarm::kIntegerExpected, 1},
                      AlarmCase{"G00 X1 X2", alarm::kDuplicateAddress, 8},
                      AlarmCase{"G00 X1 (abc", alarm::kUnclosedComment, 8},
                      AlarmCase{"G00 X1000000", alarm::kValueOutOfRange, 5},
                      AlarmCase{"G00 Z-1000000", alarm::kValueOutOfRange, 5},
                      AlarmCase{"N123456789 G00 X1", alarm::kValueOutOfRange, 1},
                      AlarmCase{"DPRNT[X]", alarm::kUnsupportedStatement, 1},
                      AlarmCase{"ENDIF", alarm::kStructureMismatch, 1},
                      AlarmCase{"GOTO 10 X5", alarm::kWordsAfterStatement, 9},
                      AlarmCase{"/0 G00 X1", alarm::kBadBlockSkip, 0},
                      AlarmCase{"G333 X1", alarm::kUnsupportedG, 1},
                      AlarmCase{"G00 G01 X1", alarm::kGroupConflict, 5},
                      AlarmCase{"G01 X10", alarm::kFeedMissing, 1},
                      AlarmCase{"G01 X1 F-5", alarm::kNegativeFeed, 8},
                      AlarmCase{"G04 X-1", alarm::kNegativeDwell, 5},
                      AlarmCase{"G04 U-1", alarm::kNegativeDwell, 5},
                      AlarmCase{"G04 X1 U2", alarm::kDwellTimeTwice, 8},
                      AlarmCase{"G81.4 T0 L1", alarm::kBadWordValue, 7},
                      AlarmCase{"G81.4 T1.5", alarm::kBadWordValue, 7},
                      AlarmCase{"G81.4 T10000", alarm::kBadWordValue, 7},
                      AlarmCase{"G81.4 T10 L0", alarm::kBadWordValue, 11},
                      AlarmCase{"G81.4 T10 L1 P91 Q2", alarm::kBadWordValue, 14},
                      AlarmCase{"G81.4 T10 L1 P20", alarm::kBadWordValue, 14},
                      AlarmCase{"G81.4 T10 L1 P20 Q0.05", alarm::kBadWordValue, 18},
                      AlarmCase{"G81.4 T10 L1 P20 Q-26", alarm::kBadWordValue, 18},
                      AlarmCase{"G81.4 T10 R360", alarm::kBadWordValue, 11},
                      AlarmCase{"G80.4 P2", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.8 P100 L360", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.8 P0 L10", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.8 P990 L11", alarm::kBadWordValue, 12},
                      AlarmCase{"G51.8 P1 L0", alarm::kBadWordValue, 10},
                      AlarmCase{"G51.8 P100", alarm::kBadWordValue, 1},
                      AlarmCase{"G51.8 P100 L10 R400", alarm::kBadWordValue, 16},
                      AlarmCase{"G51.8 H3 A1 B1", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.8 H1 A10", alarm::kBadWordValue, 1},
                      AlarmCase{"G51.8 H1 A10 B0", alarm::kBadWordValue, 14},
                      AlarmCase{"G51.8 H2 D10 P5", alarm::kBadWordValue, 14},
                      AlarmCase{"G51.8 H2 D0 P1", alarm::kBadWordValue, 10},
                      AlarmCase{"G51.2 P0 Q1", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.2 P1.5 Q1", alarm::kBadWordValue, 7},
                      AlarmCase{"G51.2 P1 Q0", alarm::kBadWordValue, 10},
                      AlarmCase{"G51.2 P1 Q2 R361", alarm::kBadWordValue, 13},
                      AlarmCase{"G51.2 P1", alarm::kBadWordValue, 1},
                      AlarmCase{"G50.2 P2", alarm::kBadWordValue, 7},
                      AlarmCase{"G71 P10 F100", alarm::kContourMissing, 0},
                      AlarmCase{"G74 X20 Z-5 Q1 F1", alarm::kCycleWordMissing, 0},
                      AlarmCase{"G02 X20 Z1 R3 F100", alarm::kArcGeometry, 0},
                      AlarmCase{"G02 X0 Z1 R3 F100", alarm::kArcFullCircleWithR, 0},
                      AlarmCase{"GOTO 77", alarm::kSequenceNotFound, 0},
                      AlarmCase{"M99 P77", alarm::kSequenceNotFound, 0},
                      AlarmCase{"G00 Y10", alarm::kWordNotAllowed, 5},
                      AlarmCase{"X1 G65 P9000", alarm::kWordNotAllowed, 1},
                      AlarmCase{"T0170", alarm::kBadWordValue, 1},
                      AlarmCase{"G04.1 P1 Q23", alarm::kSyncForm, 0},
                      AlarmCase{"G04.1 Q12", alarm::kSyncForm, 0},
                      AlarmCase{"#3000=201(X)", alarm::kUserAlarmRange, 0},
                      AlarmCase{"#3000=-1(X)", alarm::kUserAlarmRange, 0},
                      AlarmCase{"BREAK", alarm::kLoopControl, 1},
                      AlarmCase{"G17 G02 X1 R5 F1", alarm::kNoPlaneAxis, 0},
                      AlarmCase{"#3000=7(SEVEN)", alarm::kUserAlarmBase + 7, 0},
                      AlarmCase{"#3000=0", alarm::kUserAlarmBase, 0},
                      AlarmCase{"#3000=100(X)", alarm::kUserAlarmBase + 100, 0},
                      AlarmCase{"#3000=200(FANUC 0I)", alarm::kUserAlarmBase + 200, 0},
                      AlarmCase{"CH3", alarm::kWrongChannel, 0}));

// Column 0 in the table above means "not asserted"; these check the column of the blamed word.
TEST(InterpAlarmColumns, NegativeFeedPointsAtF) {
  RunResult r = run_alarm("G00 Z1\nG01 X1 Z2 F-5\nM30\n", alarm::kNegativeFeed, 2, 11);
}

TEST(InterpAlarmColumns, DuplicateAddressPointsAtTheSecondWord) {
  run_alarm("G00 Z1\nG00  Z2 X1 Z3\nM30\n", alarm::kDuplicateAddress, 2, 12);
}

TEST(InterpAlarmColumns, SyncNotIncludingChannelPointsAtTheBlock) {
  RunResult r = run("G00 Z1\nG04.1 P1 Q23\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kSyncForm);
  EXPECT_EQ(r.alarm->line, 2);
  EXPECT_GE(r.alarm->column, 1);
}

TEST(InterpAlarmMisc, ProgramEndMissing) {
  RunResult r = run("G00 Z1\nG00 Z2\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kProgramEndMissing);
}

TEST(InterpAlarmMisc, SubprogramEndMissing) {
  RunResult r = run("O0001\nM98 P1000\nM30\nO1000\nG00 Z1\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kSubprogramEndMissing);
}

TEST(InterpAlarmMisc, ReleasedAxis) {
  InterpreterConfig c = lathe();
  c.axes.push_back(AxisConfig{'C', false, true});
  c.axes.back().exchange = 3;
  run_alarm("G140 C3\nG00 C10\nM30\n", alarm::kReleasedAxis, 2, 5, c);
}

TEST(InterpAlarmMisc, CallNestingTooDeep) {
  std::string p = "O0001\nM98 P1000\nM30\nO1000\nM98 P1000\nM99\n";  // recursion
  RunResult r = run(p);
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kCallNestingTooDeep);
  EXPECT_EQ(r.alarm->line, 5);
}

TEST(InterpAlarmMisc, StatementLimit) {
  InterpreterConfig c = lathe();
  c.statement_limit = 1000;
  RunResult r = run("G00 Z1\nWHILE[1]DO1\n#1=#1+1\nEND1\nM30\n", c);
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, alarm::kStatementLimit);
  EXPECT_GE(r.alarm->line, 2);
  EXPECT_LE(r.alarm->line, 4);
  EXPECT_EQ(r.commands.size(), 1u);
}

TEST(InterpAlarmMisc, MustBeAlone) {
  // G04.1 is a block of its own: no motion words with it.
  RunResult r = run("G00 Z1\nG04.1 P1 G00 X10\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->line, 2);
  EXPECT_TRUE(r.alarm->number == alarm::kMustBeAlone || r.alarm->number == alarm::kWordNotAllowed)
      << r.alarm->number;
}

TEST(InterpAlarmMisc, DivisionByZeroIsAMacroAlarm) {
  RunResult r = run("G00 Z1\n#1=1/0\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, 3112);
  EXPECT_EQ(r.alarm->line, 2);
}

TEST(InterpAlarmMisc, WritingNullIsAnAlarm) {
  RunResult r = run("G00 Z1\n#0=5\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, 3114);
  EXPECT_EQ(r.alarm->line, 2);
}

TEST(InterpAlarmMisc, AsinOutOfRange) {
  RunResult r = run("G00 Z1\n#1=ASIN[2]\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->number, 3111);
}

}  // namespace
}  // namespace mcnc::interp::test
