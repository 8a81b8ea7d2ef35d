// G12.1 / G13.1 polar interpolation, format 1 (spec dafeng L711-849): the program moves the tool
// tip in the plane of the linear axis and a virtual axis at right angles to it; the machine
// turns the work on the rotary axis (transform/polar_interpolation.hpp).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::interp {

namespace {

constexpr std::size_t kMaxPolarSteps = 200000;  // machine lines of one programmed move

}  // namespace

bool ProgramRun::polar_allows(GFunction f, int code10, int column) {
  if (!interpolation_mode()) {
    return true;
  }
  switch (f) {
    // The codes the spec allows in polar interpolation (L711-849, detail 8).
    case GFunction::linear:
    case GFunction::arc_cw:
    case GFunction::arc_ccw:
    case GFunction::dwell:
    case GFunction::tnrc_cancel:
    case GFunction::macro_call:
    case GFunction::absolute:
    case GFunction::incremental:
    case GFunction::feed_per_min:
    case GFunction::feed_per_rev:
    case GFunction::polar_off:
      return true;
    case GFunction::cylindrical:
      return cylindrical_ ||
             fail(alarm::kInterpolationModeRestriction,
                  "G07.1 is not allowed in polar interpolation: G13.1 first", column);
    case GFunction::polar_coords_on:
    case GFunction::polar_coords_off:
      return polar_ ||
             fail(alarm::kInterpolationModeRestriction,
                  "G15/G16 are not allowed in cylindrical interpolation: G07.1 " +
                      std::string(1, config_.axes[static_cast<std::size_t>(cylinder_axis_)].name) +
                      "0 first",
                  column);
    case GFunction::tnrc_left:
    case GFunction::tnrc_right:
      return true;
    default:
      return fail(alarm::kInterpolationModeRestriction,
                  "G" + std::to_string(code10 / 10) +
                      (code10 % 10 != 0 ? "." + std::to_string(code10 % 10) : "") +
                      " is not allowed in polar or cylindrical interpolation (spec L711-849): "
                      "cancel the mode first",
                  column);
  }
}

bool ProgramRun::run_polar(GFunction f, int column) {
  const bool on = f == GFunction::polar_on;
  const std::string code = on ? "G12.1" : "G13.1";
  for (const BlockWord& w : words_) {
    if (w.column != column) {
      return fail(alarm::kMustBeAlone, code + " stands alone in its block (spec L711-849)",
                  w.column);
    }
  }
  if (contour_.active()) {
    return contour_forbids(on ? "G12.1" : "G13.1", column);
  }
  if (compensation_ != Command::Compensation::off || lookahead_.holding()) {
    return fail(alarm::kInterpolationModeRestriction,
                code +
                    " is switched under G40 only (spec L711-849): cancel G41/G42 with a move "
                    "first",
                column);
  }
  if (!on) {
    end_polar();
    return true;
  }
  if (polar_) {
    return fail(alarm::kInterpolationModeRestriction, "G12.1 while polar interpolation is on",
                column);
  }
  if (frame_active() || modal_.turret_mirror) {
    return fail(alarm::kInterpolationModeRestriction,
                "G12.1 is not allowed under G68.1, G51.1 or G68 (spec L4502-4652): cancel them "
                "first",
                column);
  }
  std::array<int, 2> axes{-1, -1};
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    axes[0] = config_.axes[i].name == config_.polar_linear ? static_cast<int>(i) : axes[0];
    axes[1] = config_.axes[i].name == config_.polar_rotary ? static_cast<int>(i) : axes[1];
  }
  if (axes[0] < 0 || axes[1] < 0 || config_.axes[static_cast<std::size_t>(axes[0])].rotary ||
      !config_.axes[static_cast<std::size_t>(axes[1])].rotary) {
    return fail(alarm::kInterpolationModeRestriction,
                "G12.1 needs a linear and a rotary axis of this channel for polar interpolation "
                "(parameters 5530/5531: `polar` of the parameter file)",
                column);
  }
  const auto lin = static_cast<std::size_t>(axes[0]);
  const auto rot = static_cast<std::size_t>(axes[1]);
  const double x = machine_[lin] - offset_sum(axes[0]) - tool_offset(axes[0]);
  if (x < 0.0) {
    return fail(alarm::kInterpolationModeRestriction,
                "G12.1 with the tool below the turning centre (a negative radius): position "
                "the linear axis at 0 or above first",
                column);
  }
  polar_axes_ = axes;
  polar_zero_ = machine_[rot];
  polar_at_ = transform::PolarPoint{x, polar_zero_};
  // The virtual axis starts at 0, wherever the rotary axis stands (spec L711-849, detail 10).
  machine_[rot] = offset_sum(axes[1]) + tool_offset(axes[1]);
  polar_from_ = machine_;
  polar_command_.reset();
  lookahead_.passed(machine_);
  polar_ = true;
  modal_.codes[21] = 12.1;
  return true;
}

