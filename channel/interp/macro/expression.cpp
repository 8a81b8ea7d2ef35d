#include "channel/interp/macro/expression.hpp"
#include "channel/interp/program_chars.hpp"

#include "channel/interp/macro/macro_alarms.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <system_error>

namespace mcnc::interp::macro {

using interp::is_blank;
using interp::is_digit;
using interp::is_letter;
using interp::to_upper;

namespace {

enum class Tok { kEnd, kNumber, kHash, kOpen, kClose, kComma, kOperator, kWord, kAssign, kInvalid };

struct Token {
  Tok kind = Tok::kEnd;
  std::size_t begin = 0;
  std::size_t end = 0;
  int binary_level = 0;  // 1 (loosest) .. 5; 0 = not a binary operator
  OpCode binary = OpCode::kAdd;
  bool unary = false;
  OpCode unary_op = OpCode::kNegate;
  char upper[8] = {};  // a word, upper case, cut at 7 characters (enough for every keyword)
  std::size_t word_length = 0;
};

struct WordOperator {
  std::string_view name;
  int level;
  OpCode op;
};

constexpr std::array<WordOperator, 10> kWordOperators{{
    {"XOR", 1, OpCode::kBitXor},
    {"AND", 2, OpCode::kAnd},
    {"OR", 2, OpCode::kOr},
    {"EQ", 3, OpCode::kEq},
    {"NE", 3, OpCode::kNe},
    {"GT", 3, OpCode::kGt},
    {"GE", 3, OpCode::kGe},
    {"LT", 3, OpCode::kLt},
    {"LE", 3, OpCode::kLe},
    {"MOD", 5, OpCode::kMod},
}};

constexpr int kLevels = 5;
constexpr int kMaxUnaryPrefixes = 32;

std::string_view word_of(const Token& t) {
  return std::string_view(t.upper, t.word_length < 8 ? t.word_length : 7);
}

}  // namespace

class ExpressionParser {
 public:
  ExpressionParser(std::string_view text, int first_column, ParseLimits limits)
      : text_(text), first_column_(first_column), limits_(limits) {}

  ParseResult run(ParseMode mode) {
    ParseResult out;
    const bool ok = mode == ParseMode::kOperandPrefix ? parse_unary() : parse_binary(1);
    if (ok && mode == ParseMode::kWhole) {
      const Token t = peek();
      if (t.kind != Tok::kEnd) {
        unexpected(t);
      }
    }
    if (alarm_) {
      out.alarm = alarm_;
      out.end = pos_;
      return out;
    }
    out.end = pos_;
    expression_.stack_depth_ = max_stack_;
    out.expression = std::move(expression_);
    return out;
  }

  static Expression without_last(const Expression& e) {
    Expression copy = e;
    copy.code_.pop_back();
    return copy;
  }

 private:
  int column(std::size_t index) const { return first_column_ + static_cast<int>(index); }

  bool fail(int number, std::size_t index, const char* text) {
    alarm_ = make_alarm(number, column(index), "%s", text);
    return false;
  }

  std::size_t skip_blanks(std::size_t i) const {
    while (i < text_.size() && is_blank(text_[i])) {
      ++i;
    }
    return i;
  }

