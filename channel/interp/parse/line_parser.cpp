#include "channel/interp/parse/line_parser.hpp"

#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_chars.hpp"

#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <system_error>

namespace mcnc::interp::parse {

namespace {

constexpr std::array<std::array<char, 2>, 15> kTwoLetterAddresses{{{'U', 'X'},
                                                                   {'U', 'Y'},
                                                                   {'U', 'Z'},
                                                                   {'U', 'A'},
                                                                   {'U', 'B'},
                                                                   {'U', 'C'},
                                                                   {'P', 'S'},
                                                                   {'S', 'P'},
                                                                   {'N', 'Q'},
                                                                   {'P', 'Q'},
                                                                   {'U', 'R'},
                                                                   {'P', 'A'},
                                                                   {'P', 'N'},
                                                                   {'D', 'T'},
                                                                   {'D', 'C'}}};

bool is_two_letter_address(char a, char b) {
  for (const auto& pair : kTwoLetterAddresses) {
    if (pair[0] == a && pair[1] == b) {
      return true;
    }
  }
  return false;
}

// A number of at most 15 digits is an integer below 10^15 over a power of ten up to 10^15, both
// exact doubles, so their quotient is the correctly rounded value std::from_chars gives, without
// its general algorithm (most words of a program are such numbers).
constexpr int kExactDigits = 15;
constexpr std::array<double, kExactDigits + 1> kPowersOfTen{
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

// The characters that may start a comment or cut the line (`(`, `;`, `//`); a single '/' (a
// block skip) is one of them and stays as it is.
constexpr std::array<bool, 256> kCommentMarks = [] {
  std::array<bool, 256> marks{};
  for (const char c : {';', '/', '('}) {
    marks[static_cast<unsigned char>(c)] = true;
  }
  return marks;
}();

// The characters a line must be rewritten for before it is parsed: comment marks and lower case.
// Most lines have none, and are parsed as they are read.
constexpr std::array<bool, 256> kRewritten = [] {
  std::array<bool, 256> rewritten = kCommentMarks;
  for (int c = 'a'; c <= 'z'; ++c) {
    rewritten[static_cast<std::size_t>(c)] = true;
  }
  return rewritten;
}();

// The digits of a literal from `i`: integer digits, then an optional point and its digits.
struct Digits {
  std::size_t end = 0;         // the first character after them
  std::uint64_t mantissa = 0;  // all digits as one integer: exact up to kExactDigits
  int digits = 0;
  int decimals = 0;
  bool point = false;
};

// The run of digits from `i` taken into `mantissa`; the index after it. One unsigned comparison
// tells a digit: any other character's distance from '0' is above 9.
inline std::size_t take_digits(const char* t, std::size_t n, std::size_t i,
                               std::uint64_t& mantissa) {
  for (unsigned digit = 0;
       i < n &&
       (digit = static_cast<unsigned>(static_cast<unsigned char>(t[i])) - unsigned{'0'}) <= 9;
       ++i) {
    mantissa = mantissa * 10 + digit;
  }
  return i;
}

inline Digits read_digits(const char* t, std::size_t n, std::size_t i) {
  Digits d;
  std::uint64_t mantissa = 0;
  const std::size_t point = take_digits(t, n, i, mantissa);
  d.digits = static_cast<int>(point - i);
  d.end = point;
  if (point < n && t[point] == '.') {
    d.point = true;
    d.end = take_digits(t, n, point + 1, mantissa);
    d.decimals = static_cast<int>(d.end - point - 1);
    d.digits += d.decimals;
  }
  d.mantissa = mantissa;
  return d;
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

// Parses one line. `text_` is the upper-cased line with comments blanked (columns preserved)
// and cut at `;` or `//`.
class LineParser {
 public:
  // `arena` nullptr: check only, keeping no words, expressions or assignments.
  LineParser(std::string_view text, Line& line, std::optional<ParseError>& error, Arena* arena)
      : text_(text), line_(line), error_(error), arena_(arena) {}

  void run() {
    skip_blanks();
    if (at_end()) {
      return;
    }
    if (peek() == '%') {
      return;
    }
    if (peek() == '/') {
      ++pos_;
      line_.skip_level = 1;
      if (!at_end() && is_digit(peek())) {
        line_.skip_level = peek() - '0';
        ++pos_;
        if (line_.skip_level == 0) {
          fail(alarm::kBadBlockSkip, "block skip level must be 1-9", pos_);
          return;
        }
      }
      skip_blanks();
      if (!at_end() && !is_letter(peek()) && peek() != '#') {
        fail(alarm::kBadBlockSkip, "block skip '/' must be followed by a block", pos_ + 1);
        return;
      }
      if (!at_end() && peek() == '#' && pos_ > 0 && text_[pos_ - 1] == '/') {
        fail(alarm::kBadBlockSkip, "block skip '/' must be followed by a block", pos_ + 1);
        return;
      }
    }
    if (!at_end() && (peek() == ':' ||
                      (peek() == 'O' && pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1])))) {
      return;  // the program-number line (`O` or ISO's `:`); the program splitter has checked it
    }
    if (!at_end() && peek() == 'N' && pos_ + 1 < text_.size() && !is_letter(text_[pos_ + 1])) {
      if (!parse_sequence()) {
        return;
      }
    }
    skip_blanks();
    if (at_end()) {
      return;
    }
    parse_statement(line_.statement);
  }

 private:
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }
  int column(std::size_t index) const { return static_cast<int>(index) + 1; }
  // The hot loops read the text through locals: a store through a `char` (a word's address)
  // may alias anything, which would make them reload the string's pointer and size.
  void skip_blanks() {
    const char* const t = text_.data();
    const std::size_t n = text_.size();
    std::size_t i = pos_;
    while (i < n && is_blank(t[i])) {
      ++i;
    }
    pos_ = i;
  }
  bool failed() const { return error_.has_value(); }
  void fail(int number, std::string text, std::size_t index) {
    if (!error_) {
      error_ = ParseError{number, std::move(text), column(index)};
    }
  }
  void fail_at_column(int number, std::string text, int col) {
    if (!error_) {
      error_ = ParseError{number, std::move(text), col};
    }
  }

