// G31 skip (spec dafeng L5210-5316, gsk A.6.20): a feed move that ends where a skip input
// switches. The interpreter emits the move and stops reading ahead there (a barrier, L6907);
// the channel runs it, stops it at the signal and tells where (Interpreter::skip_result).
// G31 P98/P99 (L5246-5252) skip where an axis is held back at its load ratio (G10 L14 P6,
// param 5511). G31.8 (L5317-5354) stores where each of several signals came; G160
// (L5355-5428) skips where the axis, its torque limited, is held back.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

namespace mcnc::interp {

namespace {
constexpr std::int64_t kGskFirstSkipVariable = 995;  // #995-#999
constexpr std::size_t kGskSkipVariables = 5;
}  // namespace

bool ProgramRun::skip_move_allowed(const char* code, int column) {
  if (interpolation_mode()) {
    return fail(
        alarm::kInterpolationModeRestriction,
        std::string(code) + " is not a move of polar or cylindrical interpolation (spec L612-849)",
        column);
  }
  if (compensation_ != Command::Compensation::off) {
    return fail(
        alarm::kWordNotAllowed,
        std::string(code) + " with nose radius compensation: cancel it (G40) first (gsk A.6.20)",
        column);
  }
  return true;
}

bool ProgramRun::read_skip_input(const char* code, int column, int& input, bool& on) {
  // L (on) / K (off) / I (signed) name the input's port, else param 5510 (on).
  BlockWord* l = word('L');
  BlockWord* k = word('K');
  BlockWord* i = word('I');
  input = config_.skip_input;
  on = true;
  if (BlockWord* w = l != nullptr ? l : (k != nullptr ? k : i)) {
    w->used = true;
    const double v = w == i ? std::fabs(w->value) : w->value;
    if (!(v >= 1.0 && v <= 99.0 && v == std::floor(v))) {
      return fail(alarm::kBadWordValue,
                  std::string(code) + " " + w->address.first + " must name an input 1-99",
                  w->column);
    }
    input = static_cast<int>(v);
    on = w == l || (w == i && w->value > 0.0);
  } else if (input == 0) {
    return fail(alarm::kSkipInput,
                std::string(code) +
                    " without L, K or I skips on the input of param 5510, which is 0 "
                    "(skip_input in the machine file)",
                column);
  }
  return true;
}

bool ProgramRun::read_result_variable(char letter, const char* code, const char* what,
                                      std::int64_t& variable) {
  variable = 0;
  if (BlockWord* w = word(letter)) {
    w->used = true;
    if (!(w->value >= 1.0 && w->value == std::floor(w->value))) {
      return fail(alarm::kBadWordValue,
                  std::string(code) + " " + letter + " names the variable that receives " + what,
                  w->column);
    }
    variable = static_cast<std::int64_t>(w->value);
  }
  return true;
}

Command* ProgramRun::emit_skip_move(const char* code, bool one_axis, int column) {
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return nullptr;
  }
  bool any = false;
  int named = 0;
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    any = any || (given[a] && target[a] != machine_[a]);
    named += given[a] ? 1 : 0;
  }
  if (one_axis && named > 1) {
    fail(alarm::kWordNotAllowed, std::string(code) + " takes exactly one axis", column);
    return nullptr;
  }
  if (!any) {
    fail(alarm::kWordNotAllowed, std::string(code) + " needs an end point to move to", column);
    return nullptr;
  }
  if (!check_feed(column)) {
    return nullptr;
  }
  Command& c = emit(Op::linear);
  c.to = target;
  c.feed = modal_.feed;
  c.feed_mode = modal_.feed_mode;
  c.exact_stop = true;
  block_barrier_ = true;  // the next block needs where it ended (L6907)
  machine_ = target;
  block_moved_ = true;
  return &c;
}

