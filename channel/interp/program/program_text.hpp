#pragma once
// Splits the text of one program file into its programs (pure: no file I/O). It knows only the
// file format: the `%` tape marks, `O` program-number lines and which lines belong to which
// program. Blocks are passed on untouched, with their 1-based line numbers in the file, so that
// the interpreter's alarms point into the file. Rules and decisions: docs/dialect.md, "Program
// format". The file is read line by line (TextSource): a program is a range of it, not a copy.
#include "channel/interp/program/text_source.hpp"
#include "channel/interp/program_alarm.hpp"

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::interp::program {

inline constexpr int kMaxProgramNumber = 9999;  // O + 4 digits (Dafeng spec L113, §1.10 L154)

// One program of a file: where it is, and what its O line says.
struct Program {
  std::optional<int> number;  // the O number; none for a file without O lines
  std::string name;           // text of the first `( )` comment on the O line, trimmed
  std::string file;           // the file name given to split_programs
  int header_line = 0;        // line of the O word; 0 when there is none
  int header_column = 0;      // 1-based column of the O word; 0 when there is none
  // Its lines: the O line itself (when there is one) and every following line up to the next
  // O line or the end of the tape, blank and comment-only lines included. They are bytes
  // [begin, end) of `text`, the first one line `first_line` of the file.
  int first_line = 0;
  int line_count = 0;
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
  std::shared_ptr<const TextSource> text;  // the file's text, shared by its programs
};

// Either the programs of the file in file order, or the first alarm (then `programs` is empty:
// a file with a format error yields nothing, so a half-read file is never run).
struct SplitResult {
  std::vector<Program> programs;
  std::optional<ProgramAlarm> alarm;  // `program` names the file
};

// Reads `text` once, line by line.
SplitResult split_programs(std::shared_ptr<const TextSource> text, const std::string& file_name);
// The same over a text held in memory.
SplitResult split_programs(std::string_view text, const std::string& file_name);

// "O0012": the spelling used in alarm texts and file names (4 digits, zero padded).
std::string program_label(int number);

}  // namespace mcnc::interp::program