  // The next token without consuming it (the position after it is token.end).
  Token peek() const {
    Token t;
    const std::size_t i = skip_blanks(pos_);
    t.begin = i;
    t.end = i + 1;
    if (i >= text_.size()) {
      t.kind = Tok::kEnd;
      t.end = i;
      return t;
    }
    const char c = text_[i];
    const char next = i + 1 < text_.size() ? text_[i + 1] : '\0';
    const auto op = [&](int level, OpCode binary, std::size_t length) {
      t.kind = Tok::kOperator;
      t.binary_level = level;
      t.binary = binary;
      t.end = i + length;
    };
    if (is_digit(c) || c == '.') {
      t.kind = Tok::kNumber;
      std::size_t j = i;
      while (j < text_.size() && is_digit(text_[j])) {
        ++j;
      }
      if (j < text_.size() && text_[j] == '.') {
        ++j;
        while (j < text_.size() && is_digit(text_[j])) {
          ++j;
        }
      }
      t.end = j;
      return t;
    }
    if (is_letter(c)) {
      std::size_t j = i;
      while (j < text_.size() && is_letter(text_[j])) {
        ++j;
      }
      // Digits belong to the name only when a '[' follows: ROUND2[, ATAN2 [. Otherwise they
      // are a number after a word operator: #1EQ10.
      std::size_t k = j;
      while (k < text_.size() && is_digit(text_[k])) {
        ++k;
      }
      if (k > j && skip_blanks(k) < text_.size() && text_[skip_blanks(k)] == '[') {
        j = k;
      }
      t.kind = Tok::kWord;
      t.end = j;
      t.word_length = j - i;
      for (std::size_t n = 0; n < t.word_length && n < 7; ++n) {
        t.upper[n] = to_upper(text_[i + n]);
      }
      if (t.word_length <= 3) {
        for (const WordOperator& w : kWordOperators) {
          if (w.name == word_of(t)) {
            op(w.level, w.op, t.word_length);
            t.kind = Tok::kOperator;
          }
        }
      }
      return t;
    }
    switch (c) {
      case '#':
        t.kind = Tok::kHash;
        return t;
      case '[':
        t.kind = Tok::kOpen;
        return t;
      case ']':
        t.kind = Tok::kClose;
        return t;
      case ',':
        t.kind = Tok::kComma;
        return t;
      case '+':
        op(4, OpCode::kAdd, 1);
        t.unary = true;
        t.unary_op = OpCode::kPlus;
        return t;
      case '-':
        op(4, OpCode::kSub, 1);
        t.unary = true;
        t.unary_op = OpCode::kNegate;
        return t;
      case '*':
        op(5, OpCode::kMul, 1);
        return t;
      case '/':
        op(5, OpCode::kDiv, 1);
        return t;
      case '^':
        op(1, OpCode::kBitXor, 1);
        return t;
      case '|':
        if (next == '|') {
          op(2, OpCode::kOr, 2);
        } else {
          op(1, OpCode::kBitOr, 1);
        }
        return t;
      case '&':
        if (next == '&') {
          op(2, OpCode::kAnd, 2);
        } else {
          op(1, OpCode::kBitAnd, 1);
        }
        return t;
      case '=':
        if (next == '=') {
          op(3, OpCode::kEq, 2);
        } else {
          t.kind = Tok::kAssign;
        }
        return t;
      case '!':
        if (next == '=') {
          op(3, OpCode::kNe, 2);
        } else {
          t.kind = Tok::kOperator;
          t.unary = true;
          t.unary_op = OpCode::kNot;
        }
        return t;
      case '~':
        t.kind = Tok::kOperator;
        t.unary = true;
        t.unary_op = OpCode::kBitNot;
        return t;
      case '>':
        if (next == '=') {
          op(3, OpCode::kGe, 2);
        } else {
          op(3, OpCode::kGt, 1);
        }
        return t;
      case '<':
        if (next == '=') {
          op(3, OpCode::kLe, 2);
        } else {
          op(3, OpCode::kLt, 1);
        }
        return t;
      default:
        t.kind = Tok::kInvalid;
        return t;
    }
  }

  bool emit(OpCode op, int col, int stack_delta, double operand = 0.0,
            Function function = Function::kSin, int argc = 0) {
    Instruction in;
    in.op = op;
    in.column = col;
    in.operand = operand;
    in.function = function;
    in.argc = static_cast<std::uint8_t>(argc);
    expression_.code_.push_back(in);
    stack_ += stack_delta;
    if (stack_ > max_stack_) {
      max_stack_ = stack_;
    }
    if (max_stack_ > kMaxEvalStack) {
      alarm_ = make_alarm(alarm::kTooComplex, col,
                          "expression too complex (more than %d "
                          "pending operands)",
                          kMaxEvalStack);
      return false;
    }
    return true;
  }

