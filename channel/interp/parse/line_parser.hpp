#pragma once
// Parses one program line into a Line (statement.hpp). Lexical rules: spec dafeng §1.7-§1.9 and
// docs/dialect.md "Blocks and words": comments `( )`, `;` and `//` (the rest of the line), block
// skip `/` or `/n` at the start, an optional N word, then one statement. Words are one or two
// letters (UX..UC, PS, SP, NQ, PQ, UR, PA, PN, DT, DC), a comma word (,C ,R ,A), an optional
// sub-index (`S2=`), and a literal or a macro operand (`#1`, `-#1`, `[expr]`, `SIN[30]`).
#include "channel/interp/parse/statement.hpp"

#include <optional>
#include <string_view>

namespace mcnc::interp::parse {

struct ParseError {
  int number = 0;
  std::string text;
  int column = 0;
};

struct LineParse {
  Line line;
  std::optional<ParseError> error;
};

// `text` without its line terminator (a trailing '\r' is tolerated); `line_number` is stored.
// Words and expressions go to `arena`; the line refers to them by index.
LineParse parse_line(std::string_view text, int line_number, Arena& arena);
// The same into `line`, a default-constructed Line (a loaded program's lines are parsed in
// place); the parse error, if any (then `line` holds what was parsed before it).
std::optional<ParseError> parse_line_into(std::string_view text, int line_number, Arena& arena,
                                          Line& line);
// The syntax check of parse_line_into, without what only running the line needs: the same
// error, if any, and in `line` (a default-constructed Line) its number, skip level, N number
// and its statement's kind, label, column and `then` statement. No words, expressions,
// assignments or messages are kept: its word indices refer to nothing.
// A program's load checks the lines it does not keep this way (ParsedProgram).
std::optional<ParseError> check_line_into(std::string_view text, int line_number, Line& line);

}  // namespace mcnc::interp::parse
