#include "channel/interp/block_lexer.hpp"
#include "channel/interp/program_chars.hpp"

#include "channel/interp/program_alarms.hpp"

#include <charconv>
#include <cstdio>
#include <system_error>

namespace mcnc::interp {

namespace {

int column_of(std::size_t index) {
  return static_cast<int>(index) + 1;
}

std::string describe_char(char c) {
  const auto byte = static_cast<unsigned char>(c);
  char buf[32];
  if (byte >= 0x21 && byte < 0x7f) {
    std::snprintf(buf, sizeof buf, "'%c'", c);
  } else {
    std::snprintf(buf, sizeof buf, "byte 0x%02X", byte);
  }
  return buf;
}

// Blanks out comments in place so that columns stay those of the original line. Returns the end
// of the executable part (a `;` or `//` ends it) and reports an unclosed '(' through `open_at`.
std::size_t blank_comments(std::string& text, std::optional<std::size_t>& open_at) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ';') {
      return i;
    }
    if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      return i;
    }
    if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      if (close == std::string::npos) {
        open_at = i;
        return i;
      }
      for (std::size_t j = i; j <= close; ++j) {
        text[j] = ' ';
      }
      i = close;
    }
  }
  return text.size();
}

}  // namespace

LexedLine lex_line(std::string_view line) {
  LexedLine out;
  if (!line.empty() && line.back() == '\r') {
    line.remove_suffix(1);
  }
  std::size_t first = 0;
  while (first < line.size() && is_blank(line[first])) {
    ++first;
  }
  if (first < line.size() && line[first] == '%') {
    out.ignored = true;
    return out;
  }

  std::string text(line);
  std::optional<std::size_t> open_comment;
  const std::size_t end = blank_comments(text, open_comment);

  std::size_t i = 0;
  while (i < end) {
    if (is_blank(text[i])) {
      ++i;
      continue;
    }
    if (!is_letter(text[i])) {
      out.error = LexError{alarm::kUnexpectedCharacter,
                           "unexpected character " + describe_char(text[i]), column_of(i)};
      return out;
    }
    LexWord word;
    word.letter = to_upper(text[i]);
    word.column = column_of(i);
    const std::string address(1, word.letter);
    ++i;
    while (i < end && is_blank(text[i])) {
      ++i;
    }
    bool negative = false;
    if (i < end && (text[i] == '+' || text[i] == '-')) {
      word.has_sign = true;
      negative = text[i] == '-';
      ++i;
    }
    const std::size_t digits_begin = i;
    int int_digits = 0;
    while (i < end && is_digit(text[i])) {
      ++i;
      ++int_digits;
    }
    if (i < end && text[i] == '.') {
      word.has_point = true;
      ++i;
      while (i < end && is_digit(text[i])) {
        ++i;
        ++word.frac_digits;
      }
    }
    const bool continues_badly = i < end && (text[i] == '.' || text[i] == '+' || text[i] == '-');
    if (int_digits + word.frac_digits == 0 || continues_badly) {
      out.error =
          LexError{alarm::kMalformedNumber, "malformed number after " + address, word.column};
      return out;
    }
    double magnitude = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data() + digits_begin, text.data() + i, magnitude);
    if (ec == std::errc::result_out_of_range) {
      out.error =
          LexError{alarm::kValueOutOfRange, "value of " + address + " out of range", word.column};
      return out;
    }
    if (ec != std::errc() || ptr != text.data() + i) {
      out.error =
          LexError{alarm::kMalformedNumber, "malformed number after " + address, word.column};
      return out;
    }
    word.value = negative ? -magnitude : magnitude;
    out.words.push_back(word);
  }
  if (open_comment) {
    out.error = LexError{alarm::kUnclosedComment, "comment '(' not closed on its line",
                         column_of(*open_comment)};
  }
  return out;
}

}  // namespace mcnc::interp