bool ProgramRun::polar_coordinate_target(AxisVector& target,
                                         std::array<bool, kMaxChannelAxes>& given) {
  if (!polar_) {
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      const AxisWords aw = given[i] ? axis_words(static_cast<int>(i)) : AxisWords{};
      if (aw.word != nullptr) {
        return fail(alarm::kInterpolationModeRestriction,
                    "under G16 the axis words are polar coordinates of G12.1's plane (spec "
                    "L711-849, format 2): G12.1 first, or G15",
                    aw.word->column);
      }
    }
    return true;
  }
  if (BlockWord* a = comma_word('A'); a != nullptr && config_.dialect != Dialect::gsk) {
    return fail(alarm::kInterpolationModeRestriction,
                "no ,A under G16: the end point is given by its radius and angle already",
                a->column);
  }
  const int lin = polar_axes_[0];
  const int rot = polar_axes_[1];
  const AxisWords radius = axis_words(lin);
  const AxisWords angle = axis_words(rot);
  if (radius.word == nullptr && angle.word == nullptr) {
    return true;
  }
  const auto l = static_cast<std::size_t>(lin);
  const auto r = static_cast<std::size_t>(rot);
  const double shift_l = offset_sum(lin) + tool_offset(lin);
  const double shift_r = offset_sum(rot) + tool_offset(rot);
  std::array<double, 2> polar{};
  if (polar_command_) {
    polar = *polar_command_;
  } else {
    // From the plane's point where G16 finds the tool (G12.1 starts at the angle 0).
    const double x = machine_[l] - shift_l;
    const double y = machine_[r] - shift_r;
    polar = {std::hypot(x, y), std::atan2(y, x) * 180.0 / std::numbers::pi};
  }
  if (radius.word != nullptr) {
    const double v = to_physical(lin, scaled_axis_word(lin, *radius.word));
    polar[0] = radius.incremental ? polar[0] + v : v;
  }
  if (angle.word != nullptr) {
    const double v = scaled_axis_word(rot, *angle.word);  // degrees, also in G20
    polar[1] = angle.incremental ? polar[1] + v : v;
  }
  const double a = polar[1] * std::numbers::pi / 180.0;
  target[l] = polar[0] * std::cos(a) + shift_l;
  target[r] = polar[0] * std::sin(a) + shift_r;
  given[l] = true;
  given[r] = true;
  polar_command_ = polar;
  return true;
}

void ProgramRun::end_polar() {
  modal_.codes[21] = 13.1;
  if (!polar_) {
    return;
  }
  const auto lin = static_cast<std::size_t>(polar_axes_[0]);
  const auto rot = static_cast<std::size_t>(polar_axes_[1]);
  machine_[lin] = polar_at_.radius + offset_sum(polar_axes_[0]) + tool_offset(polar_axes_[0]);
  machine_[rot] = polar_at_.degrees;
  polar_ = false;
  lookahead_.passed(machine_);
}

void ProgramRun::expand_modes(std::vector<Command>& list, std::size_t from) {
  if (polar_) {
    expand_polar(list, from);
  } else if (cylindrical_) {
    expand_cylindrical(list, from);
  }
}