  bool enter_bracket(std::size_t index) {
    if (++depth_ > limits_.max_nesting) {
      alarm_ = make_alarm(alarm::kTooComplex, column(index), "brackets nested deeper than %d",
                          limits_.max_nesting);
      return false;
    }
    return true;
  }

  // Expects the ']' that closes the '[' at `open`.
  bool close_bracket(std::size_t open) {
    const Token t = peek();
    if (t.kind == Tok::kClose) {
      pos_ = t.end;
      --depth_;
      return true;
    }
    if (t.kind == Tok::kEnd) {
      alarm_ = make_alarm(alarm::kBracketNotClosed, column(open), "'[' at column %d is not closed",
                          column(open));
      return false;
    }
    return unexpected(t);
  }

  // A token that cannot follow a complete operand.
  bool unexpected(const Token& t) {
    switch (t.kind) {
      case Tok::kClose:
        return fail(alarm::kUnexpectedBracket, t.begin, "']' without a matching '['");
      case Tok::kComma:
        return fail(alarm::kOperatorExpected, t.begin, "',' outside a function's brackets");
      case Tok::kAssign:
        return fail(alarm::kOperatorExpected, t.begin,
                    "'=' is not a comparison here: write == or EQ");
      case Tok::kWord:
        if (!known_word(t)) {
          return unknown_word(t);
        }
        break;
      case Tok::kInvalid:
        alarm_ = make_alarm(alarm::kOperatorExpected, column(t.begin), "unexpected character '%c'",
                            text_[t.begin]);
        return false;
      default:
        break;
    }
    alarm_ =
        make_alarm(alarm::kOperatorExpected, column(t.begin), "operator expected before '%.*s'",
                   static_cast<int>(t.end - t.begin), text_.data() + t.begin);
    return false;
  }

  bool known_word(const Token& t) const {
    const std::string_view w = word_of(t);
    return t.word_length < 8 && (w == "PI" || w == "CHN" || find_function(w) != nullptr);
  }

  bool unknown_word(const Token& t) {
    alarm_ = make_alarm(alarm::kUnknownWord, column(t.begin), "unknown function or word '%.*s'",
                        static_cast<int>(t.end - t.begin), text_.data() + t.begin);
    return false;
  }

  bool parse_binary(int level) {
    if (level > kLevels) {
      return parse_unary();
    }
    if (!parse_binary(level + 1)) {
      return false;
    }
    for (;;) {
      const Token t = peek();
      if (t.kind != Tok::kOperator || t.binary_level != level) {
        return true;
      }
      pos_ = t.end;
      if (!parse_binary(level + 1)) {
        return false;
      }
      if (!emit(t.binary, column(t.begin), -1)) {
        return false;
      }
    }
  }

  bool parse_unary() {
    // Prefixes are collected in a loop, not by recursion, so `------1` cannot exhaust the stack.
    std::array<std::pair<OpCode, int>, kMaxUnaryPrefixes> prefixes{};
    int count = 0;
    for (;;) {
      const Token t = peek();
      if (t.kind != Tok::kOperator || !t.unary) {
        break;
      }
      if (count == kMaxUnaryPrefixes) {
        return fail(alarm::kTooComplex, t.begin, "too many signs in a row");
      }
      prefixes[static_cast<std::size_t>(count++)] = {t.unary_op, column(t.begin)};
      pos_ = t.end;
    }
    if (!parse_primary()) {
      return false;
    }
    while (count > 0) {
      const auto& [op, col] = prefixes[static_cast<std::size_t>(--count)];
      if (!emit(op, col, 0)) {
        return false;
      }
    }
    return true;
  }

  bool missing_operand(const Token& t) {
    if (t.kind == Tok::kEnd) {
      return fail(alarm::kMissingOperand, t.begin, "operand missing at the end of the expression");
    }
    alarm_ = make_alarm(alarm::kMissingOperand, column(t.begin), "operand missing before '%.*s'",
                        static_cast<int>(t.end - t.begin), text_.data() + t.begin);
    return false;
  }

