// G07.1 / G107 cylindrical interpolation (spec dafeng L612-710): the program moves the tool on
// the cylinder's surface unrolled into the plane, the rotary axis programmed in degrees
// (transform/cylindrical_interpolation.hpp).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

bool ProgramRun::run_cylindrical(int column) {
  // The block holds G07.1 and the rotary axis with the cylinder's radius, nothing else.
  BlockWord* radius_word = nullptr;
  int axis = -1;
  for (BlockWord& w : words_) {
    if (w.column == column) {
      continue;
    }
    int named = -1;
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      const bool plain = w.address.second == 0 && !w.address.comma && w.index < 0;
      named = plain && config_.axes[i].rotary && w.address.first == config_.axes[i].name
                  ? static_cast<int>(i)
                  : named;
    }
    if (named < 0 || radius_word != nullptr) {
      return fail(alarm::kMustBeAlone,
                  "G07.1 stands alone in its block with the rotary axis and the cylinder's "
                  "radius, e.g. G07.1 C30 (spec L612-710)",
                  w.column);
    }
    radius_word = &w;
    axis = named;
  }
  if (radius_word == nullptr) {
    return fail(alarm::kCycleWordMissing,
                "G07.1 needs the rotary axis and the cylinder's radius, e.g. G07.1 C30 (C0 ends "
                "it)",
                column);
  }
  radius_word->used = true;
  const double radius = scaled(*radius_word, true) * (modal_.metric ? 1.0 : 25.4);
  if (radius < 0.0) {
    return fail(alarm::kBadWordValue, "the cylinder's radius must not be negative",
                radius_word->column);
  }
  if (contour_.active()) {
    return contour_forbids("G07.1", column);
  }
  if (compensation_ != Command::Compensation::off || lookahead_.holding()) {
    return fail(alarm::kInterpolationModeRestriction,
                "G07.1 is switched under G40 only: cancel G41/G42 with a move first", column);
  }
  if (radius == 0.0) {
    end_cylindrical();
    return true;
  }
  if (cylindrical_) {
    return fail(alarm::kInterpolationModeRestriction,
                "G07.1 while cylindrical interpolation is on: end it with G07.1 " +
                    std::string(1, config_.axes[static_cast<std::size_t>(cylinder_axis_)].name) +
                    "0 first",
                column);
  }
  if (frame_active() || modal_.turret_mirror) {
    return fail(alarm::kInterpolationModeRestriction,
                "G07.1 is not allowed under G68.1, G51.1 or G68 (spec L4502-4652): cancel them "
                "first",
                column);
  }
  if (offset_sum(axis) != 0.0 || tool_offset(axis) != 0.0) {
    return fail(alarm::kInterpolationModeRestriction,
                "G07.1 on a rotary axis with a work offset, G50 shift or G52: the angles on the "
                "cylinder are machine angles here",
                radius_word->column);
  }
  // The plane as the mode will see it: it must hold the rotary axis.
  cylinder_axis_ = axis;
  cylindrical_ = true;
  const std::array<int, 2> plane = plane_axis_indices();
  if (plane[0] != axis && plane[1] != axis) {
    cylindrical_ = false;
    return fail(alarm::kInterpolationModeRestriction,
                std::string("select the plane with ") + config_.cylindrical_parallel +
                    " (the axis the rotary axis is parallel to, param 0016) before G07.1 (spec "
                    "L612-710)",
                column);
  }
  cylinder_radius_ = radius;
  cylindrical_ = true;
  const auto rot = static_cast<std::size_t>(axis);
  machine_[rot] = transform::CylindricalInterpolation(radius).to_length(machine_[rot]);
  cylinder_from_ = machine_;
  lookahead_.passed(machine_);
  return true;
}

void ProgramRun::end_cylindrical() {
  if (!cylindrical_) {
    return;
  }
  const auto rot = static_cast<std::size_t>(cylinder_axis_);
  machine_[rot] = transform::CylindricalInterpolation(cylinder_radius_).to_degrees(machine_[rot]);
  cylindrical_ = false;
  lookahead_.passed(machine_);
}

void ProgramRun::expand_cylindrical(std::vector<Command>& list, std::size_t from) {
  const transform::CylindricalInterpolation cylinder(cylinder_radius_);
  const auto rot = static_cast<std::size_t>(cylinder_axis_);
  const std::array<int, 2> axes = plane_axis_indices();
  auto on_machine = [&](AxisVector v) {
    v[rot] = cylinder.to_degrees(v[rot]);
    return v;
  };
  const auto first = list.begin() + static_cast<std::ptrdiff_t>(from);
  const std::vector<Command> made(first, list.end());
  list.erase(first, list.end());
  for (const Command& c : made) {
    if (c.op != Op::linear && c.op != Op::arc) {
      list.emplace_back(c).to = on_machine(c.to);
      continue;
    }
    const auto a = static_cast<std::size_t>(axes[0]);
    const auto b = static_cast<std::size_t>(axes[1]);
    const transform::PlanePiece piece = plane_piece(c, cylinder_from_, axes, {0.0, 0.0});
    const double total = piece.length();
    std::vector<ModeStep> steps;
    double before = 0.0;
    for (const double f :
         transform::CylindricalInterpolation::chord_ends(piece, config_.polar_tolerance)) {
      const std::array<double, 2> p = piece.at(f);
      steps.push_back(ModeStep{a == rot ? cylinder.to_degrees(p[0]) : p[0],
                               b == rot ? cylinder.to_degrees(p[1]) : p[1], (f - before) * total});
      before = f;
    }
    emit_mode_steps(list, c, cylinder_from_, on_machine(cylinder_from_), axes, steps, total);
    cylinder_from_ = c.to;
  }
}

}  // namespace mcnc::interp