  bool parse_sequence() {
    const std::size_t start = pos_;
    ++pos_;
    skip_blanks();
    const std::size_t digits = pos_;
    while (!at_end() && is_digit(peek())) {
      ++pos_;
    }
    if (pos_ == digits) {
      fail(alarm::kIntegerExpected, "sequence number N needs digits", start);
      return false;
    }
    if (!at_end() && (peek() == '.' || peek() == '#' || peek() == '[')) {
      fail(alarm::kIntegerExpected, "sequence number N must be a plain integer", start);
      return false;
    }
    if (pos_ - digits > 8) {
      fail(alarm::kValueOutOfRange, "sequence number N has more than 8 digits", start);
      return false;
    }
    std::int64_t n = 0;
    std::from_chars(text_.data() + digits, text_.data() + pos_, n);
    line_.sequence = n;
    line_.sequence_column = column(start);
    return true;
  }

  // The run of letters at the current position, upper case.
  std::string_view letters_at(std::size_t i) const {
    std::size_t j = i;
    while (j < text_.size() && is_letter(text_[j])) {
      ++j;
    }
    return std::string_view(text_).substr(i, j - i);
  }

  bool keyword(std::string_view word) {
    const std::string_view run = letters_at(pos_);
    if (run != word) {
      return false;
    }
    pos_ += word.size();
    return true;
  }

  void expect_end(const char* what) {
    skip_blanks();
    if (!failed() && !at_end()) {
      fail(alarm::kWordsAfterStatement, std::string("unexpected text after ") + what, pos_);
    }
  }

