// A word's literal value is what std::from_chars reads from its digits, bit for bit, whether it
// takes the parser's short path (at most 15 digits) or the general one.
#include "channel/interp/parse/line_parser.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <random>
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

}  // namespace
}  // namespace mcnc::interp::parse
