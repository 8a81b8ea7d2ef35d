#include "channel/interp/minimal_interpreter.hpp"
#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace mcnc::interp {
namespace {

// A lathe channel: X in diameter (U incremental), Z (W incremental).
std::vector<AxisAddress> lathe_axes() {
  return {{'X', 'U', true}, {'Z', 'W', false}};
}

AxisVector xz(double x, double z) {
  AxisVector v{};
  v[0] = x;
  v[1] = z;
  return v;
}

// Pulls every command until nullopt; fails the test on an alarm.
std::vector<CanonicalCommand> drain(MinimalInterpreter& interp) {
  std::vector<CanonicalCommand> out;
  for (int guard = 0; guard < 10000; ++guard) {
    auto r = interp.next();
    if (!r) {
      return out;
    }
    if (const auto* alarm = std::get_if<ProgramAlarm>(&*r)) {
      ADD_FAILURE() << "alarm " << alarm->number << ": " << alarm->text;
      return out;
    }
    out.push_back(std::get<CanonicalCommand>(*r));
  }
  ADD_FAILURE() << "next() never ended";
  return out;
}

std::optional<ProgramAlarm> load(const std::string& text) {
  MinimalInterpreter interp(lathe_axes());
  return interp.load(text, "T.nc");
}

// Loads a program expected to fail and checks the alarm.
void expect_alarm(const std::string& text, int number, int line, int column,
                  const std::string& message = {}) {
  SCOPED_TRACE(text);
  const auto alarm = load(text);
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, number) << alarm->text;
  EXPECT_EQ(alarm->line, line) << alarm->text;
  EXPECT_EQ(alarm->column, column) << alarm->text;
  EXPECT_EQ(alarm->program, "T.nc");
  if (!message.empty()) {
    EXPECT_EQ(alarm->text, message);
  }
}

const char* const kProgram =
    "%\n"                              // 1
    "O1234 (MAIN)\n"                   // 2
    "N10 G00 X100. Z50.   ; rapid\n"   // 3
    "N20 G01 U-20 F200\n"              // 4
    "N30 W-10.5\n"                     // 5
    "\n"                               // 6
    "N40 X60 Z30 (modal G01 and F)\n"  // 7
    "N45\n"                            // 8
    "(only a comment)\n"               // 9
    "G0 X.5\n"                         // 10
    "N50 G04 P1500\n"                  // 11
    "G4 X2.5\n"                        // 12
    "g4 u0.25\n"                       // 13
    "F300\n"                           // 14
    "g1 w+2\n"                         // 15
    "N60 M30\n"                        // 16
    "%\n";                             // 17

void expect_command(const CanonicalCommand& c, CommandKind kind, double x, double z, int line,
                    std::size_t block) {
  EXPECT_EQ(c.kind, kind);
  EXPECT_EQ(c.target[0], x);
  EXPECT_EQ(c.target[1], z);
  for (std::size_t i = 2; i < kMaxChannelAxes; ++i) {
    EXPECT_EQ(c.target[i], 0.0);
  }
  EXPECT_EQ(c.line, line);
  EXPECT_EQ(c.block, block);
}

