#pragma once
// Helpers for the tests of mcnc::interp::Interpreter (the ISO lathe interpreter): run a program
// text, collect its commands and its alarm, and build configurations.
#include "channel/interp/interpreter.hpp"
#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::interp::test {

// What a run produced: every command pulled, then the alarm if the run ended in one.
struct RunResult {
  std::vector<Command> commands;
  std::optional<ProgramAlarm> alarm;
  bool ended = false;  // next() returned nullopt

  // Commands of one op, in order.
  std::vector<Command> of(Op op) const {
    std::vector<Command> out;
    for (const Command& c : commands) {
      if (c.op == op) {
        out.push_back(c);
      }
    }
    return out;
  }
  // Commands that come from a given line.
  std::vector<Command> at_line(int line) const {
    std::vector<Command> out;
    for (const Command& c : commands) {
      if (c.line == line) {
        out.push_back(c);
      }
    }
    return out;
  }
};

inline InterpreterConfig lathe() {
  return InterpreterConfig{};
}

inline InterpreterConfig gsk() {
  InterpreterConfig c;
  c.dialect = Dialect::gsk;
  c.macro.local_last = 33;
  c.macro.common_last = 199;
  c.macro.extended_common = false;
  c.macro.vacant_ordering = macro::VacantOrdering::kLiteralGskTable;
  return c;
}

// X (diameter), Y, Z.
inline InterpreterConfig lathe_xyz() {
  InterpreterConfig c;
  c.axes = {AxisConfig{'X', true}, AxisConfig{'Y', false}, AxisConfig{'Z', false}};
  return c;
}

// Pulls until the end, an alarm or `limit` commands.
inline RunResult drain(Interpreter& in, std::size_t limit = 100000) {
  RunResult r;
  while (r.commands.size() < limit) {
    auto x = in.next();
    if (!x) {
      r.ended = true;
      return r;
    }
    if (const auto* a = std::get_if<ProgramAlarm>(&*x)) {
      r.alarm = *a;
      auto after = in.next();
      EXPECT_FALSE(after.has_value()) << "a pull after an alarm must return nullopt";
      return r;
    }
    r.commands.push_back(std::get<Command>(*x));
  }
  return r;
}

inline RunResult run(const std::string& text, const InterpreterConfig& config = lathe()) {
  Interpreter in(config);
  if (auto a = in.start(text, "test.nc")) {
    RunResult r;
    r.alarm = *a;
    return r;
  }
  return drain(in);
}

// Runs a program that must end without an alarm.
inline RunResult run_ok(const std::string& text, const InterpreterConfig& config = lathe()) {
  RunResult r = run(text, config);
  EXPECT_FALSE(r.alarm.has_value()) << "alarm " << r.alarm->number << " line " << r.alarm->line
                                    << " col " << r.alarm->column << ": " << r.alarm->text;
  EXPECT_TRUE(r.ended);
  return r;
}

// Runs a program that must end in `number` at `line` (and `column` when > 0).
inline RunResult run_alarm(const std::string& text, int number, int line, int column = -1,
                           const InterpreterConfig& config = lathe()) {
  RunResult r = run(text, config);
  EXPECT_TRUE(r.alarm.has_value()) << "no alarm; " << r.commands.size() << " commands";
  if (r.alarm) {
    EXPECT_EQ(r.alarm->number, number) << r.alarm->text;
    EXPECT_EQ(r.alarm->line, line) << r.alarm->text;
    if (column >= 0) {
      EXPECT_EQ(r.alarm->column, column) << r.alarm->text;
    }
    // Nothing of the failing block was emitted.
    for (const Command& c : r.commands) {
      EXPECT_NE(c.line, line) << "a command of the failing line " << line << " was emitted";
    }
  }
  return r;
}

// A program that must end in alarm `number` at `line` (and `column` when >= 0).
struct ExpectedAlarm {
  const char* program;
  int number;
  int line;
  int column = -1;
};

template <std::size_t N>
void expect_alarms(const ExpectedAlarm (&cases)[N], const InterpreterConfig& config = lathe()) {
  for (const ExpectedAlarm& a : cases) {
    SCOPED_TRACE(a.program);
    run_alarm(a.program, a.number, a.line, a.column, config);
  }
}

// `config` with the nose (cutter) radius of tool offset 1.
inline InterpreterConfig with_nose_radius(InterpreterConfig config, double radius) {
  config.tool_geometry[1].radius = radius;
  return config;
}

// How long the linear commands take at their feeds (minutes), from `from`: a line's length is
// the Euclidean length over the first `axes` axes, as the planner measures it.
inline double minutes_at_feed(const RunResult& r, AxisVector from, std::size_t axes) {
  double minutes = 0.0;
  for (const Command& c : r.commands) {
    if (c.op != Op::linear) {
      continue;
    }
    double length = 0.0;
    for (std::size_t i = 0; i < axes; ++i) {
      length += (c.to[i] - from[i]) * (c.to[i] - from[i]);
    }
    minutes += std::sqrt(length) / c.feed;
    from = c.to;
  }
  return minutes;
}

// Expects a motion command's end point (physical: X as a radius).
#define EXPECT_AT(cmd, ...)                                                                  \
  do {                                                                                       \
    const double want_[] = {__VA_ARGS__};                                                    \
    for (std::size_t i_ = 0; i_ < sizeof want_ / sizeof want_[0]; ++i_) {                    \
      EXPECT_NEAR((cmd).to[i_], want_[i_], 1e-9) << "axis " << i_ << " line " << (cmd).line; \
    }                                                                                        \
  } while (0)

}  // namespace mcnc::interp::test