  bool parse_primary() {
    const Token t = peek();
    switch (t.kind) {
      case Tok::kNumber:
        return parse_number(t);
      case Tok::kHash:
        pos_ = t.end;
        return parse_variable(t.begin);
      case Tok::kOpen:
        pos_ = t.end;
        return enter_bracket(t.begin) && parse_binary(1) && close_bracket(t.begin);
      case Tok::kWord:
        return parse_word(t);
      case Tok::kInvalid:
        return unexpected(t);
      default:
        return missing_operand(t);
    }
  }

  bool parse_number(const Token& t) {
    pos_ = t.end;
    if (pos_ < text_.size() && text_[pos_] == '.') {
      return fail(alarm::kMalformedNumber, t.begin, "malformed number: more than one '.'");
    }
    if (t.end - t.begin == 1 && text_[t.begin] == '.') {
      return fail(alarm::kMalformedNumber, t.begin, "malformed number: '.' without digits");
    }
    double value = 0.0;
    const auto res = std::from_chars(text_.data() + t.begin, text_.data() + t.end, value);
    if (res.ec != std::errc() || value > kMaxMagnitude) {
      return fail(alarm::kMalformedNumber, t.begin, "number beyond 10^47");
    }
    return emit(OpCode::kNumber, column(t.begin), 1, value);
  }

  // After a '#' at `hash`: digits (a fixed number) or '[' expr ']' (indirection).
  bool parse_variable(std::size_t hash) {
    const std::size_t i = skip_blanks(pos_);
    const char c = i < text_.size() ? text_[i] : '\0';
    if (is_digit(c)) {
      std::size_t j = i;
      while (j < text_.size() && is_digit(text_[j])) {
        ++j;
      }
      if (j < text_.size() && text_[j] == '.') {
        return fail(alarm::kBadVariableSyntax, i, "a variable number is an integer");
      }
      if (j - i > 15) {
        return fail(alarm::kUndefinedVariable, i, "variable number too large");
      }
      double number = 0.0;
      std::from_chars(text_.data() + i, text_.data() + j, number);
      pos_ = j;
      return emit(OpCode::kVariable, column(hash), 1, number);
    }
    if (c == '[') {
      pos_ = i + 1;
      return enter_bracket(i) && parse_binary(1) && close_bracket(i) &&
             emit(OpCode::kIndirect, column(hash), 0);
    }
    if (c == '-') {
      return fail(alarm::kBadVariableSyntax, i, "a variable number cannot be negative");
    }
    if (c == '+') {
      return fail(alarm::kBadVariableSyntax, i, "a variable number takes no sign");
    }
    if (c == '#') {
      return fail(alarm::kBadVariableSyntax, i,
                  "variable number expected after '#' (indirection is written #[#n])");
    }
    return fail(alarm::kBadVariableSyntax, i < text_.size() ? i : hash,
                "variable number expected after '#'");
  }