TEST(MinimalInterpreter, SmallProgramProducesTheExpectedCommands) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load(kProgram, "O1234.nc"));
  EXPECT_EQ(interp.block_count(), 10u);
  interp.rewind(xz(10.0, 100.0));
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 10u);

  expect_command(cmds[0], CommandKind::rapid, 50.0, 50.0, 3, 1);   // X100 diameter = 50 radius
  expect_command(cmds[1], CommandKind::linear, 40.0, 50.0, 4, 2);  // U-20 diameter = -10
  EXPECT_EQ(cmds[1].feed, 200.0);
  expect_command(cmds[2], CommandKind::linear, 40.0, 39.5, 5, 3);
  EXPECT_EQ(cmds[2].feed, 200.0);
  expect_command(cmds[3], CommandKind::linear, 30.0, 30.0, 7, 4);
  EXPECT_EQ(cmds[3].feed, 200.0);
  expect_command(cmds[4], CommandKind::rapid, 0.25, 30.0, 10, 5);
  EXPECT_EQ(cmds[4].feed, 0.0);
  expect_command(cmds[5], CommandKind::dwell, 0.25, 30.0, 11, 6);
  EXPECT_EQ(cmds[5].dwell_s, 1.5);
  expect_command(cmds[6], CommandKind::dwell, 0.25, 30.0, 12, 7);
  EXPECT_EQ(cmds[6].dwell_s, 2.5);  // G04 X is seconds, never halved as a diameter
  expect_command(cmds[7], CommandKind::dwell, 0.25, 30.0, 13, 8);
  EXPECT_EQ(cmds[7].dwell_s, 0.25);
  expect_command(cmds[8], CommandKind::linear, 0.25, 32.0, 15, 9);
  EXPECT_EQ(cmds[8].feed, 300.0);
  expect_command(cmds[9], CommandKind::program_end, 0.25, 32.0, 16, 10);
  EXPECT_EQ(cmds[9].end_code, 30);

  EXPECT_FALSE(interp.next().has_value());
  EXPECT_FALSE(interp.next().has_value());
}

TEST(MinimalInterpreter, RewindReproducesTheSameSequence) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load(kProgram, "O1234.nc"));
  interp.rewind(xz(10.0, 100.0));
  const auto first = drain(interp);
  interp.rewind(xz(10.0, 100.0));
  const auto second = drain(interp);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].kind, second[i].kind);
    EXPECT_EQ(first[i].target, second[i].target);
    EXPECT_EQ(first[i].feed, second[i].feed);
    EXPECT_EQ(first[i].dwell_s, second[i].dwell_s);
    EXPECT_EQ(first[i].line, second[i].line);
    EXPECT_EQ(first[i].block, second[i].block);
  }
}

TEST(MinimalInterpreter, RewindMidProgramRestartsFromTheFirstBlock) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("G00 U10 W-1\nM02\n", "p"));
  interp.rewind(xz(0.0, 0.0));
  ASSERT_TRUE(interp.next().has_value());
  interp.rewind(xz(1.0, 2.0));
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 2u);
  expect_command(cmds[0], CommandKind::rapid, 6.0, 1.0, 1, 1);  // from the new current position
  expect_command(cmds[1], CommandKind::program_end, 6.0, 1.0, 2, 2);
  EXPECT_EQ(cmds[1].end_code, 2);
}

TEST(MinimalInterpreter, UnprogrammedAxesKeepTheCurrentPosition) {
  MinimalInterpreter interp({{'X', 'U', true}, {'Z', 'W', false}, {'C', 'H', false}});
  ASSERT_FALSE(interp.load("G00 H90\nZ5\nM30\n", "p"));
  AxisVector start{};
  start[0] = 7.0;
  start[1] = 8.0;
  start[2] = 9.0;
  interp.rewind(start);
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 3u);
  EXPECT_EQ(cmds[0].target[0], 7.0);
  EXPECT_EQ(cmds[0].target[1], 8.0);
  EXPECT_EQ(cmds[0].target[2], 99.0);
  EXPECT_EQ(cmds[1].target[1], 5.0);
  EXPECT_EQ(cmds[1].target[2], 99.0);
}

TEST(MinimalInterpreter, PowerOnMotionIsRapid) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("X10 Z1\nM30\n", "p"));
  interp.rewind(AxisVector{});
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 2u);
  EXPECT_EQ(cmds[0].kind, CommandKind::rapid);
}

