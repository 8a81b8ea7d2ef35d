#include "channel/interp/block_lexer.hpp"
#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp {
namespace {

TEST(BlockLexer, SplitsWordsWithColumnsAndValues) {
  const LexedLine l = lex_line("N10 G01X-12.5 z+3 F.5 W7.");
  ASSERT_FALSE(l.error);
  ASSERT_EQ(l.words.size(), 6u);
  EXPECT_EQ(l.words[0].letter, 'N');
  EXPECT_EQ(l.words[0].value, 10.0);
  EXPECT_EQ(l.words[0].column, 1);
  EXPECT_EQ(l.words[1].letter, 'G');
  EXPECT_EQ(l.words[1].value, 1.0);
  EXPECT_EQ(l.words[1].column, 5);
  EXPECT_EQ(l.words[2].letter, 'X');
  EXPECT_EQ(l.words[2].value, -12.5);
  EXPECT_TRUE(l.words[2].has_sign);
  EXPECT_TRUE(l.words[2].has_point);
  EXPECT_EQ(l.words[2].frac_digits, 1);
  EXPECT_EQ(l.words[2].column, 8);
  EXPECT_EQ(l.words[3].letter, 'Z');  // lower case is upper-cased
  EXPECT_EQ(l.words[3].value, 3.0);
  EXPECT_TRUE(l.words[3].has_sign);
  EXPECT_EQ(l.words[3].column, 15);
  EXPECT_EQ(l.words[4].letter, 'F');
  EXPECT_EQ(l.words[4].value, 0.5);
  EXPECT_EQ(l.words[5].letter, 'W');
  EXPECT_EQ(l.words[5].value, 7.0);
  EXPECT_TRUE(l.words[5].has_point);
  EXPECT_EQ(l.words[5].frac_digits, 0);
}

TEST(BlockLexer, ValuesParseToTheNearestDouble) {
  const LexedLine l = lex_line("X0.1 Z123456.789 U-0.3");
  ASSERT_FALSE(l.error);
  ASSERT_EQ(l.words.size(), 3u);
  EXPECT_EQ(l.words[0].value, 0.1);
  EXPECT_EQ(l.words[1].value, 123456.789);
  EXPECT_EQ(l.words[2].value, -0.3);
}

TEST(BlockLexer, BlanksBetweenAddressAndNumberAreAllowed) {
  const LexedLine l = lex_line("G 00 X\t10");
  ASSERT_FALSE(l.error);
  ASSERT_EQ(l.words.size(), 2u);
  EXPECT_EQ(l.words[0].value, 0.0);
  EXPECT_EQ(l.words[1].value, 10.0);
  EXPECT_EQ(l.words[1].column, 6);
}

TEST(BlockLexer, CommentsKeepColumns) {
  const LexedLine l = lex_line("(a comment; with X1) G00 (more) X5");
  ASSERT_FALSE(l.error);
  ASSERT_EQ(l.words.size(), 2u);
  EXPECT_EQ(l.words[0].column, 22);
  EXPECT_EQ(l.words[1].column, 33);
}

TEST(BlockLexer, SemicolonAndDoubleSlashEndTheBlock) {
  const LexedLine a = lex_line("G00 X1 ; Q?? anything #");
  ASSERT_FALSE(a.error);
  EXPECT_EQ(a.words.size(), 2u);
  const LexedLine b = lex_line("G00 X1 // [rest]");
  ASSERT_FALSE(b.error);
  EXPECT_EQ(b.words.size(), 2u);
}

TEST(BlockLexer, PercentLineIsIgnoredAndBlankLineIsEmpty) {
  EXPECT_TRUE(lex_line("%").ignored);
  EXPECT_TRUE(lex_line("  % anything").ignored);
  const LexedLine blank = lex_line("   \t ");
  EXPECT_FALSE(blank.ignored);
  EXPECT_FALSE(blank.error);
  EXPECT_TRUE(blank.words.empty());
}

TEST(BlockLexer, CarriageReturnIsTolerated) {
  const LexedLine l = lex_line("G01 X1\r");
  ASSERT_FALSE(l.error);
  ASSERT_EQ(l.words.size(), 2u);
  EXPECT_EQ(l.words[1].value, 1.0);
}

TEST(BlockLexer, MalformedNumbers) {
  for (const char* text : {"G00 X Z1", "G00 X1.2.3", "G00 X--1", "G00 X1-2", "G00 X.", "G00 X+"}) {
    const LexedLine l = lex_line(text);
    ASSERT_TRUE(l.error) << text;
    EXPECT_EQ(l.error->number, alarm::kMalformedNumber) << text;
    EXPECT_EQ(l.error->column, 5) << text;
    EXPECT_EQ(l.error->text, "malformed number after X") << text;
    EXPECT_EQ(l.words.size(), 1u) << text;  // the words before the error are kept
  }
}

TEST(BlockLexer, UnexpectedCharacter) {
  const LexedLine l = lex_line("G00 #1=5");
  ASSERT_TRUE(l.error);
  EXPECT_EQ(l.error->number, alarm::kUnexpectedCharacter);
  EXPECT_EQ(l.error->column, 5);
  EXPECT_EQ(l.error->text, "unexpected character '#'");
  const LexedLine b = lex_line("G00 \x01");
  ASSERT_TRUE(b.error);
  EXPECT_EQ(b.error->text, "unexpected character byte 0x01");
}

TEST(BlockLexer, UnclosedCommentComesAfterTheWordsBeforeIt) {
  const LexedLine l = lex_line("G00 X1 (no end");
  ASSERT_TRUE(l.error);
  EXPECT_EQ(l.error->number, alarm::kUnclosedComment);
  EXPECT_EQ(l.error->column, 8);
  EXPECT_EQ(l.words.size(), 2u);
}

TEST(BlockLexer, HugeNumberIsOutOfRange) {
  const std::string digits(400, '9');
  const LexedLine l = lex_line("X" + digits);
  ASSERT_TRUE(l.error);
  EXPECT_EQ(l.error->number, alarm::kValueOutOfRange);
  EXPECT_EQ(l.error->column, 1);
}

}  // namespace
}  // namespace mcnc::interp
