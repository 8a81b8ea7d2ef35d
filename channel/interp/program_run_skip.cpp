// G31 skip (spec dafeng L5210-5316, gsk A.6.20): a feed move that ends where a skip input
// switches. The interpreter emits the move and stops reading ahead there (a barrier, L6907);
// the channel runs it, stops it at the signal and tells where (Interpreter::skip_result).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

bool ProgramRun::run_skip(int column) {
  if (interpolation_mode()) {
    return fail(alarm::kInterpolationModeRestriction,
                "G31 is not a move of polar or cylindrical interpolation (spec L612-849)", column);
  }
  if (compensation_ != Command::Compensation::off) {
    return fail(alarm::kWordNotAllowed,
                "G31 with nose radius compensation: cancel it (G40) first (gsk A.6.20)", column);
  }
  // The input: L (on) / K (off) / I (signed) name its port, else param 5510 (on); P names a
  // PLC signal (P1-P8) or the torque (P98/P99).
  BlockWord* l = word('L');
  BlockWord* k = word('K');
  BlockWord* i = word('I');
  BlockWord* p = word('P');
  const int ways = (l != nullptr) + (k != nullptr) + (i != nullptr) + (p != nullptr);
  if (ways > 1) {
    BlockWord* second = p != nullptr ? p : (i != nullptr ? i : k);
    return fail(alarm::kWordNotAllowed, "G31 takes one of L, K, I and P", second->column);
  }
  if (p != nullptr) {
    p->used = true;
    const bool torque = p->value == 98.0 || p->value == 99.0;
    if (!torque && !(p->value >= 1.0 && p->value <= 8.0 && p->value == std::floor(p->value))) {
      return fail(alarm::kBadWordValue, "G31 P must be 1-8, 98 or 99", p->column);
    }
    return fail(alarm::kNotInThisVersion,
                torque ? "G31 P98/P99 (the torque skip) needs the drive's torque limit, not in "
                         "this version"
                       : "G31 P1-P8 (the PLC's skip signals G0014) is not in this version: wire "
                         "the probe to a drive and name its input with L, K or I",
                p->column);
  }
  int input = config_.skip_input;
  bool on = true;
  if (BlockWord* w = l != nullptr ? l : (k != nullptr ? k : i)) {
    w->used = true;
    const double v = w == i ? std::fabs(w->value) : w->value;
    if (!(v >= 1.0 && v <= 99.0 && v == std::floor(v))) {
      return fail(alarm::kBadWordValue,
                  std::string("G31 ") + w->address.first + " must name an input 1-99", w->column);
    }
    input = static_cast<int>(v);
    on = w == l || (w == i && w->value > 0.0);
  } else if (input == 0) {
    return fail(alarm::kSkipInput,
                "G31 without L, K or I skips on the input of param 5510, which is 0 "
                "(skip_input in the machine file)",
                column);
  }
  std::int64_t flag = 0;
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (!(r->value >= 1.0 && r->value == std::floor(r->value))) {
      return fail(alarm::kBadWordValue, "G31 R names the variable that receives the result",
                  r->column);
    }
    flag = static_cast<std::int64_t>(r->value);
  }
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  bool any = false;
  for (std::size_t a = 0; a < config_.axes.size(); ++a) {
    any = any || (given[a] && target[a] != machine_[a]);
  }
  if (!any) {
    return fail(alarm::kWordNotAllowed, "G31 needs an end point to move to", column);
  }
  if (!check_feed(column)) {
    return false;
  }
  Command& c = emit(Op::linear);
  c.to = target;
  c.feed = feed_;
  c.feed_mode = feed_mode_;
  c.exact_stop = true;
  c.skip = true;
  c.input = input;
  c.input_on = on;
  block_barrier_ = true;
  machine_ = target;
  block_moved_ = true;
  // Until the channel says otherwise (a dry run, `mcnc interp`): skipped at the end point, so
  // a program that checks the signal runs its checked branch.
  skip_flag_variable_ = flag;
  record_skip(true, transform::to_vector(frame_.to_machine(transform::to_point(machine_))));
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
  if (skip_flag_variable_ != 0) {
    (void)vars_.write(skip_flag_variable_, macro::MacroValue::of(skipped ? 1.0 : 0.0));
  }
}

}  // namespace mcnc::interp
