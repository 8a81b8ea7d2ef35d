#pragma once
// A program ready to run: every line parsed when the program is loaded (so a syntax error is an
// alarm before the program moves anything), the N numbers indexed, and the block structure
// matched: WHILE-DO m with END m, IF with ELIF/ELSE/ENDIF, within the nesting limits.
#include "channel/interp/canonical_command.hpp"
#include "channel/interp/parse/statement.hpp"
#include "channel/interp/program/program_text.hpp"

#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace mcnc::interp::parse {

struct StructureLimits {
  int max_while_nesting = 5;  // spec dafeng L7133
  int max_if_nesting = 10;    // spec dafeng L7035
  int max_loop_label = 0;     // DO m: m up to this (GSK and FANUC: 3); 0 = any positive m
};

struct ParsedProgram {
  std::optional<int> number;
  std::string file;
  std::shared_ptr<const std::string> source;  // the file's text: what the lines' text views
  std::vector<Line> lines;
  Arena arena;  // the words and expressions of `lines`
  // For a WHILE or END line: the index of its partner. For IF / ELIF / ELSE: the next branch
  // line of the same IF (ELIF, ELSE or ENDIF); for ENDIF itself -1. -1 elsewhere.
  std::vector<int> partner;
  // For ELIF / ELSE lines: the ENDIF of their IF.
  std::vector<int> endif_of;
  // The innermost WHILE line enclosing each line (-1: none); BREAK and CONTINUE use it.
  std::vector<int> loop_of;
  // N number -> line indices in program order.
  std::unordered_map<std::int64_t, std::vector<int>> sequence_lines;
};

struct ParsedProgramResult {
  std::optional<ParsedProgram> program;
  std::optional<ProgramAlarm> alarm;
};

ParsedProgramResult parse_program(const program::Program& program, StructureLimits limits = {});

}  // namespace mcnc::interp::parse
