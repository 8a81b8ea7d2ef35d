// G10 L14 P7 / P8 (spec dafeng §2.9.2, L4895-5093): the load of the drilling (G83/G87) and
// rigid tapping (G84/G88 with M29) cycles watched while they feed into the hole. The
// interpreter marks each in-feed with the loads, where the tool retracts to (R) and what
// follows an overload (params 5100/5200); the channel watches the drive's load, retracts and
// alarms, goes on or retries, and tells how it went (set_overload_result).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <string>

namespace mcnc::interp {

namespace {
// The longest load filter J a program may name: an hour (as P0/P1's).
constexpr double kMaxOverloadFilterSeconds = 3600.0;
}  // namespace

bool ProgramRun::run_overload_watch(int /*column*/) {
  // G10 L14 P7|P8 R J α (L4897-4906): α the load of each axis named (% of the rated torque,
  // absolute addresses only), J the seconds it must stay above, R the variable that counts the
  // overloads (else param 5113 / 5251). Without axes it cancels the watch (L4906).
  const int p = static_cast<int>(word('P')->value);
  const std::string code = "G10 L14 P" + std::to_string(p);
  OverloadWatch w;
  if (!read_result_variable('R', code.c_str(), "the count of overloads", w.variable)) {
    return false;
  }
  if (BlockWord* j = word('J')) {
    j->used = true;
    if (!(j->value >= 0.0 && j->value <= kMaxOverloadFilterSeconds)) {
      return fail(alarm::kBadWordValue, code + " J (the filter time, s) must be 0-3600", j->column);
    }
    w.filter_s = j->value;
  }
  if (!read_axis_percents("the overload loads", w.loads, w.axes)) {
    return false;
  }
  const OverloadParams& params =
      p == 7 ? config_.cycles.drill_overload : config_.cycles.tap_overload;
  if (w.variable == 0) {
    w.variable = params.variable;
  }
  overload_watch_[p == 7 ? 0 : 1] = w.axes != 0 ? w : OverloadWatch{};
  return true;
}

void ProgramRun::watch_overload(Command& c, bool tapping, double depth) {
  const OverloadWatch& w = overload_watch_[tapping ? 1 : 0];
  if (w.axes == 0) {
    return;
  }
  const OverloadParams& params =
      tapping ? config_.cycles.tap_overload : config_.cycles.drill_overload;
  c.overload_axes = w.axes;
  std::copy(w.loads.begin(), w.loads.end(), c.overload_loads.begin());
  c.overload_filter_s = w.filter_s;
  c.overload_retract = depth;
  c.overload_outcome = !params.retract ? Command::Overload::stop
                       : params.retry  ? Command::Overload::retry
                       : params.alarm  ? Command::Overload::alarm
                                       : Command::Overload::go_on;
  c.overload_variable = w.variable;
  overload_variable_ = w.variable;
  c.overload_p = tapping ? 8 : 7;
  if (overload_block_ == 0) {
    overload_block_ = ++overload_blocks_;
  }
  c.overload_block = overload_block_;
  // The channel runs the in-feed on its own (it may retract and retry it) and answers before
  // anything after it is read: a read-ahead stop.
  c.barrier = true;
}

void ProgramRun::set_overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                                     const AxisVector& stop_at) {
  const std::int64_t variable = overload_variable_;
  if (overloads != 0 && variable != 0) {
    // "The variable + 1 on each overload" (L4900); one that cannot be written stays as it was.
    const macro::VariableRead before = vars_.read(variable);
    (void)vars_.write(variable, macro::MacroValue::of(before.value.number() + overloads));
  }
  if (dropped_block == 0) {
    return;
  }
  // Case 2 (L4913-4914): the block ends where the tool retracted to; the rest of its commands
  // (the other holes of K, the way out) is not run.
  while (ready_head_ < ready_.size() && ready_[ready_head_].overload_block == dropped_block) {
    ++ready_head_;
  }
  if (ready_head_ == ready_.size()) {
    ready_.clear();
    ready_head_ = 0;
  }
  set_machine(stop_at);
}

}  // namespace mcnc::interp