  // Parses an expression at pos_ into the arena; returns its index or -1.
  int expression(Statement& /*s*/, macro::ParseMode mode) {
    const std::string_view rest = std::string_view(text_).substr(pos_);
    macro::ParseResult r = macro::parse_expression(rest, column(pos_), mode);
    if (r.alarm) {
      fail_at_column(r.alarm.number, std::string(r.alarm.text()), r.alarm.column);
      return -1;
    }
    if (r.expression.empty()) {
      fail(alarm::kMalformedNumber, "expression expected", pos_);
      return -1;
    }
    pos_ += r.end;
    if (arena_ == nullptr) {
      return 0;
    }
    arena_->expressions.push_back(std::move(r.expression));
    return static_cast<int>(arena_->expressions.size()) - 1;
  }

  // `[cond]` after IF / ELIF / WHILE.
  int bracket_condition(Statement& s, const char* what) {
    skip_blanks();
    if (at_end() || peek() != '[') {
      fail(alarm::kMalformedNumber, std::string(what) + " needs a condition in [ ]", pos_);
      return -1;
    }
    return expression(s, macro::ParseMode::kOperandPrefix);
  }

  bool integer_label(int& label, const char* what) {
    skip_blanks();
    const std::size_t start = pos_;
    while (!at_end() && is_digit(peek())) {
      ++pos_;
    }
    if (pos_ == start || pos_ - start > 9) {
      fail(alarm::kIntegerExpected, std::string(what) + " needs a positive integer", start);
      return false;
    }
    std::from_chars(text_.data() + start, text_.data() + pos_, label);
    if (label <= 0) {
      fail(alarm::kIntegerExpected, std::string(what) + " needs a positive integer", start);
      return false;
    }
    return true;
  }

  void parse_statement(Statement& s) {
    s.column = column(pos_);
    const char c = peek();
    if (c == '#') {
      s.kind = StatementKind::assignment;
      const std::string_view rest = std::string_view(text_).substr(pos_);
      macro::AssignmentParse a = macro::parse_assignment(rest, column(pos_));
      if (a.alarm) {
        fail_at_column(a.alarm.number, std::string(a.alarm.text()), a.alarm.column);
        return;
      }
      if (arena_ != nullptr) {
        s.assignment = std::make_unique<macro::Assignment>(std::move(a.assignment));
      }
      pos_ = text_.size();
      return;
    }
    if (!is_letter(c)) {
      fail(alarm::kUnexpectedCharacter, "unexpected character " + describe_char(c), pos_);
      return;
    }
    const std::string_view run = letters_at(pos_);
    if (run.size() < 2) {  // every statement keyword has two letters or more: NC words
      parse_block(s);
      return;
    }
    if (run == "IF") {
      pos_ += 2;
      s.condition = bracket_condition(s, "IF");
      if (failed()) {
        return;
      }
      skip_blanks();
      if (at_end()) {
        s.kind = StatementKind::if_block;
        return;
      }
      s.kind = StatementKind::if_then;
      keyword("THEN");
      skip_blanks();
      if (at_end()) {
        fail(alarm::kWordsAfterStatement, "IF [...] THEN needs a statement", pos_);
        return;
      }
      s.then = std::make_unique<Statement>();
      parse_statement(*s.then);
      const StatementKind k = s.then->kind;
      if (!failed() && k != StatementKind::block && k != StatementKind::assignment &&
          k != StatementKind::go_to && k != StatementKind::loop_break &&
          k != StatementKind::loop_continue) {
        fail_at_column(alarm::kWordsAfterStatement,
                       "IF [...] may only be followed by a block, an assignment, GOTO, BREAK "
                       "or CONTINUE on its line",
                       s.then->column);
      }
      return;
    }
    if (run == "ELIF" || run == "ELSEIF") {
      pos_ += run.size();
      s.kind = StatementKind::elif;
      s.condition = bracket_condition(s, "ELIF");
      expect_end("ELIF [...]");
      return;
    }
    if (run == "ELSE") {
      pos_ += 4;
      s.kind = StatementKind::else_branch;
      expect_end("ELSE");
      return;
    }
    if (run == "ENDIF") {
      pos_ += 5;
      s.kind = StatementKind::endif;
      expect_end("ENDIF");
      return;
    }
    if (run == "WHILE") {
      pos_ += 5;
      s.kind = StatementKind::while_do;
      s.condition = bracket_condition(s, "WHILE");
      if (failed()) {
        return;
      }
      skip_blanks();
      if (!keyword("DO")) {
        fail(alarm::kWordsAfterStatement, "WHILE [...] needs DO m", pos_);
        return;
      }
      if (integer_label(s.label, "DO")) {
        expect_end("DO m");
      }
      return;
    }
    if (run == "END") {
      pos_ += 3;
      s.kind = StatementKind::loop_end;
      if (integer_label(s.label, "END")) {
        expect_end("END m");
      }
      return;
    }
    if (run == "GOTO" || run == "GOTOF" || run == "GOTOB") {
      pos_ += run.size();
      s.kind = StatementKind::go_to;
      s.direction = run == "GOTOF"   ? GotoDirection::forward
                    : run == "GOTOB" ? GotoDirection::backward
                                     : GotoDirection::wrap;
      skip_blanks();
      s.target = expression(s, macro::ParseMode::kExpressionPrefix);
      expect_end("GOTO n");
      return;
    }
    if (run == "BREAK" || run == "BRK") {
      pos_ += run.size();
      s.kind = StatementKind::loop_break;
      expect_end("BREAK");
      return;
    }
    if (run == "CONTINUE" || run == "CONT") {
      pos_ += run.size();
      s.kind = StatementKind::loop_continue;
      expect_end("CONTINUE");
      return;
    }
    if (run == "CH") {
      pos_ += 2;
      s.kind = StatementKind::channel_only;
      if (integer_label(s.label, "CH") && s.label > 255) {
        fail_at_column(alarm::kValueOutOfRange, "CH n: n must be 1-255", s.column);
        return;
      }
      expect_end("CH n");
      return;
    }
    if (run.size() >= 3) {
      std::string name(run);
      fail(alarm::kUnsupportedStatement,
           name +
               " is not a statement this interpreter knows (macro functions such as DPRNT, "
               "SPSV or MBRD are not supported)",
           pos_);
      return;
    }
    parse_block(s);
  }

