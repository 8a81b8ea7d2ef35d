// Splitting program files. Spec references: dialect-dafeng-lathe.md (L113 program format and
// `%`, L154 O has 4 digits) and dialect-gsk-lathe-and-iso-mill.md (L86 O0000-O9999, L1098 and
// L1617 no variable as the program number).
#include "channel/interp/program/program_text.hpp"
#include "channel/interp/program/program_format_alarms.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::program {
namespace {

// The program's lines, read from its text as the interpreter reads them.
std::vector<RawLine> lines_of(const Program& p, std::vector<std::string>& texts) {
  std::vector<RawLine> out;
  LineReader reader(*p.text, p.begin, p.end, p.first_line);
  RawLine raw;
  while (reader.next(raw)) {
    texts.emplace_back(raw.text);
    out.push_back(RawLine{raw.line, {}, raw.offset, raw.next});  // the text is in `texts`
  }
  EXPECT_EQ(static_cast<int>(out.size()), p.line_count);
  return out;
}

std::vector<int> line_numbers(const Program& p) {
  std::vector<std::string> texts;
  std::vector<int> out;
  for (const RawLine& l : lines_of(p, texts)) {
    out.push_back(l.line);
  }
  return out;
}

void expect_alarm(std::string_view text, int number, int line, int column) {
  const SplitResult r = split_programs(text, "f.nc");
  ASSERT_TRUE(r.alarm) << text;
  EXPECT_EQ(r.alarm->number, number) << text << ": " << r.alarm->text;
  EXPECT_EQ(r.alarm->line, line) << text;
  EXPECT_EQ(r.alarm->column, column) << text;
  EXPECT_EQ(r.alarm->program, "f.nc");
  EXPECT_FALSE(r.alarm->text.empty());
  EXPECT_TRUE(r.programs.empty());
}

TEST(SplitPrograms, TapeWithOneProgramKeepsFileLineNumbers) {
  // The layout of launch/programs/*.nc: leader %, O line with a name, blocks, trailer %.
  const SplitResult r =
      split_programs("%\nO0100 (demo: rough)\nN10 G00 X64.\r\nN20 M30\n%\n", "demo.nc");
  ASSERT_FALSE(r.alarm);
  ASSERT_EQ(r.programs.size(), 1u);
  const Program& p = r.programs[0];
  EXPECT_EQ(p.number, 100);
  EXPECT_EQ(p.name, "demo: rough");
  EXPECT_EQ(p.file, "demo.nc");
  EXPECT_EQ(p.header_line, 2);
  EXPECT_EQ(p.header_column, 1);
  EXPECT_EQ(line_numbers(p), (std::vector<int>{2, 3, 4}));
  std::vector<std::string> texts;
  lines_of(p, texts);
  ASSERT_EQ(texts.size(), 3u);
  EXPECT_EQ(texts[1], "N10 G00 X64.");  // CR of CRLF removed
  EXPECT_EQ(texts[0], "O0100 (demo: rough)");
}

TEST(SplitPrograms, SeveralProgramsInOneFile) {
  const SplitResult r = split_programs(
      "%\n(header)\nO0001\nM98 P1000\nM30\n\nO1000 (SUB)\nG00 X1\nM99\n%\nO2000\n", "multi.nc");
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_EQ(r.programs.size(), 2u);
  EXPECT_EQ(r.programs[0].number, 1);
  EXPECT_EQ(r.programs[0].name, "");
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{3, 4, 5, 6}));
  EXPECT_EQ(r.programs[1].number, 1000);
  EXPECT_EQ(r.programs[1].name, "SUB");
  EXPECT_EQ(line_numbers(r.programs[1]), (std::vector<int>{7, 8, 9}));
}

TEST(SplitPrograms, TextAfterTheClosingPercentIsIgnored) {
  // Dafeng spec L113 (manual L285): everything after % is ignored, also a further O line.
  const SplitResult r = split_programs("O0001\nM30\n%\nO0001\ngarbage #\n", "f.nc");
  ASSERT_FALSE(r.alarm);
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{1, 2}));
}

TEST(SplitPrograms, TextBeforeTheLeaderIsIgnoredOnlyWhenItIsComments) {
  const SplitResult r = split_programs("\n(tape label)\n  %  title\nO7\nM30\n", "f.nc");
  ASSERT_FALSE(r.alarm);
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_EQ(r.programs[0].number, 7);
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{4, 5}));
}

TEST(SplitPrograms, FileWithoutOLineIsOneUnnumberedProgram) {
  const SplitResult r = split_programs("(cam header)\n\nG00 X1\n\nM30", "part.nc");
  ASSERT_FALSE(r.alarm);
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_FALSE(r.programs[0].number);
  EXPECT_EQ(r.programs[0].header_line, 0);
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{3, 4, 5}));  // last line unterminated
}

TEST(SplitPrograms, EmptyOrCommentOnlyFileHasNoProgram) {
  EXPECT_TRUE(split_programs("", "f.nc").programs.empty());
  EXPECT_TRUE(split_programs("%\n(nothing)\n%\n", "f.nc").programs.empty());
  EXPECT_FALSE(split_programs("", "f.nc").alarm);
}

