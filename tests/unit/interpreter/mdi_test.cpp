// Blocks the operator types (MDI) and programs the operator selects: the interpreter ends MDI
// blocks at their text's end; the channel's source checks both before they run, keeps its own
// program while MDI blocks run, and goes back to it at the next rewind.
#include "channel/interp/interpreter_source.hpp"
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <string>

namespace mcnc::interp::test {
namespace {

RunResult run_mdi(const std::string& text) {
  Interpreter in(lathe());
  if (auto a = in.start_mdi(text)) {
    RunResult r;
    r.alarm = *a;
    return r;
  }
  return drain(in);
}

TEST(Mdi, BlocksEndWithTheirTextAndAreNamedMdi) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start_mdi("G00 X20 Z5\nG01 Z-10 F100").has_value());
  const RunResult r = drain(in);  // a command's file lives as long as its interpreter
  ASSERT_FALSE(r.alarm.has_value()) << r.alarm->text;
  ASSERT_TRUE(r.ended);
  ASSERT_EQ(r.commands.size(), 3U);
  EXPECT_AT(r.commands[0], 10.0, 5.0);  // X is a diameter: 10 as the radius
  EXPECT_AT(r.commands[1], 10.0, -10.0);
  EXPECT_EQ(r.commands[2].op, Op::end);
  EXPECT_EQ(r.commands[2].code, 0);
  ASSERT_NE(r.commands[0].file, nullptr);
  EXPECT_EQ(*r.commands[0].file, kMdiName);
}

TEST(Mdi, M30M02AndM99EndThemWithTheirCode) {
  for (const auto& [text, code] :
       {std::pair{"G00 Z1 M30", 30}, std::pair{"G00 Z1 M02", 2}, std::pair{"G00 Z1 M99", 99}}) {
    const RunResult r = run_mdi(text);
    ASSERT_FALSE(r.alarm.has_value()) << text << ": " << r.alarm->text;
    ASSERT_EQ(r.of(Op::end).size(), 1U) << text;
    EXPECT_EQ(r.of(Op::end)[0].code, code) << text;
    EXPECT_EQ(r.of(Op::rapid).size(), 1U) << text;  // M99 does not loop back
  }
}

TEST(Mdi, ABadBlockIsAnAlarmWithWhereAndNothingOfIt) {
  const RunResult r = run_mdi("G00 X10\nG01 Z5 F");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->program, kMdiName);
  EXPECT_EQ(r.alarm->line, 2);
  EXPECT_TRUE(r.commands.empty());  // the text is parsed whole before anything runs
}

// X and Z, on a channel that runs only what a machine without PLC can.
InterpreterConfig xz() {
  InterpreterConfig c;
  c.channel = 1;
  c.axes = {AxisConfig{'X', true}, AxisConfig{'Z', false}};
  return c;
}

// The commands of the source's run under way, to its end.
std::vector<Command> pull_all(InterpreterSource& s) {
  std::vector<Command> out;
  while (auto r = s.next()) {
    if (std::holds_alternative<ProgramAlarm>(*r)) {
      ADD_FAILURE() << std::get<ProgramAlarm>(*r).text;
      break;
    }
    out.push_back(std::get<Command>(*r));
  }
  return out;
}

TEST(ProgramCheck, FindsWhatTheChannelCannotRunBeforeItRuns) {
  const CheckedProgram ok = InterpreterSource::check(xz(), "G00 X10\nG00 Z2\nM30\n", "A.nc", false);
  EXPECT_FALSE(ok.alarm.has_value());
  EXPECT_EQ(ok.block_count, 3U);
  EXPECT_EQ(ok.name, "A.nc");
  // A T code needs the PLC node this channel lacks: an alarm on line 2, before anything moves.
  const CheckedProgram tool =
      InterpreterSource::check(xz(), "G00 X10\nT0101\nM30\n", "B.nc", false);
  ASSERT_TRUE(tool.alarm.has_value());
  EXPECT_EQ(tool.alarm->line, 2);
  EXPECT_EQ(tool.alarm->program, "B.nc");
  const CheckedProgram mdi = InterpreterSource::check(xz(), "G00 X10 Z5", "MDI", true);
  EXPECT_FALSE(mdi.alarm.has_value());
  EXPECT_EQ(mdi.block_count, 1U);
  // The same text as a program lacks its end.
  EXPECT_TRUE(InterpreterSource::check(xz(), "G00 X10 Z5", "C.nc", false).alarm.has_value());
}

