#pragma once
// Splits one program line into address words. It knows only the lexical rules (comments, `%`
// lines, number syntax); what a word means is decided by the interpreter.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::interp {

struct LexWord {
  char letter = 0;  // upper case
  double value = 0.0;
  bool has_sign = false;   // '+' or '-' written
  bool has_point = false;  // decimal point written
  int frac_digits = 0;     // digits after the decimal point
  int column = 0;          // 1-based column of the letter
};

struct LexError {
  int number = 0;
  std::string text;
  int column = 0;
};

struct LexedLine {
  bool ignored = false;        // a `%` line: nothing on it counts
  std::vector<LexWord> words;  // every word before the first error
  std::optional<LexError> error;
};

// `line` without its line terminator (a trailing '\r' is tolerated).
LexedLine lex_line(std::string_view line);

}  // namespace mcnc::interp
