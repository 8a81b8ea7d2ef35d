#pragma once
// One program line, parsed once when its program is loaded: an NC block (address words whose
// values are literals or macro expressions) or a macro statement (assignment, IF, WHILE, GOTO,
// ...). Execution evaluates the expressions; parsing never looks at variable values.
#include "channel/interp/macro/expression.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::interp::parse {

// An address: one letter ("X"), two letters ("UA", "PS", "SP") or a comma word (",C").
struct Address {
  char first = 0;
  char second = 0;  // 0 for one-letter addresses
  bool comma = false;

  bool is(char a) const { return first == a && second == 0 && !comma; }
  bool is(char a, char b) const { return first == a && second == b && !comma; }
  friend bool operator==(const Address&, const Address&) = default;
};

struct Word {
  // The value: a literal, or expression `expression` of the arena (`X#1`, `X[#1+2]`).
  double value = 0.0;
  std::int32_t expression = -1;  // index in its line's Arena
  std::int32_t column = 0;       // 1-based column of the address
  std::int16_t index = -1;       // the n of `S2=1000`, `Q1=2`, `PS1=500`; -1 when absent
  Address address;
  bool literal = true;
  bool has_point = false;  // literal written with a decimal point
};

enum class StatementKind : std::uint8_t {
  empty,          // blank, comment only, the O line, a `%` line
  block,          // NC words
  assignment,     // #n = expr
  go_to,          // GOTO / GOTOF / GOTOB target
  if_then,        // IF[cond] <statement> (THEN optional): `then` holds the statement
  if_block,       // IF[cond] alone: the block form up to ENDIF
  elif,           // ELIF[cond] / ELSEIF[cond]
  else_branch,    // ELSE
  endif,          // ENDIF
  while_do,       // WHILE[cond] DO m
  loop_end,       // END m
  loop_break,     // BREAK / BRK
  loop_continue,  // CONTINUE / CONT
  channel_only,   // CH n
};

enum class GotoDirection : std::uint8_t { wrap, forward, backward };  // GOTO, GOTOF, GOTOB

// The words and expressions of a run of program lines, in one place: a large program costs no
// allocation per line. Statements refer to them by index.
struct Arena {
  std::vector<Word> words;
  std::vector<macro::Expression> expressions;
  std::vector<std::string> messages;  // the first `( )` comment of lines that have one
};

struct Statement {
  StatementKind kind = StatementKind::empty;
  std::uint32_t first_word = 0;  // block: arena words [first_word, first_word + word_count)
  std::uint32_t word_count = 0;
  std::unique_ptr<macro::Assignment> assignment;  // assignment (held apart: most lines are blocks)
  int condition = -1;                             // IF / ELIF / WHILE: arena expression index
  int target = -1;                                // GOTO: arena expression index
  GotoDirection direction = GotoDirection::wrap;
  int label = 0;                    // DO m / END m; CH n
  int column = 0;                   // of the statement's first character
  std::unique_ptr<Statement> then;  // if_then
};

struct Line {
  int line = 0;                // 1-based line in the file
  int skip_level = 0;          // `/` (1) or `/n`; 0: not skippable
  std::int64_t sequence = -1;  // N number, -1 when none
  int sequence_column = 0;
  Statement statement;
  int message = -1;       // arena index of the first `( )` comment: the #3000 / #3006 message
  std::string_view text;  // the line as written, held with the line by its ParsedProgram
  const Arena* arena = nullptr;  // what `statement`'s indices refer to
};

}  // namespace mcnc::interp::parse