bool ProgramRun::run_skip(int column) {
  if (!skip_move_allowed("G31", column)) {
    return false;
  }
  // The input: L, K, I or param 5510; P names a PLC signal (P1-P8: G0014.0-7, going on, L5233)
  // or the load (P98: the load alone, L5246-5249; P99: the input or the load, L5251-5252).
  BlockWord* p = word('P');
  const bool or_load = p != nullptr && p->value == 99.0;  // P99 comes beside L, K or I
  const int ways = (word('L') != nullptr) + (word('K') != nullptr) + (word('I') != nullptr) +
                   (p != nullptr && !or_load);
  if (ways > 1) {
    BlockWord* second =
        p != nullptr && !or_load ? p : (word('I') != nullptr ? word('I') : word('K'));
    return fail(alarm::kWordNotAllowed, "G31 takes one of L, K, I and P", second->column);
  }
  int signal = 0;
  bool load = false;
  if (p != nullptr) {
    p->used = true;
    // GSK: P1-P4 select the skip signals whose addresses params №148-№151 hold (gsk A.6.20).
    if (config_.dialect == Dialect::gsk &&
        !(p->value >= 1.0 && p->value <= 4.0 && p->value == std::floor(p->value))) {
      return fail(alarm::kBadWordValue,
                  "G31 P must be 1-4, the skip signals of params 148-151 (gsk A.6.20)", p->column);
    }
    load = p->value == 98.0 || or_load;
    if (!load && !(p->value >= 1.0 && p->value <= 8.0 && p->value == std::floor(p->value))) {
      return fail(alarm::kBadWordValue, "G31 P must be 1-8, 98 or 99", p->column);
    }
    signal = load ? 0 : static_cast<int>(p->value);
  }
  const bool input_too = !load || or_load;  // P98 skips on the load alone
  int input = 0;                            // P1-P8 and P98: no probe input
  bool on = true;
  if (signal == 0 && input_too && !read_skip_input("G31", column, input, on)) {
    return false;
  }
  std::int64_t flag = 0;
  if (!read_result_variable('R', "G31", "the result", flag)) {
    return false;
  }
  const AxisVector from = machine_;
  Command* c = emit_skip_move("G31", false, column);
  if (c == nullptr) {
    return false;
  }
  c->skip = input_too;
  c->input = input;
  c->input_on = on;
  c->skip_signal = signal;
  if (load && !set_load_ratios(*c, from, or_load ? "G31 P99" : "G31 P98", column)) {
    return false;
  }
  // Until the channel says otherwise (a dry run, `mcnc interp`): skipped at the end point, so
  // a program that checks the signal runs its checked branch.
  skip_flag_variable_ = flag;
  record_skip(true, transform::to_vector(frame_.to_machine(transform::to_point(machine_))));
  return true;
}

bool ProgramRun::set_load_ratios(Command& c, const AxisVector& from, const char* code, int column) {
  // Each axis the move moves is watched at its ratio of G10 L14 P6, else of param 5511
  // (L5247); the others cannot be held back by what the move runs into.
  c.load_skip = true;
  bool any = false;
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    const double ratio = load_ratio_[a] > 0.0 ? load_ratio_[a] : config_.axes[a].skip_load;
    c.load_ratio[a] = machine_[a] != from[a] ? ratio : 0.0;
    any = any || c.load_ratio[a] > 0.0;
  }
  if (!any) {
    return fail(alarm::kCycleWordMissing,
                std::string(code) +
                    " needs the load ratio of an axis it moves: G10 L14 P6 or param 5511 "
                    "(skip_load of the axis)",
                column);
  }
  return true;
}

bool ProgramRun::run_load_ratio(int /*column*/) {
  // G10 L14 P6 α (L5246-5247): the load ratios G31 P98/P99 skip at, in percent of the rated
  // torque, by absolute addresses only (L4773); 0 gives an axis back to param 5511, and the
  // block without axes all of them (as G10 L14 P1 without axes cancels the checks, L4866).
  AxisVector ratios = load_ratio_;
  std::uint32_t given = 0;
  if (!read_axis_percents("the load ratios", ratios, given)) {
    return false;
  }
  load_ratio_ = given != 0 ? ratios : AxisVector{};
  return true;
}