TEST(MinimalInterpreter, ModalCodesWithoutAxisWordsProduceNoCommand) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("G01\nF100\nN5 (x)\n; nothing\nZ-1\nG00\nZ0\nM30\n", "p"));
  EXPECT_EQ(interp.block_count(), 3u);
  interp.rewind(AxisVector{});
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 3u);
  expect_command(cmds[0], CommandKind::linear, 0.0, -1.0, 5, 1);
  EXPECT_EQ(cmds[0].feed, 100.0);
  expect_command(cmds[1], CommandKind::rapid, 0.0, 0.0, 7, 2);
  expect_command(cmds[2], CommandKind::program_end, 0.0, 0.0, 8, 3);
}

TEST(MinimalInterpreter, MotionAndEndInOneBlockGiveTwoCommandsOfOneBlock) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("G01 Z-3 F50 M30\n", "p"));
  EXPECT_EQ(interp.block_count(), 1u);
  interp.rewind(AxisVector{});
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 2u);
  expect_command(cmds[0], CommandKind::linear, 0.0, -3.0, 1, 1);
  expect_command(cmds[1], CommandKind::program_end, 0.0, -3.0, 1, 1);
}

TEST(MinimalInterpreter, BlocksAfterTheEndAreNeitherCheckedNorRun) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("G00 X1\nM30\nG02 X1 Q ###\n(unclosed\n", "p"));
  EXPECT_EQ(interp.block_count(), 2u);
  interp.rewind(AxisVector{});
  EXPECT_EQ(drain(interp).size(), 2u);
}

TEST(MinimalInterpreter, CaseSpacesCrLfAndSignsAreAccepted) {
  MinimalInterpreter interp(lathe_axes());
  ASSERT_FALSE(interp.load("o0001\r\nn1 g 01 x 20. z-1.5 f 1000\r\nm 30\r\n", "p"));
  interp.rewind(AxisVector{});
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 2u);
  expect_command(cmds[0], CommandKind::linear, 10.0, -1.5, 2, 1);
  EXPECT_EQ(cmds[0].feed, 1000.0);
}

TEST(MinimalInterpreter, RadiusAxisIsNotHalved) {
  MinimalInterpreter interp({{'X', 'U', false}, {'Z', 'W', false}});
  ASSERT_FALSE(interp.load("G00 X10 Z1\nU-4\nM30\n", "p"));
  interp.rewind(AxisVector{});
  const auto cmds = drain(interp);
  ASSERT_EQ(cmds.size(), 3u);
  EXPECT_EQ(cmds[0].target[0], 10.0);
  EXPECT_EQ(cmds[1].target[0], 6.0);
}

TEST(MinimalInterpreter, EmptyLoadAndFailedLoad) {
  MinimalInterpreter interp(lathe_axes());
  EXPECT_EQ(interp.block_count(), 0u);
  EXPECT_FALSE(interp.next().has_value());  // nothing loaded: nothing to run

  const auto alarm = interp.load("G00 X1\nG02 X2\nM30\n", "bad.nc");
  ASSERT_TRUE(alarm);
  EXPECT_EQ(interp.block_count(), 0u);
  interp.rewind(AxisVector{});
  for (int i = 0; i < 2; ++i) {
    auto r = interp.next();
    ASSERT_TRUE(r.has_value());
    const auto* a = std::get_if<ProgramAlarm>(&*r);
    ASSERT_NE(a, nullptr);  // no command of a bad program ever comes out
    EXPECT_EQ(a->number, alarm::kUnsupportedG);
    EXPECT_EQ(a->line, 2);
    EXPECT_EQ(a->program, "bad.nc");
  }

  // A good program loaded afterwards runs normally.
  ASSERT_FALSE(interp.load("M30\n", "good.nc"));
  interp.rewind(AxisVector{});
  EXPECT_EQ(drain(interp).size(), 1u);
}

TEST(MinimalInterpreter, ConstructorRejectsBadAxisLists) {
  EXPECT_THROW(MinimalInterpreter({{'X', 'U', true}, {'X', 'W', false}}), std::invalid_argument);
  EXPECT_THROW(MinimalInterpreter({{'F', 'U', false}}), std::invalid_argument);
  EXPECT_THROW(MinimalInterpreter({{'X', '1', false}}), std::invalid_argument);
  EXPECT_THROW(MinimalInterpreter(std::vector<AxisAddress>(kMaxChannelAxes + 1)),
               std::invalid_argument);
  EXPECT_NO_THROW(MinimalInterpreter({{'x', 'u', true}}));
}