  bool parse_word(const Token& t) {
    const std::string_view w = word_of(t);
    if (t.word_length < 8 && w == "PI") {
      pos_ = t.end;
      return emit(OpCode::kNumber, column(t.begin), 1, std::numbers::pi);
    }
    if (t.word_length < 8 && w == "CHN") {
      pos_ = t.end;
      return emit(OpCode::kChannel, column(t.begin), 1);
    }
    const FunctionInfo* f = t.word_length < 8 ? find_function(w) : nullptr;
    if (f == nullptr) {
      return unknown_word(t);
    }
    pos_ = t.end;
    const std::size_t open = skip_blanks(pos_);
    if (open >= text_.size() || text_[open] != '[') {
      alarm_ = make_alarm(alarm::kBracketExpected, column(t.begin), "'[' expected after %.*s",
                          static_cast<int>(f->name.size()), f->name.data());
      return false;
    }
    pos_ = open + 1;
    if (!enter_bracket(open)) {
      return false;
    }
    int argc = 0;
    for (;;) {
      if (!parse_binary(1)) {
        return false;
      }
      ++argc;
      const Token sep = peek();
      if (sep.kind != Tok::kComma) {
        break;
      }
      pos_ = sep.end;
    }
    if (!close_bracket(open)) {
      return false;
    }
    if (argc < f->min_args || argc > f->max_args) {
      if (f->min_args == f->max_args) {
        alarm_ = make_alarm(alarm::kArgumentCount, column(t.begin), "%.*s takes %d argument%s",
                            static_cast<int>(f->name.size()), f->name.data(), f->min_args,
                            f->min_args == 1 ? "" : "s");
      } else {
        alarm_ =
            make_alarm(alarm::kArgumentCount, column(t.begin), "%.*s takes %d or %d arguments",
                       static_cast<int>(f->name.size()), f->name.data(), f->min_args, f->max_args);
      }
      return false;
    }
    return emit(OpCode::kCall, column(t.begin), 1 - argc, 0.0, f->function, argc);
  }

  std::string_view text_;
  int first_column_;
  ParseLimits limits_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  int stack_ = 0;
  int max_stack_ = 0;
  Expression expression_;
  MacroAlarm alarm_;
};

ParseResult parse_expression(std::string_view text, int first_column, ParseMode mode,
                             ParseLimits limits) {
  return ExpressionParser(text, first_column, limits).run(mode);
}

namespace {

EvalResult failed(MacroAlarm a) {
  return EvalResult{MacroValue::null(), a};
}

// A computed variable number (dafeng L6427): an integer (within the snap tolerance), >= 0.
bool to_variable_number(double x, int column, std::int64_t& n, MacroAlarm& a) {
  if (!std::isfinite(x) || std::fabs(x) > 1e15) {
    a = make_alarm(alarm::kUndefinedVariable, column, "variable #[%g] does not exist", x);
    return false;
  }
  const double r = std::round(x);
  if (std::fabs(x - r) > snap_tolerance(x)) {
    a = make_alarm(alarm::kVariableNumberNotInteger, column,
                   "variable number %.10g is not an integer", x);
    return false;
  }
  if (r < 0.0) {
    a = make_alarm(alarm::kUndefinedVariable, column, "variable #%.0f does not exist", r);
    return false;
  }
  n = static_cast<std::int64_t>(r);
  return true;
}

bool in_range(double v) {
  return std::isfinite(v) && std::fabs(v) <= kMaxMagnitude;
}

// The evaluation stack, without MacroValue's initialisation.
class Slots {
 public:
  struct Ref {
    Slots& slots;
    std::size_t i;
    Ref& operator=(MacroValue v) {
      slots.number_[i] = v.number();
      slots.null_[i] = v.is_null();
      return *this;
    }
    operator MacroValue() const {  // implicit: `MacroValue a = stack[i]` reads like an array
      return slots.null_[i] ? MacroValue::null() : MacroValue::of(slots.number_[i]);
    }
    double number() const { return slots.number_[i]; }  // 0 for null, as stored
  };
  Ref operator[](std::size_t i) { return Ref{*this, i}; }