bool ProgramRun::run_multi_skip(int column) {
  if (!skip_move_allowed("G31.8", column)) {
    return false;
  }
  const int ways = (word('L') != nullptr) + (word('K') != nullptr) + (word('I') != nullptr);
  if (ways > 1) {
    return fail(alarm::kWordNotAllowed, "G31.8 takes one of L, K and I", column);
  }
  int input = 0;
  bool on = true;
  if (!read_skip_input("G31.8", column, input, on)) {
    return false;
  }
  // P: the first variable of the stored positions, mandatory (L5344).
  std::int64_t first = 0;
  if (!read_result_variable('P', "G31.8", "the first position", first)) {
    return false;
  }
  if (first == 0) {
    return fail(alarm::kCycleWordMissing,
                "G31.8 needs P, the first variable of the positions it stores (spec L5344)",
                column);
  }
  int most = 0;  // Q: at most this many signals (0: no limit but the variables')
  if (BlockWord* q = word('Q')) {
    q->used = true;
    if (!(q->value >= 1.0 && q->value <= kMaxMultiSkipSignals &&
          q->value == std::floor(q->value))) {
      return fail(alarm::kBadWordValue,
                  "G31.8 Q (the most signals) must be 1-" + std::to_string(kMaxMultiSkipSignals),
                  q->column);
    }
    most = static_cast<int>(q->value);
  }
  std::int64_t count_variable = 0;
  if (!read_result_variable('R', "G31.8", "the number of signals", count_variable)) {
    return false;
  }
  const AxisVector from = machine_;
  Command* c = emit_skip_move("G31.8", true, column);
  if (c == nullptr) {
    return false;
  }
  c->skip = true;
  c->input = input;
  c->input_on = on;
  c->max_signals = most == 0 ? kMaxMultiSkipSignals : most;
  c->multi_skip = true;
  multi_skip_first_ = first;
  multi_skip_count_variable_ = count_variable;
  multi_skip_axis_ = 0;
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    multi_skip_axis_ = machine_[a] != from[a] ? static_cast<int>(a) : multi_skip_axis_;
  }
  c->skip_axis = static_cast<std::size_t>(multi_skip_axis_);  // the probe the channel arms
  multi_skip_column_ = column;
  // Without the channel (a dry run, `mcnc interp`): Q signals (one without Q) evenly along the
  // move, the last at its end, so that a program that counts them runs through (decision 93).
  std::array<double, kMaxMultiSkipSignals> at{};
  const int n = most == 0 ? 1 : most;
  multi_skip_dry_ = static_cast<std::size_t>(n);
  for (std::size_t k = 0; k < multi_skip_dry_; ++k) {
    multi_skip_before_[k] = vars_.read(first + static_cast<std::int64_t>(k)).value;
  }
  const auto axis = static_cast<std::size_t>(multi_skip_axis_);
  const AxisVector start_m = transform::to_vector(frame_.to_machine(transform::to_point(from)));
  const AxisVector end_m = transform::to_vector(frame_.to_machine(transform::to_point(machine_)));
  for (int k = 1; k <= n; ++k) {
    at[static_cast<std::size_t>(k - 1)] =
        start_m[axis] + (end_m[axis] - start_m[axis]) * static_cast<double>(k) / n;
  }
  return record_multi_skip(std::span<const double>(at.data(), static_cast<std::size_t>(n)), column);
}

bool ProgramRun::record_multi_skip(std::span<const double> at, int column) {
  // #P.. the machine positions (D27: machine, as the text says), as #5021 reads them; R the
  // count.
  for (std::size_t k = 0; k < at.size(); ++k) {
    const macro::MacroAlarm a = vars_.write(
        multi_skip_first_ + static_cast<std::int64_t>(k),
        macro::MacroValue::of(machine_reading(static_cast<std::size_t>(multi_skip_axis_), at[k])));
    if (a.number != 0) {
      return fail(alarm::kBadWordValue,
                  "G31.8 P: #" + std::to_string(multi_skip_first_ + static_cast<std::int64_t>(k)) +
                      " cannot hold a position: " + std::string(a.text()),
                  column);
    }
  }
  if (multi_skip_count_variable_ != 0) {
    (void)vars_.write(multi_skip_count_variable_,
                      macro::MacroValue::of(static_cast<double>(at.size())));
  }
  return true;
}