void ProgramRun::expand_polar(std::vector<Command>& list, std::size_t from) {
  const auto lin = static_cast<std::size_t>(polar_axes_[0]);
  const auto rot = static_cast<std::size_t>(polar_axes_[1]);
  const double t_lin = offset_sum(polar_axes_[0]) + tool_offset(polar_axes_[0]);
  const double t_rot = offset_sum(polar_axes_[1]) + tool_offset(polar_axes_[1]);
  const transform::PolarInterpolation polar(polar_zero_);
  auto on_machine = [&](const transform::PolarPoint& m, AxisVector v) {
    v[lin] = m.radius + t_lin;
    v[rot] = m.degrees;
    return v;
  };
  const auto first = list.begin() + static_cast<std::ptrdiff_t>(from);
  const std::vector<Command> made(first, list.end());
  list.erase(first, list.end());
  for (const Command& c : made) {
    if (c.op != Op::linear && c.op != Op::arc) {
      Command& kept = list.emplace_back(c);
      kept.to = on_machine(polar_at_, c.to);
      continue;
    }
    const transform::PlanePiece piece = plane_piece(c, polar_from_, polar_axes_, {t_lin, t_rot});
    std::vector<transform::PolarStep> steps;
    if (!polar.steps(piece, polar_at_.degrees, config_.polar_tolerance, steps, kMaxPolarSteps)) {
      fail(alarm::kInterpolationModeRestriction,
           "the move needs more than " + std::to_string(kMaxPolarSteps) +
               " machine lines to stay on the contour in polar interpolation",
           0);
      return;
    }
    std::vector<ModeStep> machine_steps;
    machine_steps.reserve(steps.size());
    for (const transform::PolarStep& s : steps) {
      machine_steps.push_back(
          ModeStep{s.machine.radius + t_lin, s.machine.degrees, s.plane_length});
    }
    emit_mode_steps(list, c, polar_from_, on_machine(polar_at_, polar_from_), polar_axes_,
                    machine_steps, piece.length());
    polar_at_ = steps.back().machine;
    polar_from_ = c.to;
  }
}

transform::PlanePiece ProgramRun::plane_piece(const Command& c, const AxisVector& from,
                                              const std::array<int, 2>& axes,
                                              const std::array<double, 2>& shift) {
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  transform::PlanePiece piece;
  piece.from = {from[a] - shift[0], from[b] - shift[1]};
  piece.to = {c.to[a] - shift[0], c.to[b] - shift[1]};
  if (c.op == Op::arc) {
    piece.arc = true;
    piece.centre = {c.center[0] - shift[0], c.center[1] - shift[1]};
    piece.ccw = c.direction == ArcDirection::ccw;
    piece.turns = c.turns;
  }
  return piece;
}

void ProgramRun::emit_mode_steps(std::vector<Command>& into, const Command& c,
                                 const AxisVector& from, const AxisVector& start,
                                 const std::array<int, 2>& axes, const std::vector<ModeStep>& steps,
                                 double total) {
  double covered = 0.0;
  AxisVector at = start;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const ModeStep& s = steps[k];
    const bool last = k + 1 == steps.size();
    covered += s.length;
    // The axes outside the mode's plane move in proportion to the contour's length.
    const double f = last || total <= 0.0 ? 1.0 : covered / total;
    Command& step = into.emplace_back(c);
    step.op = Op::linear;
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      step.to[i] = from[i] + f * (c.to[i] - from[i]);
    }
    step.to[static_cast<std::size_t>(axes[0])] = s.first;
    step.to[static_cast<std::size_t>(axes[1])] = s.second;
    step.exact_stop = c.exact_stop && last;
    // F is the speed along the contour: the machine line of this step is longer (angles count
    // as lengths for the planner) or shorter than the piece of contour it covers.
    double machine_length = 0.0;
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      machine_length += (step.to[i] - at[i]) * (step.to[i] - at[i]);
    }
    if (machine_length > 0.0) {
      step.feed = c.feed * std::sqrt(machine_length) / std::max(s.length, config_.polar_tolerance);
    }
    at = step.to;
  }
}

}  // namespace mcnc::interp
