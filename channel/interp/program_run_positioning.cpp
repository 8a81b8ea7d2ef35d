// The mill's one-shot positioning codes (gsk B.1; FANUC 0i-M for what the seed leaves out):
// G27 reference point return check, G29 return from the reference point, G60 single-direction
// positioning. Each moves at rapid, as G28 does.
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

namespace {

constexpr double kAtReference = 1e-6;  // mm or degrees

}  // namespace

bool ProgramRun::run_reference_check(int column) {
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  // The point reached must be the first reference point of every named axis. The interpreter
  // knows where it will be, so the alarm comes before the block moves (docs/alarms.md).
  const AxisVector reached = to_inclined(target);
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    const double home = config_.axes[i].reference[0];
    if (given[i] && std::fabs(reached[i] - home) > kAtReference) {
      return fail(alarm::kReferencePoint,
                  std::string("G27: ") + config_.axes[i].name + " would end at machine " +
                      path::mm_text(reached[i]) + ", not at its reference point " +
                      path::mm_text(home),
                  column);
    }
  }
  if (target != machine_) {
    emit(Op::rapid).to = target;
    machine_ = target;
    block_moved_ = true;
  }
  return true;
}

bool ProgramRun::run_return_from_reference(int column) {
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  // Through the last G28/G30's intermediate point, on the axes that named one.
  AxisVector via = machine_;
  bool any = false;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (!given[i]) {
      continue;
    }
    any = true;
    if (!reference_via_given_[i]) {
      return fail(alarm::kReferencePoint,
                  std::string("G29: ") + config_.axes[i].name +
                      " has no intermediate point: a G28 or G30 naming it comes first",
                  column);
    }
    via[i] = reference_via_[i];
  }
  if (!any) {
    return true;
  }
  if (via != machine_) {
    emit(Op::rapid).to = via;
  }
  emit(Op::rapid).to = target;
  machine_ = target;
  block_moved_ = true;
  return true;
}

bool ProgramRun::run_single_direction(int /*column*/) {
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  // Every named axis goes to its end point less its approach first and comes in from there in
  // the approach's direction, so the backlash is always taken up the same way.
  AxisVector past = target;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    past[i] -= given[i] ? config_.axes[i].approach : 0.0;
  }
  if (past != target && past != machine_) {
    emit(Op::rapid).to = past;
  }
  if (target != machine_) {
    emit(Op::rapid).to = target;
    block_moved_ = true;
  }
  machine_ = target;
  return true;
}

}  // namespace mcnc::interp