void ProgramRun::set_multi_skip_result(std::span<const double> latched, const AxisVector& stop_at) {
  // The variables the dry run filled beyond what the probe latched get back what they held:
  // a position that was not measured must not read as one.
  const std::size_t n = std::min(latched.size(), multi_skip_before_.size());
  for (std::size_t k = n; k < multi_skip_dry_; ++k) {
    (void)vars_.write(multi_skip_first_ + static_cast<std::int64_t>(k), multi_skip_before_[k]);
  }
  (void)record_multi_skip(latched.first(n), multi_skip_column_);
  set_machine(stop_at);  // the next block starts where the axes stopped
}

bool ProgramRun::run_torque_skip(int column) {
  if (!skip_move_allowed("G160", column)) {
    return false;
  }
  // P: the torque limit in percent of the motor's rated torque (param 5515 without it); -1
  // cancels it. Q: the following error beyond which it skips, mm (param 5516 without it).
  double limit = config_.torque_skip_percent;
  if (BlockWord* p = word('P')) {
    p->used = true;
    if (!(p->value == -1.0 || (p->value > 0.0 && p->value <= kMaxTorquePercent))) {
      return fail(alarm::kBadWordValue,
                  "G160 P (the torque limit, % of the rated torque) must be above 0 and up to "
                  "1000, or -1 to cancel it",
                  p->column);
    }
    limit = p->value;
  } else if (limit <= 0.0) {
    return fail(alarm::kCycleWordMissing,
                "G160 without P takes the torque limit of param 5515, which is 0 "
                "(torque_skip.limit)",
                column);
  }
  double deviation = config_.torque_skip_deviation;
  if (BlockWord* q = word('Q')) {
    q->used = true;
    if (!(q->value >= 0.0)) {
      return fail(alarm::kBadWordValue, "G160 Q (the following error, mm) must be 0 or more",
                  q->column);
    }
    deviation = length_of(*q);
  }
  const AxisVector from = machine_;
  Command* c = emit_skip_move("G160", true, column);
  if (c == nullptr) {
    return false;
  }
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    c->skip_axis = machine_[a] != from[a] ? a : c->skip_axis;
  }
  c->torque_skip = true;
  c->torque_limit = limit;
  c->deviation = deviation;
  skip_flag_variable_ = 0;
  if (limit > 0.0) {  // P-1 only moves, with the limit cancelled (decision 94)
    record_skip(true, transform::to_vector(frame_.to_machine(transform::to_point(machine_))));
  }
  return true;
}

void ProgramRun::set_skip_result(bool skipped, const AxisVector& skip_at,
                                 const AxisVector& stop_at) {
  record_skip(skipped, skip_at);
  set_machine(stop_at);  // the next block starts where the axes stopped
}

void ProgramRun::record_skip(bool skipped, const AxisVector& skip_at) {
  // #5061.. as #5001 reads a position: in the work system with the offsets in force.
  const AxisVector at =
      transform::to_vector(frame_.to_program(transform::to_point(from_inclined(skip_at))));
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    const int axis = static_cast<int>(a);
    skip_position_[a] = to_programmed(axis, at[a] - offset_sum(axis) - tool_offset(axis));
  }
  skip_known_ = true;
  // GSK: the skip position also goes to #995-#999, axis 1-5 of the channel in order (gsk A.6.20,
  // L675; the order is the spec's proposal).
  for (std::size_t a = 0;
       config_.dialect == Dialect::gsk && a < config_.axes.size() && a < kGskSkipVariables; ++a) {
    (void)vars_.write(kGskFirstSkipVariable + static_cast<std::int64_t>(a),
                      macro::MacroValue::of(skip_position_[a]));
  }
  if (skip_flag_variable_ != 0) {
    (void)vars_.write(skip_flag_variable_, macro::MacroValue::of(skipped ? 1.0 : 0.0));
  }
}

}  // namespace mcnc::interp
