#pragma once
// Helpers shared by the macro tests: parse-and-evaluate in one call.
#include "channel/interp/macro/expression.hpp"

#include <string_view>

namespace mcnc::interp::macro::test {

inline EvalResult eval_text(std::string_view text, const VariableStore& store) {
  ParseResult p = parse_expression(text);
  if (p.alarm) {
    return EvalResult{MacroValue::null(), p.alarm};
  }
  return evaluate(p.expression, store);
}

inline MacroAlarm assign(std::string_view text, VariableStore& store) {
  AssignmentParse p = parse_assignment(text);
  if (p.alarm) {
    return p.alarm;
  }
  return execute(p.assignment, store);
}

}  // namespace mcnc::interp::macro::test
