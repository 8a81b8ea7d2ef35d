// A word's literal value is what std::from_chars reads from its digits, bit for bit, whether it
// takes the parser's short path (at most 15 digits) or the general one.
#include "channel/interp/parse/line_parser.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::interp::parse {
namespace {

double word_value(const std::string& line) {
  Arena arena;
  const LineParse parsed = parse_line(line, 1, arena);
  EXPECT_FALSE(parsed.error.has_value()) << line;
  EXPECT_EQ(arena.words.size(), 1U) << line;
  return arena.words.empty() ? 0.0 : arena.words.front().value;
}

TEST(LineParser, LiteralsAreReadAsFromCharsReadsThem) {
  std::vector<std::string> numbers{"0",
                                   "0.",
                                   ".5",
                                   "5.",
                                   "1",
                                   "0.1",
                                   "0.3",
                                   "123.456",
                                   "000000000000001",
                                   "999999999999999",
                                   "99999999999999.9",
                                   "0.000000000000001",
                                   "1000000000000000",
                                   "0.30000000000000004",
                                   "12345678901234.5",
                                   "1.7976931348623157"};
  std::mt19937_64 random(23);
  std::uniform_int_distribution<int> digit(0, 9);
  std::uniform_int_distribution<int> length(1, 17);
  for (int i = 0; i < 50000; ++i) {
    std::string n;
    const int count = length(random);
    for (int d = 0; d < count; ++d) {
      n += static_cast<char>('0' + digit(random));
    }
    n.insert(n.begin() + std::uniform_int_distribution<int>(0, count)(random), '.');
    numbers.push_back(n);
  }
  for (const std::string& n : numbers) {
    double expected = 0.0;
    std::from_chars(n.data(), n.data() + n.size(), expected);
    if (expected > 1e15) {
      continue;  // out of range (alarm 1007), whatever the path
    }
    const double got = word_value("X" + n);
    EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << n << ": " << got << " " << expected;
    EXPECT_EQ(word_value("Z-" + n), -expected) << n;
  }
}

// What a line parses to, words and error, as text: two parses agree when their texts do.
std::string parsed_words(const std::string& line) {
  Arena arena;
  const LineParse parsed = parse_line(line, 1, arena);
  std::string out;
  for (const Word& w : arena.words) {
    out += std::string(1, w.address.first) +
           (w.address.second != 0 ? std::string(1, w.address.second) : "") + "@" +
           std::to_string(w.column) + "[" + std::to_string(w.index) +
           "]=" + (w.literal ? std::to_string(w.value) : "expr") + (w.has_point ? "." : "") + " ";
  }
  if (parsed.error) {
    out += "error " + std::to_string(parsed.error->number) + " at " +
           std::to_string(parsed.error->column) + ": " + parsed.error->text;
  }
  return out;
}

// A one-letter word with a literal right after it is read by a short path; a blank after the
// letter takes the general path. Both give the same words, columns, sub-indices and errors; a
// line with lower case or a comment is rewritten first, and parses as its upper-case form.
TEST(LineParser, PlainWordsParseAsTheGeneralPathParsesThem) {
  // The general path's twin of each word has a blank after the letter, which moves no column.
  const std::vector<std::pair<std::string, std::string>> same{
      {"X40.", "X 40."},
      {"Z-10.", "Z -10."},
      {"Z-10.", "Z- 10."},
      {"X+.5", "X +.5"},
      {"S2=1000", "S 2=1000"},
      {"S2 =1000", "S 2 =1000"},
      {"Q123=4", "Q 123=4"},
      {"Q1234=4", "Q 1234=4"},
      {"X1.2.3", "X 1.2.3"},
      {"X12#1", "X 12#1"},
      {"X1[2]", "X 1[2]"},
      {"X.", "X ."},
      {"X1234567890123456", "X 1234567890123456"},
      {"X12345678901234567", "X 12345678901234567"},
      {"G01 X1 O2", "G01 X1 O 2"},
  };
  for (const auto& [plain, general] : same) {
    EXPECT_EQ(parsed_words(plain), parsed_words(general)) << plain << " | " << general;
  }
  EXPECT_EQ(parsed_words("G01 X40. Z-10. F500"),
            "G@1[-1]=1.000000 X@5[-1]=40.000000. "
            "Z@10[-1]=-10.000000. F@16[-1]=500.000000 ");
  EXPECT_EQ(parsed_words("S2=1000"), "S@1[2]=1000.000000 ");
  EXPECT_EQ(parsed_words("g01 x40. (a comment) z-10.;f500"),
            parsed_words("G01 X40.             Z-10."));
}

// What the syntax check sees of a line: its error and what the block structure and the jumps
// need.
std::string checked_shape(const std::optional<ParseError>& error, const Line& line) {
  std::ostringstream out;
  if (error) {
    out << "error " << error->number << " at " << error->column << ": " << error->text;
    return out.str();
  }
  out << line.line << " /" << line.skip_level << " N" << line.sequence << "@"
      << line.sequence_column;
  for (const Statement* s = &line.statement; s != nullptr; s = s->then.get()) {
    out << " kind " << static_cast<int>(s->kind) << " label " << s->label << " column " << s->column
        << " direction " << static_cast<int>(s->direction);
  }
  return out.str();
}

// The lines of the fuzz corpus (lathe and mill programs, and the inputs that once crashed the
// interpreter) and of the example and conformance programs, each whole and cut after every
// character (which makes most of them malformed): the check that a long program's load does
// for the lines it does not keep gives the same error, number, text and column, as the full
// parse, and the same N number and statement structure.
TEST(LineParser, TheCheckGivesTheFullParsesErrorsAndStructure) {
  const std::filesystem::path root(MCNC_SOURCE_DIR);
  std::vector<std::filesystem::path> files;
  for (const char* dir :
       {"tests/fuzz/corpus", "tests/fuzz/crashes", "launch/programs", "tests/conformance"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / dir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".nc") {
        files.push_back(entry.path());
      }
    }
  }
  ASSERT_GT(files.size(), 100U);
  int lines = 0;
  int errors = 0;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    std::string text;
    int number = 0;
    while (std::getline(in, text)) {
      ++number;
      for (std::size_t cut = 1; cut <= text.size(); ++cut) {
        const std::string_view part = std::string_view(text).substr(0, cut);
        Arena arena;
        Line parsed;
        const std::optional<ParseError> parse_error = parse_line_into(part, number, arena, parsed);
        Line checked;
        const std::optional<ParseError> check_error = check_line_into(part, number, checked);
        ASSERT_EQ(checked_shape(check_error, checked), checked_shape(parse_error, parsed))
            << file << ":" << number << ": " << part;
        ++lines;
        errors += parse_error ? 1 : 0;
      }
    }
  }
  // Both kinds were compared, many of each.
  EXPECT_GT(errors, 10000);
  EXPECT_GT(lines - errors, 10000);
}

}  // namespace
}  // namespace mcnc::interp::parse
