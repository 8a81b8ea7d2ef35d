#pragma once
// Macro B expressions (spec dafeng §4.1-§4.2, gsk A.7.4): parsed once into a postfix program,
// evaluated any number of times against a VariableStore.
//
// Syntax: numbers (`12`, `12.`, `.5`; no exponent), `#n`, `#[expr]`, brackets `[ ]`, the
// constants PI and CHN, the functions of macro_math.hpp written `NAME[arg, ...]`, unary
// `- + ! ~`, and binary operators, loosest first (decision D18):
//   1. bitwise     `|` `&` `^` XOR
//   2. logical     `||` `&&` OR AND
//   3. comparison  `==` `!=` `>` `>=` `<` `<=` EQ NE GT GE LT LE   (1 or 0)
//   4. additive    `+` `-`
//   5. multiplic.  `*` `/` MOD
//   6. unary       `-` `+` `!` `~`                                   (tightest)
// Operators of one level associate left to right. Words are case-insensitive and need no
// blanks around them (`#1EQ#2`). Blanks and tabs between tokens are ignored.
//
// Null: only a variable reference (bare or bracketed) yields null; every operator and function
// counts null as 0 and yields a number (macro_value.hpp).
//
// Errors carry the 1-based column in the caller's line: parse_* take the column of text[0].
#include "channel/interp/macro/macro_math.hpp"
#include "channel/interp/macro/macro_value.hpp"
#include "channel/interp/macro/variable_store.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace mcnc::interp::macro {

enum class OpCode : std::uint8_t {
  kNumber,    // push operand
  kVariable,  // push #operand
  kIndirect,  // pop n, push #n
  kChannel,   // push CHN
  kNegate,
  kPlus,
  kNot,
  kBitNot,
  kAdd,
  kSub,
  kMul,
  kDiv,
  kMod,
  kEq,
  kNe,
  kGt,
  kGe,
  kLt,
  kLe,
  kAnd,
  kOr,
  kBitAnd,
  kBitOr,
  kBitXor,
  kCall,  // pop argc arguments, push function(...)
};

struct Instruction {
  OpCode op = OpCode::kNumber;
  Function function = Function::kSin;  // kCall
  std::uint8_t argc = 0;               // kCall
  int column = 0;                      // of the token, for alarms
  double operand = 0.0;                // kNumber value, kVariable number
};

// The largest evaluation stack an expression may need; deeper ones are refused when parsed.
inline constexpr int kMaxEvalStack = 128;

class Expression {
 public:
  const std::vector<Instruction>& code() const { return code_; }
  int stack_depth() const { return stack_depth_; }
  bool empty() const { return code_.empty(); }

 private:
  friend class ExpressionParser;
  std::vector<Instruction> code_;
  int stack_depth_ = 0;
};

enum class ParseMode {
  // The whole text is one expression; anything after it is an alarm.
  kWhole,
  // The longest expression at the start of the text; parsing stops before the first token that
  // cannot continue it (`GOTO`, `THEN`, an address letter, an unmatched `]` or `,`).
  kExpressionPrefix,
  // One operand at the start of the text, with its unary signs: `#1`, `-#1`, `[#1+2]`,
  // `SIN[30]`, `12.5`. This is what may follow an address letter (`X#1`, `X-#1`, `X[...]`).
  kOperandPrefix,
};

struct ParseLimits {
  // Brackets of any kind nested deeper than this are an alarm (spec L6906; at least 10 levels).
  int max_nesting = 20;
};

struct ParseResult {
  Expression expression;
  std::size_t end = 0;  // index in the text just past what was parsed
  MacroAlarm alarm;
};

ParseResult parse_expression(std::string_view text, int first_column = 1,
                             ParseMode mode = ParseMode::kWhole, ParseLimits limits = {});

struct EvalResult {
  MacroValue value;
  MacroAlarm alarm;
};

// Evaluates against `store` (variables, CHN and the dialect's vacant ordering). Does not
// allocate or throw. Results beyond 10^47 and non-finite results are alarm 3111.
EvalResult evaluate(const Expression& expression, const VariableStore& store);

// `#n = expr` or `#[expr] = expr`: the statement form (dafeng L6680-6695, gsk B.4 item 10).
struct Assignment {
  std::int64_t target = -1;  // the variable number when written `#n`
  Expression target_index;   // the index expression when written `#[expr]`
  int target_column = 0;     // of the '#'
  Expression value;
};

struct AssignmentParse {
  Assignment assignment;
  MacroAlarm alarm;
};

AssignmentParse parse_assignment(std::string_view text, int first_column = 1,
                                 ParseLimits limits = {});

// Evaluates the value, then the target index, and writes (a null value stays null: `#1=#0`).
MacroAlarm execute(const Assignment& assignment, VariableStore& store);

}  // namespace mcnc::interp::macro