TEST(SplitPrograms, ProgramNumberForms) {
  // 1-4 digits, leading zeros optional, O0000 allowed (GSK spec L86), lower case, blanks.
  const SplitResult r = split_programs(
      "O0\nM30\no12 ;c\nM30\nO 9999(  NAME  )(second)\nM30\n O0013 // x\nM30\n", "f.nc");
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_EQ(r.programs.size(), 4u);
  EXPECT_EQ(r.programs[0].number, 0);
  EXPECT_EQ(r.programs[1].number, 12);
  EXPECT_EQ(r.programs[2].number, 9999);
  EXPECT_EQ(r.programs[2].name, "NAME");
  EXPECT_EQ(r.programs[3].number, 13);
  EXPECT_EQ(r.programs[3].header_column, 2);
}

TEST(SplitPrograms, MacroKeywordsAreNotProgramNumbers) {
  const SplitResult r = split_programs(
      "O0001\nWHILE[#1 LT 3] DO1\n#2=[#1 OR 4]\nIF[#1 EQ 0] GOTO 10\n#3=ROUND[#1]\nEND1\n"
      "(O0002 in a comment)\nG00 X1 ; O0003\nM30\n",
      "f.nc");
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_EQ(r.programs[0].line_count, 9);
}

TEST(SplitPrograms, Alarms) {
  expect_alarm("O\nM30\n", alarm::kProgramNumberMissing, 1, 1);
  expect_alarm("%\n  O ;\n", alarm::kProgramNumberMissing, 2, 3);
  expect_alarm("O-1\n", alarm::kProgramNumberFormat, 1, 1);
  expect_alarm("O1.5\n", alarm::kProgramNumberFormat, 1, 1);
  expect_alarm("O#1\n", alarm::kProgramNumberFormat, 1, 1);      // GSK spec L1098, L1617
  expect_alarm("O12345\n", alarm::kProgramNumberTooLong, 1, 1);  // Dafeng spec L154
  expect_alarm("O00001\n", alarm::kProgramNumberTooLong, 1, 1);
  expect_alarm("O0001\nM99\nO0002\nM99\nO0001\nM99\n", alarm::kDuplicateProgramNumber, 5, 1);
  expect_alarm("O1\nM99\nO0001\n", alarm::kDuplicateProgramNumber, 3, 1);
  expect_alarm("O0001\nN10 O0002\n", alarm::kProgramNumberNotAtStart, 2, 5);
  expect_alarm("O0001\n/O0002\n", alarm::kProgramNumberNotAtStart, 2, 2);
  expect_alarm("O0001\nG00 X1O2\n", alarm::kProgramNumberNotAtStart, 2, 7);
  expect_alarm("O0001 G00 X0\n", alarm::kWordsAfterProgramNumber, 1, 7);
  expect_alarm("O0001 (a) O0002\n", alarm::kWordsAfterProgramNumber, 1, 11);
  expect_alarm("%\nG00 X1\nO0001\nM30\n%\n", alarm::kBlockOutsideProgram, 2, 1);
  // The file is read once: a block before the first O line is known to be outside a program
  // only at that O line, and is still the alarm, ahead of what is wrong with the O line.
  expect_alarm("(head)\n  G00 X1\nG01 X2\n\nO0001\nM30\n", alarm::kBlockOutsideProgram, 2, 3);
  expect_alarm("G00 X1\nG01 X2 O5\n", alarm::kBlockOutsideProgram, 1, 1);
  expect_alarm("G00 X1\nO12345\nO0001\nO0001\n", alarm::kBlockOutsideProgram, 1, 1);
}

// An O line after the closing `%` does not make the tape's blocks outside a program.
TEST(SplitPrograms, OLinesAfterTheTapeDoNotCount) {
  const SplitResult r = split_programs("%\nG00 X1\nM30\n%\nO0002\nM99\n", "f.nc");
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_EQ(r.programs.size(), 1u);
  EXPECT_FALSE(r.programs[0].number);
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{2, 3}));
}

// ISO code writes the program number with `:` where EIA writes `O` (FANUC programs punched in
// ISO code): the same number, the same rules.
TEST(SplitPrograms, IsoColonIsTheProgramNumber) {
  const SplitResult r = split_programs("%\n:1234 (NAME)\nM98 P2\nM30\n :0002\nM99\n%\n", "f.nc");
  ASSERT_FALSE(r.alarm) << r.alarm->text;
  ASSERT_EQ(r.programs.size(), 2u);
  EXPECT_EQ(r.programs[0].number, 1234);
  EXPECT_EQ(r.programs[0].name, "NAME");
  EXPECT_EQ(line_numbers(r.programs[0]), (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(r.programs[1].number, 2);
  EXPECT_EQ(r.programs[1].header_column, 2);
  expect_alarm(":\nM30\n", alarm::kProgramNumberMissing, 1, 1);
  expect_alarm(":12345\n", alarm::kProgramNumberTooLong, 1, 1);
  expect_alarm(":#1\n", alarm::kProgramNumberFormat, 1, 1);
  expect_alarm(":0001\nN10 :0002\n", alarm::kProgramNumberNotAtStart, 2, 5);
  expect_alarm("O0001\nM99\n:1\nM99\n", alarm::kDuplicateProgramNumber, 3, 1);
}

TEST(SplitPrograms, UnclosedCommentOnTheOLineIsLeftToTheLexer) {
  // The O line is passed on; the block lexer raises its unclosed-comment alarm when read.
  const SplitResult r = split_programs("O0001 (name\nM30\n", "f.nc");
  ASSERT_FALSE(r.alarm);
  EXPECT_EQ(r.programs[0].name, "name");
}

TEST(SplitPrograms, Label) {
  EXPECT_EQ(program_label(12), "O0012");
  EXPECT_EQ(program_label(9999), "O9999");
}

}  // namespace
}  // namespace mcnc::interp::program