// --- alarms: number, line and 1-based column of the offending word ---

TEST(MinimalInterpreterAlarms, UnknownWordLetter) {
  expect_alarm("G00 X1 Q5\nM30\n", alarm::kUnknownAddress, 1, 8, "unknown word address Q");
  expect_alarm("N1\n  S1000\nM30\n", alarm::kUnknownAddress, 2, 3);
  expect_alarm("G00 Y1\nM30\n", alarm::kUnknownAddress, 1, 5);  // not an axis of this channel
}

TEST(MinimalInterpreterAlarms, UnsupportedGCode) {
  expect_alarm("G02 X1 Z1\nM30\n", alarm::kUnsupportedG, 1, 1, "G02 is not supported yet");
  expect_alarm("N5 G3 X1\nM30\n", alarm::kUnsupportedG, 1, 4, "G03 is not supported yet");
  expect_alarm("G04.1 P1\nM30\n", alarm::kUnsupportedG, 1, 1, "G04.1 is not supported yet");
  expect_alarm("G114.1\nM30\n", alarm::kUnsupportedG, 1, 1, "G114.1 is not supported yet");
}

TEST(MinimalInterpreterAlarms, UnsupportedMCode) {
  expect_alarm("M3\nM30\n", alarm::kUnsupportedM, 1, 1, "M03 is not supported yet");
  expect_alarm("G00 X1 M99\n", alarm::kUnsupportedM, 1, 8, "M99 is not supported yet");
}

TEST(MinimalInterpreterAlarms, MalformedNumber) {
  expect_alarm("G00\nG01 X1.2.3 F100\nM30\n", alarm::kMalformedNumber, 2, 5,
               "malformed number after X");
  expect_alarm("G00 Z\nM30\n", alarm::kMalformedNumber, 1, 5);
}

TEST(MinimalInterpreterAlarms, IntegerExpected) {
  expect_alarm("N1.5\nM30\n", alarm::kIntegerExpected, 1, 1);
  expect_alarm("N-1\nM30\n", alarm::kIntegerExpected, 1, 1);
  expect_alarm("M30.\n", alarm::kIntegerExpected, 1, 1);
  expect_alarm("G04 P1.5\nM30\n", alarm::kIntegerExpected, 1, 5);
  expect_alarm("G-1\nM30\n", alarm::kIntegerExpected, 1, 1);
  expect_alarm("G1.25\nM30\n", alarm::kIntegerExpected, 1, 1);
}

TEST(MinimalInterpreterAlarms, SameAddressTwice) {
  expect_alarm("G00 X1 X2\nM30\n", alarm::kDuplicateAddress, 1, 8,
               "address X appears twice in the block");
  expect_alarm("N1 F1 N2\nM30\n", alarm::kDuplicateAddress, 1, 7);
  expect_alarm("M30 M02\n", alarm::kDuplicateAddress, 1, 5);
}

TEST(MinimalInterpreterAlarms, AbsoluteAndIncrementalOfOneAxis) {
  expect_alarm("G00 X1 U2\nM30\n", alarm::kAbsoluteAndIncremental, 1, 8,
               "absolute X and incremental U of one axis in one block");
  expect_alarm("G00 W1 Z2\nM30\n", alarm::kAbsoluteAndIncremental, 1, 8);
}

TEST(MinimalInterpreterAlarms, TwoGCodesOfOneGroup) {
  expect_alarm("G00 G01 X1 F1\nM30\n", alarm::kGroupConflict, 1, 5,
               "two G codes of group 01 in one block");
  expect_alarm("G0 G0 X1\nM30\n", alarm::kGroupConflict, 1, 4);
  expect_alarm("G4 P1 G4\nM30\n", alarm::kGroupConflict, 1, 7,
               "two G codes of group 00 in one block");
}