 private:
  double number_[kMaxEvalStack];  // NOLINT(cppcoreguidelines-pro-type-member-init)
  bool null_[kMaxEvalStack];      // NOLINT(cppcoreguidelines-pro-type-member-init)
};

const char* symbol(OpCode op) {
  switch (op) {
    case OpCode::kAdd:
      return "+";
    case OpCode::kSub:
      return "-";
    case OpCode::kMul:
      return "*";
    case OpCode::kDiv:
      return "/";
    case OpCode::kMod:
      return "MOD";
    case OpCode::kNegate:
      return "-";
    case OpCode::kBitNot:
      return "~";
    case OpCode::kBitAnd:
      return "&";
    case OpCode::kBitOr:
      return "|";
    case OpCode::kBitXor:
      return "XOR";
    default:
      return "operator";
  }
}

}  // namespace

EvalResult evaluate(const Expression& expression, const VariableStore& store) {
  // Left uninitialised: clearing 128 values would cost more than many expressions take to run,
  // and only slots below sp, each written before, are ever read.
  Slots stack;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  std::size_t sp = 0;
  const VacantOrdering ordering = store.dialect().vacant_ordering;
  for (const Instruction& in : expression.code()) {
    switch (in.op) {
      case OpCode::kNumber:
        stack[sp++] = MacroValue::of(in.operand);
        continue;
      case OpCode::kChannel:
        stack[sp++] = MacroValue::of(store.dialect().channel);
        continue;
      case OpCode::kVariable:
      case OpCode::kIndirect: {
        std::int64_t n = static_cast<std::int64_t>(in.operand);
        if (in.op == OpCode::kIndirect) {
          MacroAlarm a;
          if (!to_variable_number(stack[--sp].number(), in.column, n, a)) {
            return failed(a);
          }
        }
        VariableRead r = store.read(n);
        if (r.alarm) {
          r.alarm.column = in.column;
          return failed(r.alarm);
        }
        stack[sp++] = r.value;
        continue;
      }
      case OpCode::kCall: {
        std::array<double, 2> args{};
        sp -= in.argc;
        for (std::size_t i = 0; i < in.argc; ++i) {
          args[i] = stack[sp + i].number();
        }
        // FANUC and GSK round ROUND to a whole number; Dafeng keeps 3 decimals (decision D16).
        const bool whole_round =
            in.function == Function::kRound && store.dialect().round_to_integer;
        const MathResult r = whole_round ? apply_function(Function::kInt, args.data(), 1)
                                         : apply_function(in.function, args.data(), in.argc);
        if (!r.ok()) {
          return failed(make_alarm(alarm::kOutOfRange, in.column, "%s", r.error));
        }
        if (!in_range(r.value)) {
          const std::string_view name = function_info(in.function).name;
          return failed(make_alarm(alarm::kOutOfRange, in.column, "result of %.*s beyond 10^47",
                                   static_cast<int>(name.size()), name.data()));
        }
        stack[sp++] = MacroValue::of(r.value);
        continue;
      }
      default:
        break;
    }

    // Operators: null counts as 0 from here on.
    double result = 0.0;
    if (in.op == OpCode::kNegate || in.op == OpCode::kPlus || in.op == OpCode::kNot ||
        in.op == OpCode::kBitNot) {
      const double x = stack[sp - 1].number();
      switch (in.op) {
        case OpCode::kNegate:
          result = 0.0 - x;  // not -x: -0 would print as "-0"
          break;
        case OpCode::kPlus:
          result = x;
          break;
        case OpCode::kNot:
          result = x == 0.0 ? 1.0 : 0.0;
          break;
        default: {
          const auto i = to_bit_integer(x);
          if (!i) {
            return failed(make_alarm(alarm::kOutOfRange, in.column, "operand of ~ beyond 2^53"));
          }
          result = static_cast<double>(~*i);
          break;
        }
      }
      stack[sp - 1] = MacroValue::of(result);
      continue;
    }

    const MacroValue b = stack[--sp];
    const MacroValue a = stack[sp - 1];
    const double x = a.number();
    const double y = b.number();
    switch (in.op) {
      case OpCode::kAdd:
        result = x + y;
        break;
      case OpCode::kSub:
        result = x - y;
        break;
      case OpCode::kMul:
        result = x * y;
        break;
      case OpCode::kDiv:
      case OpCode::kMod:
        if (y == 0.0) {
          return failed(make_alarm(alarm::kDivisionByZero, in.column, "%s by zero",
                                   in.op == OpCode::kDiv ? "division" : "MOD"));
        }
        result = in.op == OpCode::kDiv ? x / y : std::fmod(x, y);
        break;
      case OpCode::kEq:
        result = compare(CompareOp::kEq, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kNe:
        result = compare(CompareOp::kNe, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kGt:
        result = compare(CompareOp::kGt, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kGe:
        result = compare(CompareOp::kGe, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kLt:
        result = compare(CompareOp::kLt, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kLe:
        result = compare(CompareOp::kLe, a, b, ordering) ? 1.0 : 0.0;
        break;
      case OpCode::kAnd:
        result = (x != 0.0 && y != 0.0) ? 1.0 : 0.0;
        break;
      case OpCode::kOr:
        result = (x != 0.0 || y != 0.0) ? 1.0 : 0.0;
        break;
      default: {
        const auto i = to_bit_integer(x);
        const auto j = to_bit_integer(y);
        if (!i || !j) {
          return failed(make_alarm(alarm::kOutOfRange, in.column, "operand of %s beyond 2^53",
                                   symbol(in.op)));
        }
        const std::int64_t r = in.op == OpCode::kBitAnd  ? (*i & *j)
                               : in.op == OpCode::kBitOr ? (*i | *j)
                                                         : (*i ^ *j);
        result = static_cast<double>(r);
        break;
      }
    }
    if (!in_range(result)) {
      return failed(
          make_alarm(alarm::kOutOfRange, in.column, "result of %s beyond 10^47", symbol(in.op)));
    }
    stack[sp - 1] = MacroValue::of(result + 0.0);
  }
  return EvalResult{sp == 1 ? stack[0] : MacroValue::null(), {}};
}

AssignmentParse parse_assignment(std::string_view text, int first_column, ParseLimits limits) {
  AssignmentParse out;
  std::size_t i = 0;
  while (i < text.size() && is_blank(text[i])) {
    ++i;
  }
  const int col = first_column + static_cast<int>(i);
  if (i >= text.size() || text[i] != '#') {
    out.alarm = make_alarm(alarm::kAssignmentExpected, col, "an assignment starts with '#'");
    return out;
  }
  // The target is one operand that starts with '#': `#n` or `#[expr]`.
  ParseResult target = parse_expression(text.substr(i), col, ParseMode::kOperandPrefix, limits);
  if (target.alarm) {
    out.alarm = target.alarm;
    return out;
  }
  Assignment& a = out.assignment;
  a.target_column = col;
  const Instruction& last = target.expression.code().back();
  if (last.op == OpCode::kVariable) {
    a.target = static_cast<std::int64_t>(last.operand);
  } else {
    a.target_index = ExpressionParser::without_last(target.expression);
  }
  std::size_t j = i + target.end;
  while (j < text.size() && is_blank(text[j])) {
    ++j;
  }
  const int eq_col = first_column + static_cast<int>(j);
  if (j >= text.size() || text[j] != '=') {
    out.alarm = make_alarm(alarm::kAssignmentExpected, eq_col, "'=' expected after the variable");
    return out;
  }
  if (j + 1 < text.size() && text[j + 1] == '=') {
    out.alarm = make_alarm(alarm::kAssignmentExpected, eq_col,
                           "'==' compares; an assignment is written with '='");
    return out;
  }
  ParseResult value = parse_expression(text.substr(j + 1), eq_col + 1, ParseMode::kWhole, limits);
  if (value.alarm) {
    out.alarm = value.alarm;
    return out;
  }
  a.value = std::move(value.expression);
  return out;
}

MacroAlarm execute(const Assignment& assignment, VariableStore& store) {
  const EvalResult value = evaluate(assignment.value, store);
  if (value.alarm) {
    return value.alarm;
  }
  std::int64_t target = assignment.target;
  if (target < 0) {
    const EvalResult index = evaluate(assignment.target_index, store);
    if (index.alarm) {
      return index.alarm;
    }
    MacroAlarm a;
    if (!to_variable_number(index.value.number(), assignment.target_column, target, a)) {
      return a;
    }
  }
  MacroAlarm a = store.write(target, value.value);
  if (a) {
    a.column = assignment.target_column;
  }
  return a;
}

}  // namespace mcnc::interp::macro
