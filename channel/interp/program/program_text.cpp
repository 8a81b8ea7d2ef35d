#include "channel/interp/program/program_text.hpp"

#include "channel/interp/program/program_format_alarms.hpp"
#include "channel/interp/program_chars.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>

namespace mcnc::interp::program {

namespace {

std::size_t first_non_blank(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && is_blank(line[i])) {
    ++i;
  }
  return i;
}

bool is_percent_line(std::string_view line) {
  const std::size_t i = first_non_blank(line);
  return i < line.size() && line[i] == '%';
}

// What the splitter needs to know about one line: where its executable text starts and where an
// `O` (or `:`) program-number word is, both as indices, ignoring comments (`( )`, `;`, `//`, spec
// L277) and bracketed expressions (an O there belongs to a word such as OR or ROUND).
struct LineShape {
  std::optional<std::size_t> first_exec;
  std::optional<std::size_t> o_word;
};

// Most characters of a line matter to the shape only as its first executable one: the others
// (comment and bracket marks, program-number words, blanks) are looked at one by one.
constexpr std::array<bool, 256> kShapeMarks = [] {
  std::array<bool, 256> marks{};
  for (const char c : {';', '/', '(', '[', ']', ':', 'O', 'o', ' ', '\t'}) {
    marks[static_cast<unsigned char>(c)] = true;
  }
  return marks;
}();

// The marks that are not blanks: a line without any (most blocks) has no comment, bracket or
// program-number word, and its first executable character is its first non-blank one.
constexpr std::array<bool, 256> kShapeMarksBesidesBlanks = [] {
  std::array<bool, 256> marks = kShapeMarks;
  marks[static_cast<unsigned char>(' ')] = false;
  marks[static_cast<unsigned char>('\t')] = false;
  return marks;
}();

LineShape shape_of(std::string_view line) {
  LineShape shape;
  bool any_mark = false;
  for (const char c : line) {
    any_mark |= kShapeMarksBesidesBlanks[static_cast<unsigned char>(c)];
  }
  if (!any_mark) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (!is_blank(line[i])) {
        shape.first_exec = i;
        break;
      }
    }
    return shape;
  }
  int depth = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (!kShapeMarks[static_cast<unsigned char>(c)]) {
      if (!shape.first_exec) {
        shape.first_exec = i;
      }
      continue;
    }
    if (c == ';' || (c == '/' && i + 1 < line.size() && line[i + 1] == '/')) {
      break;
    }
    if (c == '(') {
      const std::size_t close = line.find(')', i + 1);
      if (close == std::string_view::npos) {
        break;  // the lexer reports the unclosed comment when the block is read
      }
      i = close;
      continue;
    }
    if (is_blank(c)) {
      continue;
    }
    if (!shape.first_exec) {
      shape.first_exec = i;
    }
    if (c == '[') {
      ++depth;
    } else if (c == ']' && depth > 0) {
      --depth;
    } else if (c == ':' && depth == 0 && !shape.o_word) {
      shape.o_word = i;  // ISO code's program number `:1234`, EIA's `O1234`
    } else if (to_upper(c) == 'O' && depth == 0 && !shape.o_word) {
      // A letter before it makes the O part of a keyword (GOTO, DO, XOR, POPEN).
      const bool after_letter = i > 0 && is_letter(line[i - 1]);
      std::size_t j = i + 1;
      while (j < line.size() && is_blank(line[j])) {
        ++j;
      }
      // A letter after it makes it a keyword too (OR); anything else is a program number,
      // well formed or not, so that `O-1` and `O#1` are reported rather than passed on.
      const bool before_letter = j < line.size() && is_letter(line[j]);
      if (!after_letter && !before_letter) {
        shape.o_word = i;
      }
    }
  }
  return shape;
}

ProgramAlarm make_alarm(int number, std::string text, const std::string& file, int line,
                        std::size_t index) {
  return ProgramAlarm{number, std::move(text), file, line, static_cast<int>(index) + 1};
}

struct Header {
  int number = 0;
  std::string name;
};