  void parse_block(Statement& s) {
    s.kind = StatementKind::block;
    s.first_word = arena_ == nullptr ? 0 : static_cast<std::uint32_t>(arena_->words.size());
    parse_words(s);
  }

  void parse_words(Statement& s) {
    while (!failed()) {
      plain_words(s);
      if (at_end()) {
        return;
      }
      const char c = peek();
      Word w;
      w.column = column(pos_);
      if (c == ',') {
        ++pos_;
        if (at_end() || (peek() != 'C' && peek() != 'R' && peek() != 'A')) {
          fail(alarm::kUnknownAddress, "',' must be followed by C, R or A", pos_ - 1);
          return;
        }
        w.address = Address{peek(), 0, true};
        ++pos_;
      } else if (is_letter(c)) {
        const char next = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
        if (is_letter(next)) {
          if (!is_two_letter_address(c, next)) {
            const std::string_view run = letters_at(pos_);
            fail(alarm::kUnknownAddress, "unknown address " + std::string(run), pos_);
            return;
          }
          w.address = Address{c, next, false};
          pos_ += 2;
        } else {
          if (c == 'O') {
            fail(alarm::kUnknownAddress, "O is only allowed at the start of a program", pos_);
            return;
          }
          w.address = Address{c, 0, false};
          ++pos_;
        }
      } else if (c == '#') {
        fail(alarm::kUnexpectedCharacter, "a macro statement cannot follow NC words on one line",
             pos_);
        return;
      } else {
        fail(alarm::kUnexpectedCharacter, "unexpected character " + describe_char(c), pos_);
        return;
      }
      parse_index(w);
      if (!failed()) {
        parse_value(s, w);
      }
      if (!failed()) {
        keep(w);
        ++s.word_count;
      }
    }
  }