TEST(MinimalInterpreterAlarms, G01WithoutFeed) {
  expect_alarm("G01 X1\nM30\n", alarm::kFeedMissing, 1, 1);
  expect_alarm("G01\nN2 Z1\nM30\n", alarm::kFeedMissing, 2, 4);  // modal G01, still no F
  expect_alarm("G01 Z1 F0\nM30\n", alarm::kFeedMissing, 1, 8);
  expect_alarm("G00 X1 F0\nG01 Z1\nM30\n", alarm::kFeedMissing, 2, 1);
}

TEST(MinimalInterpreterAlarms, NegativeFeed) {
  expect_alarm("G01 Z1 F-5\nM30\n", alarm::kNegativeFeed, 1, 8);
}

TEST(MinimalInterpreterAlarms, DwellWithoutTime) {
  expect_alarm("N1 G04\nM30\n", alarm::kDwellTimeMissing, 1, 4);
  expect_alarm("G04 F100\nM30\n", alarm::kDwellTimeMissing, 1, 1);
}

TEST(MinimalInterpreterAlarms, DwellWithNegativeTime) {
  expect_alarm("G04 X-1\nM30\n", alarm::kNegativeDwell, 1, 5);
  expect_alarm("G04 U-0.5\nM30\n", alarm::kNegativeDwell, 1, 5);
  expect_alarm("G04 P-5\nM30\n", alarm::kNegativeDwell, 1, 5);
}

TEST(MinimalInterpreterAlarms, DwellTimeTwiceOrWithAxisWords) {
  expect_alarm("G04 X1 P100\nM30\n", alarm::kDwellTimeTwice, 1, 8);
  expect_alarm("G04 X1 U1\nM30\n", alarm::kDwellTimeTwice, 1, 8);
  expect_alarm("G04 Z1 X1\nM30\n", alarm::kAxisInDwell, 1, 5, "Z is not allowed in a G04 block");
}

TEST(MinimalInterpreterAlarms, PWithoutDwell) {
  expect_alarm("G00 X1 P5\nM30\n", alarm::kPWithoutDwell, 1, 8);
}

TEST(MinimalInterpreterAlarms, ValueOutOfRange) {
  expect_alarm("G00 X1000000\nM30\n", alarm::kValueOutOfRange, 1, 5);
  expect_alarm("N123456789\nM30\n", alarm::kValueOutOfRange, 1, 1);
  expect_alarm("O12345\nM30\n", alarm::kValueOutOfRange, 1, 1);
  expect_alarm("M1000\n", alarm::kValueOutOfRange, 1, 1);
}

TEST(MinimalInterpreterAlarms, LexicalAlarms) {
  expect_alarm("G00 #1=5\nM30\n", alarm::kUnexpectedCharacter, 1, 5);
  expect_alarm("G00 X1 (never closed\nM30\n", alarm::kUnclosedComment, 1, 8);
}

TEST(MinimalInterpreterAlarms, ProgramEndMissing) {
  expect_alarm("G00 X1\nG00 Z1\n", alarm::kProgramEndMissing, 2, 0,
               "program end M30 or M02 missing");
  expect_alarm("G00 X1\n%\n", alarm::kProgramEndMissing, 2, 0);
  expect_alarm("", alarm::kProgramEndMissing, 1, 0);
}

TEST(MinimalInterpreterAlarms, FirstAlarmInTheProgramWins) {
  // Line 2 has two faults; the leftmost is reported, and the later line is never reached.
  expect_alarm("G00 X1\nG00 Q1 X1 X2\nG02\nM30\n", alarm::kUnknownAddress, 2, 5);
  // A word fault left of a lexical fault on the same line comes first.
  expect_alarm("G00 Q1 X1.2.3\nM30\n", alarm::kUnknownAddress, 1, 5);
}

}  // namespace
}  // namespace mcnc::interp