TEST(ProgramCheck, TheGearBoxsWordsAreCheckedAndTheChannelsCoordinationRunsIt) {
  // G81.4's words are checked first (1120 at the word); whether the channel has a gear box is
  // its coordination's check when the block runs (1254), as G51.8's cam is (1253).
  const CheckedProgram egb =
      InterpreterSource::check(xz(), "G00 X10\nG81.4 T20 L1\nG80.4\nM30\n", "E.nc", false);
  EXPECT_FALSE(egb.alarm.has_value()) << egb.alarm->text;
  const CheckedProgram bad =
      InterpreterSource::check(xz(), "G00 X10\nG81.4 T0\nM30\n", "F.nc", false);
  ASSERT_TRUE(bad.alarm.has_value());
  EXPECT_EQ(bad.alarm->number, alarm::kBadWordValue);
  EXPECT_EQ(bad.alarm->line, 2);
}

TEST(ProgramCheck, MdiBlocksRunBetweenRunsOfTheChannelsOwnProgram) {
  InterpreterSource source(xz());
  ASSERT_FALSE(source.load("G00 X40\nG00 Z7\nM30\n", "OWN.nc").has_value());
  EXPECT_TRUE(source.has_program());
  source.prepare_mdi(InterpreterSource::check(xz(), "G00 Z3", "MDI", true));
  const AxisVector at{1.0, 2.0};
  ASSERT_FALSE(source.start_mdi(at).has_value());
  EXPECT_EQ(source.block_count(), 1U);
  std::vector<Command> mdi = pull_all(source);
  ASSERT_EQ(mdi.size(), 2U);
  EXPECT_AT(mdi[0], 1.0, 3.0);  // X stays where it stands
  EXPECT_EQ(mdi[1].op, Op::end);

  source.rewind(at);
  EXPECT_EQ(source.block_count(), 3U);
  const std::vector<Command> own = pull_all(source);
  ASSERT_EQ(own.size(), 3U);
  EXPECT_AT(own[1], 20.0, 7.0);
  EXPECT_EQ(own[2].code, 30);
}

TEST(ProgramCheck, AnAdoptedProgramRunsFromTheNextRewindAndABadOneStopsThere) {
  InterpreterSource source(xz());
  ASSERT_FALSE(source.load("G00 X40\nM30\n", "OWN.nc").has_value());
  source.adopt(InterpreterSource::check(xz(), "G00 Z9\nG00 Z8\nM30\n", "NEW.nc", false));
  source.rewind(AxisVector{});
  const std::vector<Command> run = pull_all(source);
  ASSERT_EQ(run.size(), 3U);
  EXPECT_AT(run[0], 0.0, 9.0);
  ASSERT_NE(run[0].file, nullptr);
  EXPECT_EQ(*run[0].file, "NEW.nc");

  source.adopt(InterpreterSource::check(xz(), "G00 X10\nT0101\nM30\n", "BAD.nc", false));
  EXPECT_FALSE(source.has_program());
  source.rewind(AxisVector{});
  const auto first = source.next();
  ASSERT_TRUE(first.has_value());
  ASSERT_TRUE(std::holds_alternative<ProgramAlarm>(*first));
  EXPECT_EQ(std::get<ProgramAlarm>(*first).line, 2);
}

TEST(ProgramCheck, StartingMdiWithoutBlocksIsAnAlarm) {
  InterpreterSource source(xz());
  const auto alarm = source.start_mdi(AxisVector{});
  ASSERT_TRUE(alarm.has_value());
  const auto pulled = source.next();
  ASSERT_TRUE(pulled.has_value());
  EXPECT_TRUE(std::holds_alternative<ProgramAlarm>(*pulled));
}

}  // namespace
}  // namespace mcnc::interp::test