  // `S2=`: digits followed by '=' are a sub-index.
  void parse_index(Word& w) {
    const char* const t = text_.data();
    const std::size_t n = text_.size();
    std::size_t i = pos_;
    while (i < n && is_blank(t[i])) {
      ++i;
    }
    const std::size_t digits = i;
    while (i < n && is_digit(t[i])) {
      ++i;
    }
    if (i == digits || i - digits > 3) {
      return;
    }
    std::size_t j = i;
    while (j < n && is_blank(t[j])) {
      ++j;
    }
    if (j < n && t[j] == '=') {
      std::from_chars(t + digits, t + i, w.index);
      pos_ = j + 1;
    }
  }

  void keep(const Word& w) {
    if (arena_ != nullptr) {
      arena_->words.push_back(w);
    }
  }

  // Whether digits `d` end the literal: at least one, and not followed by a second point, a
  // macro operand or '='.
  static bool plain_literal_end(const Digits& d, const char* t, std::size_t n) {
    const std::size_t i = d.end;
    return d.digits > 0 && !(i < n && (t[i] == '.' || t[i] == '#' || t[i] == '[' || t[i] == '='));
  }
  // The value of at most kExactDigits digits: an exact integer over an exact power of ten.
  static double exact_magnitude(const Digits& d) {
    return static_cast<double>(d.mantissa) / kPowersOfTen[static_cast<std::size_t>(d.decimals)];
  }

  // The most common words, a one-letter address with a literal right after it (`X40.`,
  // `Z-10.`, `G01`), from pos_ on: read in one go each, with the rules of parse_index and
  // parse_value. Stops, at the start of the word after the blanks before it (or at the end),
  // at any other word (blanks inside it, a sub-index, an expression, anything malformed), which
  // the general path reads.
  void plain_words(Statement& s) {
    const char* const t = text_.data();
    const std::size_t n = text_.size();
    std::size_t i = pos_;
    while (i < n && is_blank(t[i])) {
      ++i;
    }
    while (i < n) {
      const std::size_t start = i;
      const char c = t[start];
      i = start + 1;
      if (c == 'O' || !is_letter(c) || i >= n) {
        i = start;
        break;
      }
      bool negative = false;
      if (t[i] == '+' || t[i] == '-') {
        negative = t[i] == '-';
        ++i;
      }
      if (i >= n || !(is_digit(t[i]) || t[i] == '.')) {
        i = start;
        break;
      }
      const Digits d = read_digits(t, n, i);
      if (d.digits > kExactDigits || !plain_literal_end(d, t, n)) {
        i = start;
        break;
      }
      i = d.end;
      while (i < n && is_blank(t[i])) {
        ++i;
      }
      // Digits followed by '=' after blanks are a sub-index (parse_index).
      if (i < n && t[i] == '=' && !negative && !d.point && d.digits <= 3) {
        i = start;
        break;
      }
      Word w;
      w.column = column(start);
      w.address = Address{c, 0, false};
      w.has_point = d.point;
      const double magnitude = exact_magnitude(d);
      w.value = negative ? -magnitude : magnitude;
      keep(w);
      ++s.word_count;
    }
    pos_ = i;
  }