// Parses an O line whose O (or `:`) word starts the block: `O<1-4 digits>`, then only comments.
std::optional<ProgramAlarm> parse_header(std::string_view line, std::size_t o_at, int line_no,
                                         const std::string& file, Header& out) {
  std::size_t i = o_at + 1;
  while (i < line.size() && is_blank(line[i])) {
    ++i;
  }
  if (i < line.size() && (line[i] == '#' || line[i] == '+' || line[i] == '-' || line[i] == '[')) {
    // GSK spec L1098 / L1617: a variable is not allowed as the program number.
    return make_alarm(alarm::kProgramNumberFormat,
                      "program number must be written as 1 to 4 digits", file, line_no, o_at);
  }
  const std::size_t digits_begin = i;
  int value = 0;
  while (i < line.size() && is_digit(line[i])) {
    if (i - digits_begin < 5) {
      value = value * 10 + (line[i] - '0');
    }
    ++i;
  }
  const std::size_t digits = i - digits_begin;
  if (digits == 0) {
    return make_alarm(alarm::kProgramNumberMissing, "O without a program number", file, line_no,
                      o_at);
  }
  if (i < line.size() && line[i] == '.') {
    return make_alarm(alarm::kProgramNumberFormat,
                      "program number must be written as 1 to 4 digits", file, line_no, o_at);
  }
  if (digits > 4) {  // Dafeng spec L113 / L154 (manual L271), GSK spec L86: O + 4 digits
    return make_alarm(alarm::kProgramNumberTooLong, "program number has more than 4 digits", file,
                      line_no, o_at);
  }
  out.number = value;
  out.name.clear();
  bool named = false;
  for (; i < line.size(); ++i) {
    const char c = line[i];
    if (is_blank(c)) {
      continue;
    }
    if (c == ';' || (c == '/' && i + 1 < line.size() && line[i + 1] == '/')) {
      break;
    }
    if (c == '(') {
      std::size_t close = line.find(')', i + 1);
      const bool closed = close != std::string_view::npos;
      if (!closed) {
        close = line.size();
      }
      if (!named) {
        std::string_view name = line.substr(i + 1, close - i - 1);
        while (!name.empty() && is_blank(name.front())) {
          name.remove_prefix(1);
        }
        while (!name.empty() && is_blank(name.back())) {
          name.remove_suffix(1);
        }
        out.name = std::string(name);
        named = true;
      }
      if (!closed) {
        break;
      }
      i = close;
      continue;
    }
    return make_alarm(alarm::kWordsAfterProgramNumber,
                      "only a comment may follow the program number on its line", file, line_no, i);
  }
  return std::nullopt;
}

}  // namespace

std::string program_label(int number) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "O%04d", number);
  return buf;
}

SplitResult split_programs(std::string_view text, const std::string& file_name) {
  return split_programs(TextSource::of_text(std::string(text)), file_name);
}

// One pass over the file. Dafeng spec L113 (manual L285): everything after `%` is ignored. A
// `%` with nothing but blank or comment lines before it is the leader of a punched-tape style
// file (`%` / O… / `%`, GSK and FANUC practice), so the tape starts after it and ends at the
// next `%` line, or at the end of the file. A block before the first O line is an alarm when
// the tape has O lines, and the start of its one program when it has none: which of the two
// is known at the tape's first O line, or at its end.
SplitResult split_programs(std::shared_ptr<const TextSource> text, const std::string& file_name) {
  SplitResult result;
  std::vector<Program> programs;
  std::map<int, int> first_seen;  // O number -> its line, for the duplicate alarm
  std::optional<ProgramAlarm> block_before_o;
  bool leader = true;  // no block yet: a `%` here is the leader
  LineReader reader(*text, 0, text->size(), 1);
  RawLine raw;
  while (reader.next(raw)) {
    if (is_percent_line(raw.text)) {
      if (!leader) {
        break;  // the end of the tape
      }
      leader = false;  // the tape starts after it
      continue;
    }
    const LineShape shape = shape_of(raw.text);
    leader = leader && !shape.first_exec;
    if (shape.o_word) {
      if (block_before_o) {
        result.alarm = std::move(block_before_o);
        return result;
      }
      if (*shape.o_word != *shape.first_exec) {
        result.alarm = make_alarm(alarm::kProgramNumberNotAtStart,
                                  "program number O must be the first word of its block", file_name,
                                  raw.line, *shape.o_word);
        return result;
      }
      Header header;
      if (auto bad = parse_header(raw.text, *shape.o_word, raw.line, file_name, header)) {
        result.alarm = std::move(bad);
        return result;
      }
      const auto [seen, fresh] = first_seen.emplace(header.number, raw.line);
      if (!fresh) {
        result.alarm = make_alarm(alarm::kDuplicateProgramNumber,
                                  program_label(header.number) + " is already defined at line " +
                                      std::to_string(seen->second) + " of this file",
                                  file_name, raw.line, *shape.o_word);
        return result;
      }
      Program program;
      program.number = header.number;
      program.name = std::move(header.name);
      program.header_line = raw.line;
      program.header_column = static_cast<int>(*shape.o_word) + 1;
      programs.push_back(std::move(program));
    } else if (programs.empty()) {
      if (!shape.first_exec) {
        continue;  // blank and comment lines before the first O line (a file header)
      }
      block_before_o =
          make_alarm(alarm::kBlockOutsideProgram, "block before the first program number O",
                     file_name, raw.line, *shape.first_exec);
      programs.emplace_back();  // a file without O lines is one program, from its first block
    }
    Program& p = programs.back();
    if (p.line_count == 0) {
      p.file = file_name;
      p.text = text;
      p.first_line = raw.line;
      p.begin = raw.offset;
    }
    ++p.line_count;
    p.end = raw.next;
  }
  if (reader.failed()) {
    result.alarm = ProgramAlarm{alarm::kFileUnreadable, "cannot read program file " + file_name,
                                file_name, 0, 0};
    return result;
  }
  result.programs = std::move(programs);
  return result;
}

}  // namespace mcnc::interp::program
