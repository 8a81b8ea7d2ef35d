// G81.1 / G80.1 sine-profile oscillation of an axis (spec dafeng L2454-2505): the interpreter
// checks the block and hands the oscillation to the planner as one command; the axis then
// strokes by itself while the blocks after it run, and the program may not move it until G80.1.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::interp {

namespace {

std::string axis_text(char name) {
  return std::string(1, name);
}

// The stretch of axis `axis` from `a` to `b`, the other axes at `at`, as a move G22 can check.
Command stretch(const AxisVector& at, std::size_t axis, double a, double b, AxisVector& from) {
  from = at;
  from[axis] = a;
  Command c;
  c.op = Op::linear;
  c.to = at;
  c.to[axis] = b;
  return c;
}

}  // namespace

bool ProgramRun::run_oscillation(GFunction f, int column) {
  const bool on = f == GFunction::oscillation_on;
  const std::string code = on ? "G81.1" : "G80.1";
  if (frame_active()) {
    return fail(alarm::kFrameRestriction,
                code + " is not available under G68.1 or G51.1: cancel them first", column);
  }
  if (interpolation_mode()) {
    return fail(alarm::kInterpolationModeRestriction,
                code + " is not available in polar or cylindrical interpolation", column);
  }
  // One axis, absolute: the top dead point (G81.1) or where the axis goes after (G80.1).
  int axis = -1;
  double at = 0.0;
  const bool ok = for_each_axis_word([&](int a, const BlockWord& w, bool incremental) {
    const AxisConfig& ac = config_.axes[static_cast<std::size_t>(a)];
    if (axis >= 0) {
      return fail(alarm::kWordNotAllowed, code + " takes one axis: " + w.address.first, w.column);
    }
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  code + " takes the axis's absolute position: " + ac.name + " instead of " +
                      w.address.first,
                  w.column);
    }
    axis = a;
    at = scaled_axis_word(a, w);
    return true;
  });
  if (!ok) {
    return false;
  }
  if (axis < 0) {
    return fail(alarm::kCycleWordMissing,
                on ? "G81.1 needs the axis and its top dead point (G81.1 Z0 Q100 F2000)"
                   : "G80.1 needs the axis and the position it goes to (G80.1 Z0, spec L2486)",
                column);
  }
  const auto i = static_cast<std::size_t>(axis);
  const AxisConfig& a = config_.axes[i];
  const double physical = to_physical(axis, at) + offset_sum(axis) + tool_offset(axis);
  // G22: every point the axis may stand at (where it is, the dead points or G80.1's end) must
  // lie outside the forbidden area.
  auto oscillation_allowed = [&](double from_a, double to_b) {
    if (!stroke_on_) {
      return true;
    }
    const AxisVector here = machine();
    const double lo = std::min({here[i], from_a, to_b});
    const double hi = std::max({here[i], from_a, to_b});
    AxisVector from;
    const Command c = stretch(here, i, lo, hi, from);
    if (limits::forbidden(stroke_zone_, from, config_.axes.size()) ||
        limits::enters(stroke_zone_, from, c, config_.axes.size())) {
      return fail(alarm::kStrokeLimit,
                  "the oscillation of " + axis_text(a.name) +
                      " would enter the area G22 forbids (" + stroke_limits_text() + ")",
                  column);
    }
    return true;
  };
  if (!on) {
    for (const BlockWord& w : words_) {
      if (!w.used && w.column != column && !w.address.is('N')) {
        return fail(alarm::kWordNotAllowed, "G80.1 takes the axis only", w.column);
      }
    }
    if (!oscillating_[i]) {
      return fail(alarm::kOscillation, "G80.1: " + axis_text(a.name) + " does not oscillate",
                  column);
    }
    if (!oscillation_allowed(physical, physical)) {
      return false;
    }
    oscillating_[i] = false;
    machine_[i] = physical;
    Command& c = emit(Op::oscillate_end);
    c.oscillating = axis;
    c.axis = a.name;
    block_moved_ = true;
    return true;
  }
  if (!a.oscillation) {
    return fail(
        alarm::kOscillation,
        "G81.1: " + axis_text(a.name) +
            " is not enabled for oscillation (param 5700.1, `oscillation: true` of the axis)",
        column);
  }
  if (!inclined_allows(axis, "it cannot oscillate", column)) {
    return false;
  }
  if (released_[i]) {
    return fail(alarm::kReleasedAxis,
                axis_text(a.name) +
                    " was released to another channel by G140; acquire it (G141) or restore "
                    "(G142) first",
                column);
  }
  if (oscillating_[i]) {
    return fail(alarm::kOscillation,
                "G81.1: " + axis_text(a.name) + " oscillates already: G80.1 first", column);
  }
  BlockWord* q = word('Q');
  if (q == nullptr) {
    return fail(alarm::kCycleWordMissing,
                "G81.1 needs Q, the distance from the top to the bottom dead point", column);
  }
  q->used = true;
  const double distance = scaled_axis_word(axis, *q);
  if (!(std::fabs(distance) > 0.0) || !std::isfinite(distance)) {
    return fail(alarm::kBadWordValue, "G81.1 Q must not be 0", q->column);
  }
  BlockWord* fw = word('F');
  if (fw == nullptr) {
    return fail(alarm::kFeedMissing, "G81.1 needs F, the oscillation's speed", column);
  }
  fw->used = true;
  if (!(fw->value > 0.0)) {
    return fail(alarm::kBadWordValue, "G81.1 F must be above 0", fw->column);
  }
  for (const BlockWord& w : words_) {
    if (!w.used && w.column != column && !w.address.is('N')) {
      return fail(alarm::kWordNotAllowed, "G81.1 takes its axis, Q and F only", w.column);
    }
  }
  const double bottom = to_physical(axis, at + distance) + offset_sum(axis) + tool_offset(axis);
  if (!oscillation_allowed(physical, bottom)) {
    return false;
  }
  oscillating_[i] = true;
  Command& c = emit(Op::oscillate);
  c.oscillating = axis;
  c.axis = a.name;
  c.top = physical;
  c.bottom = bottom;
  // Units per minute, not per revolution (L2484): a length in inch becomes mm.
  c.feed = fw->value * (a.rotary || modal_.metric ? 1.0 : 25.4);
  c.feed_mode = FeedMode::per_min;
  return true;
}

void ProgramRun::check_oscillation(std::size_t from) {
  for (std::size_t k = from; k < ready_.size() && !alarm_; ++k) {
    const Command& c = ready_[k];
    const auto o = static_cast<std::size_t>(c.oscillating);
    if (c.op == Op::oscillate || c.op == Op::oscillate_end) {
      released_oscillating_[o] = c.op == Op::oscillate;
      oscillation_hold_[o] = c.to[o];  // where the axis stands for the path from here on
      continue;
    }
    for (std::size_t i = 0; i < config_.axes.size() && c.moves(); ++i) {
      if (released_oscillating_[i] && c.to[i] != oscillation_hold_[i]) {
        alarm_ = ProgramAlarm{alarm::kOscillation,
                              axis_text(config_.axes[i].name) +
                                  " oscillates (G81.1): no block may move it before G80.1",
                              c.file != nullptr ? *c.file : std::string(), c.line, 0};
        save_retained();
        return;
      }
    }
  }
}

bool ProgramRun::oscillation_ended() {
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (oscillating_[i]) {
      return fail(alarm::kOscillation,
                  axis_text(config_.axes[i].name) +
                      " still oscillates at the program's end: end it with G80.1 first",
                  0);
    }
  }
  return true;
}

}  // namespace mcnc::interp