  void parse_value(Statement& s, Word& w) {
    skip_blanks();
    const char* const t = text_.data();
    const std::size_t n = text_.size();
    std::size_t i = pos_;
    bool negative = false;
    if (i < n && (t[i] == '+' || t[i] == '-')) {
      negative = t[i] == '-';
      ++i;
      while (i < n && is_blank(t[i])) {
        ++i;
      }
    }
    if (i < n && (is_digit(t[i]) || t[i] == '.')) {
      const std::size_t begin = i;
      const Digits d = read_digits(t, n, i);
      i = d.end;
      w.has_point = d.point;
      if (!plain_literal_end(d, t, n)) {
        fail_at_column(alarm::kMalformedNumber, "malformed number after " + name_of(w.address),
                       w.column);
        return;
      }
      double magnitude = 0.0;
      if (d.digits <= kExactDigits) {
        magnitude = exact_magnitude(d);
      } else {
        const auto [ptr, ec] = std::from_chars(t + begin, t + i, magnitude);
        if (ec == std::errc::result_out_of_range || magnitude > 1e15) {
          fail_at_column(alarm::kValueOutOfRange,
                         "value of " + name_of(w.address) + " out of range", w.column);
          return;
        }
        if (ec != std::errc() || ptr != t + i) {
          fail_at_column(alarm::kMalformedNumber, "malformed number after " + name_of(w.address),
                         w.column);
          return;
        }
      }
      w.literal = true;
      w.value = negative ? -magnitude : magnitude;
      pos_ = i;
      return;
    }
    if (at_end() ||
        (!is_letter(peek()) && peek() != '#' && peek() != '[' && peek() != '-' && peek() != '+')) {
      fail_at_column(alarm::kMalformedNumber, name_of(w.address) + " needs a value", w.column);
      return;
    }
    if (is_letter(peek()) && letters_at(pos_).size() < 2) {
      fail_at_column(alarm::kMalformedNumber, name_of(w.address) + " needs a value", w.column);
      return;
    }
    w.literal = false;
    w.expression = expression(s, macro::ParseMode::kOperandPrefix);
  }

  static std::string name_of(const Address& a) {
    std::string n;
    if (a.comma) {
      n += ',';
    }
    n += a.first;
    if (a.second != 0) {
      n += a.second;
    }
    return n;
  }

  std::string_view text_;
  Line& line_;
  std::optional<ParseError>& error_;
  Arena* arena_;
  std::size_t pos_ = 0;
};

}  // namespace

LineParse parse_line(std::string_view text, int line_number, Arena& arena) {
  LineParse out;
  out.error = parse_line_into(text, line_number, arena, out.line);
  return out;
}

namespace {

// parse_line_into, and check_line_into when `arena` is nullptr.
std::optional<ParseError> parse_or_check(std::string_view text, int line_number, Arena* arena,
                                         Line& line) {
  line.line = line_number;
  if (!text.empty() && text.back() == '\r') {
    text.remove_suffix(1);
  }
  std::optional<ParseError> error;
  bool rewritten = false;
  for (const char c : text) {
    rewritten |= kRewritten[static_cast<unsigned char>(c)];
  }
  if (!rewritten) {
    LineParser parser(text, line, error, arena);
    parser.run();
    return error;
  }
  // Blank comments (keeping columns), remember the first one, cut at `;` or `//`, upper-case.
  // One buffer per thread: parsing a large file does not allocate a string per line.
  thread_local std::string work;
  work.resize(text.size());
  // Through locals: the stores of chars may alias anything, the string's pointer and size too.
  char* const out = work.data();
  const char* const in = text.data();
  const std::size_t size = text.size();
  std::size_t end = size;
  bool have_message = false;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = in[i];
    if (!kCommentMarks[static_cast<unsigned char>(c)]) {
      out[i] = to_upper(c);
      continue;
    }
    out[i] = c;
    if (c == ';' || (c == '/' && i + 1 < size && in[i + 1] == '/')) {
      end = i;
      break;
    }
    if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      if (close == std::string_view::npos) {
        return ParseError{alarm::kUnclosedComment, "comment '(' not closed on its line",
                          static_cast<int>(i) + 1};
      }
      if (!have_message && arena != nullptr) {
        arena->messages.emplace_back(text.substr(i + 1, close - i - 1));
        line.message = static_cast<int>(arena->messages.size()) - 1;
        have_message = true;
      }
      for (std::size_t j = i; j <= close; ++j) {
        out[j] = ' ';
      }
      i = close;
      continue;
    }
  }
  work.resize(end);
  LineParser parser(work, line, error, arena);
  parser.run();
  return error;
}

}  // namespace

std::optional<ParseError> parse_line_into(std::string_view text, int line_number, Arena& arena,
                                          Line& line) {
  return parse_or_check(text, line_number, &arena, line);
}

std::optional<ParseError> check_line_into(std::string_view text, int line_number, Line& line) {
  return parse_or_check(text, line_number, nullptr, line);
}

}  // namespace mcnc::interp::parse
