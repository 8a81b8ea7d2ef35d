// Inclined-axis control (spec dafeng §2.9, L4653-4767): the program and everything the
// interpreter computes stay in the Cartesian coordinates of a slide at right angles; the moves
// leave in the machine's inclined ones. The map is affine but not rigid, so a line stays a line
// while an arc of the program is no arc of the machine: arcs leave as chords.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"
#include "channel/interp/transform/cylindrical_interpolation.hpp"
#include "channel/interp/transform/inclined_axis.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::interp {

namespace {

// An arc's chords under inclined-axis control: as polar interpolation's steps are bounded, so
// that a huge arc with a tight tolerance is an alarm and not the read-ahead thread's memory.
constexpr std::size_t kMaxChords = 1'000'000;

double distance(const AxisVector& a, const AxisVector& b, std::size_t axes) {
  double sum = 0.0;
  for (std::size_t i = 0; i < axes; ++i) {
    sum += (b[i] - a[i]) * (b[i] - a[i]);
  }
  return std::sqrt(sum);
}

// The planner counts a thread's revolutions along the axis that travels farthest
// (motion_planner_queue.cpp): the lead is given along that axis.
double longest_travel(const AxisVector& a, const AxisVector& b, std::size_t axes) {
  double longest = 0.0;
  for (std::size_t i = 0; i < axes; ++i) {
    longest = std::max(longest, std::fabs(b[i] - a[i]));
  }
  return longest;
}

}  // namespace

AxisVector ProgramRun::to_inclined(const AxisVector& cartesian) const {
  return transform::to_vector(inclined_.to_machine(transform::to_point(cartesian)));
}

AxisVector ProgramRun::from_inclined(const AxisVector& inclined) const {
  return transform::to_vector(inclined_.to_program(transform::to_point(inclined)));
}

bool ProgramRun::inclined_allows(int axis, const std::string& what, int column) {
  if (!inclined_on() || (axis != inclined_axes_[0] && axis != inclined_axes_[1])) {
    return true;
  }
  const bool inclined = axis == inclined_axes_[0];
  return fail(alarm::kInclinedAxisRestriction,
              std::string(1, config_.axes[static_cast<std::size_t>(axis)].name) + " is the " +
                  (inclined ? "inclined axis (param 5691)" : "orthogonal axis (param 5692)") +
                  " of inclined-axis control: " + what + " (spec L4653-4767)",
              column);
}

void ProgramRun::expand_inclined(std::vector<Command>& list, std::size_t from) {
  if (!inclined_on() || from >= list.size()) {
    return;
  }
  const std::size_t axes = config_.axes.size();
  // Where the first of these moves starts: the end of the last one released (inclined).
  AxisVector at = from_inclined(released_at_);
  const auto first = list.begin() + static_cast<std::ptrdiff_t>(from);
  const std::vector<Command> made(first, list.end());
  list.erase(first, list.end());
  for (const Command& c : made) {
    if (!c.moves()) {
      list.push_back(c);
      continue;
    }
    const AxisVector start = at;
    at = c.to;
    if (c.op == Op::thread && c.thread_arc) {
      if (!alarm_) {
        alarm_ = ProgramAlarm{alarm::kInclinedAxisRestriction,
                              "an arc thread (G32.2/G32.3) cannot be cut under inclined-axis "
                              "control: its chords would not keep one lead (spec L4653-4767)",
                              c.file != nullptr ? *c.file : std::string(), c.line, 0};
      }
      return;
    }
    if (c.op != Op::arc) {
      Command& m = list.emplace_back(c);
      m.to = to_inclined(c.to);
      const AxisVector machine_start = to_inclined(start);
      if (c.op == Op::linear) {
        // The same time as the programmed line: F along the machine's longer or shorter line.
        const double programmed = distance(start, c.to, axes);
        if (programmed > 0.0) {
          m.feed = c.feed * distance(machine_start, m.to, axes) / programmed;
        }
      } else if (c.op == Op::thread) {
        // The same revolutions: the lead along the machine's farthest-travelling axis.
        const double programmed = longest_travel(start, c.to, axes);
        if (programmed > 0.0) {
          const double scale = longest_travel(machine_start, m.to, axes) / programmed;
          m.lead = c.lead * scale;
          m.lead_change = c.lead_change * scale;
        }
      }
      continue;
    }
    // An arc (with its helical axes): chords of the programmed arc, each mapped.
    const transform::PlanePiece piece = plane_piece(c, start, c.center_axes, {0.0, 0.0});
    const double plane_length = piece.length();
    double others = 0.0;  // the helical axes' travel, squared
    for (std::size_t i = 0; i < axes; ++i) {
      if (static_cast<int>(i) != c.center_axes[0] && static_cast<int>(i) != c.center_axes[1]) {
        others += (c.to[i] - start[i]) * (c.to[i] - start[i]);
      }
    }
    const double total = std::sqrt(plane_length * plane_length + others);
    const std::vector<double> ends =
        transform::CylindricalInterpolation::chord_ends(piece, config_.polar_tolerance, kMaxChords);
    if (ends.empty()) {
      if (!alarm_) {
        alarm_ = ProgramAlarm{alarm::kInclinedAxisRestriction,
                              "the arc needs more than " + std::to_string(kMaxChords) +
                                  " chords within the tolerance under inclined-axis control "
                                  "(spec L4653-4767): split it or widen polar.tolerance",
                              c.file != nullptr ? *c.file : std::string(), c.line, 0};
      }
      return;
    }
    AxisVector chord_start = to_inclined(start);
    double before = 0.0;
    for (std::size_t k = 0; k < ends.size(); ++k) {
      const bool last = k + 1 == ends.size();
      const double f = ends[k];
      AxisVector p = c.to;
      if (!last) {
        for (std::size_t i = 0; i < axes; ++i) {
          p[i] = start[i] + f * (c.to[i] - start[i]);
        }
        const std::array<double, 2> q = piece.at(f);
        p[static_cast<std::size_t>(c.center_axes[0])] = q[0];
        p[static_cast<std::size_t>(c.center_axes[1])] = q[1];
      }
      Command& step = list.emplace_back(c);
      step.op = Op::linear;
      step.to = to_inclined(p);
      step.exact_stop = c.exact_stop && last;
      const double programmed = (f - before) * total;
      if (programmed > 0.0) {
        step.feed = c.feed * distance(chord_start, step.to, axes) / programmed;
      }
      chord_start = step.to;
      before = f;
    }
  }
}

}  // namespace mcnc::interp
