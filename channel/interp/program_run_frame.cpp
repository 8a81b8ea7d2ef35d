// The G68.1 coordinate rotation (spec dafeng L4502-4652) and the G51.1 programmable mirror
// (L4233-4278): the frame between the interpreter's positions and the machine, built as a chain
// of transform links (channel/interp/transform/).
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"
#include "channel/interp/transform/axis_shift.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::interp {

namespace {

const char* frame_code_name(GFunction f, GCodeSystem system) {
  switch (f) {
    case GFunction::reference_return:
      return "G28";
    case GFunction::reference_2_4:
      return "G30";
    case GFunction::coordinate_set:
      return system == GCodeSystem::a ? "G50" : "G92";
    case GFunction::restore_origin:
      return system == GCodeSystem::a ? "G50.3" : "G92.1";
    case GFunction::local_system:
      return "G52";
    case GFunction::work_system:
    case GFunction::work_system_ext:
      return "a work coordinate system (G54-G59, G54.1)";
    case GFunction::turret_mirror_on:
      return "G68";
    default:
      return "";
  }
}

}  // namespace

AxisVector ProgramRun::machine() const {
  AxisVector m = transform::to_vector(frame_.to_machine(transform::to_point(machine_)));
  if (polar_) {
    const auto lin = static_cast<std::size_t>(polar_axes_[0]);
    m[lin] = polar_at_.radius + offset_sum(polar_axes_[0]) + tool_offset(polar_axes_[0]);
    m[static_cast<std::size_t>(polar_axes_[1])] = polar_at_.degrees;
  }
  if (cylindrical_) {
    const auto rot = static_cast<std::size_t>(cylinder_axis_);
    m[rot] = transform::CylindricalInterpolation(cylinder_radius_).to_degrees(m[rot]);
  }
  return to_inclined(m);
}

void ProgramRun::set_machine(const AxisVector& where) {
  // An oscillating axis (G81.1) stands anywhere in its stroke: the program keeps it where G81.1
  // found it, as the planner's path does.
  AxisVector inclined = where;
  for (std::size_t i = 0; i < config_.axes.size() && i < kMaxChannelAxes; ++i) {
    inclined[i] = oscillating_[i] ? machine_[i] : inclined[i];
  }
  released_at_ = inclined;
  const AxisVector at = from_inclined(inclined);  // what the modes below work in
  normal_.reset(at);
  machine_ = transform::to_vector(frame_.to_program(transform::to_point(at)));
  if (polar_) {
    // In polar interpolation the two axes stand for a point of the polar plane.
    const auto lin = static_cast<std::size_t>(polar_axes_[0]);
    const auto rot = static_cast<std::size_t>(polar_axes_[1]);
    const double t_lin = offset_sum(polar_axes_[0]) + tool_offset(polar_axes_[0]);
    polar_at_ = transform::PolarPoint{at[lin] - t_lin, at[rot]};
    const std::array<double, 2> p = transform::PolarInterpolation(polar_zero_).to_plane(polar_at_);
    machine_[lin] = p[0] + t_lin;
    machine_[rot] = p[1] + offset_sum(polar_axes_[1]) + tool_offset(polar_axes_[1]);
    polar_from_ = machine_;
  }
  if (cylindrical_) {
    const auto rot = static_cast<std::size_t>(cylinder_axis_);
    machine_[rot] = transform::CylindricalInterpolation(cylinder_radius_).to_length(at[rot]);
    cylinder_from_ = machine_;
  }
}

bool ProgramRun::frame_allows(GFunction f, int code10, int column) {
  if (!frame_active()) {
    return true;
  }
  const char* active = rotated_ ? "G68.1" : "G51.1";
  switch (f) {
    case GFunction::plane_xy:
    case GFunction::plane_zx:
    case GFunction::plane_yz: {
      const Plane wanted = f == GFunction::plane_xy   ? Plane::xy
                           : f == GFunction::plane_zx ? Plane::zx
                                                      : Plane::yz;
      if (!rotated_ || wanted == modal_.plane) {
        return true;
      }
      return fail(alarm::kFrameRestriction,
                  "G" + std::to_string(code10 / 10) +
                      " changes the plane while G68.1 turns the coordinates (spec "
                      "L4502-4652): cancel with G69.1 first",
                  column);
    }
    case GFunction::coordinate_set: {
      bool axis_word = false;  // G50 S (the spindle clamp) alone is allowed
      for (std::size_t i = 0; i < config_.axes.size(); ++i) {
        axis_word = axis_word || axis_words(static_cast<int>(i)).word != nullptr;
      }
      if (!axis_word) {
        return true;
      }
      break;
    }
    case GFunction::reference_return:
    case GFunction::reference_2_4:
    case GFunction::restore_origin:
    case GFunction::local_system:
    case GFunction::work_system:
    case GFunction::work_system_ext:
    case GFunction::turret_mirror_on:
      break;
    default:
      return true;
  }
  return fail(alarm::kFrameRestriction,
              std::string(frame_code_name(f, config_.system)) + " is not allowed while " + active +
                  " is active: cancel it first (" + (rotated_ ? "G69.1" : "G50.1") + ")",
              column);
}

bool ProgramRun::run_rotation(GFunction f, int column) {
  if (contour_.active()) {
    return contour_forbids(f == GFunction::rotation_on ? "G68.1" : "G69.1", column);
  }
  if (f == GFunction::rotation_off) {
    rotated_ = false;
    modal_.codes[17] = 69.1;
    rebuild_frame();
    return true;
  }
  if (modal_.turret_mirror) {
    return fail(alarm::kFrameRestriction,
                "G68.1 is not allowed under the facing turret's mirror G68: cancel it first (G69)",
                column);
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  BlockWord* r = word('R');
  if (r == nullptr) {
    return fail(alarm::kCycleWordMissing, "G68.1 needs the rotation angle R (degrees)", column);
  }
  r->used = true;
  transform::PlaneRotation rotation;
  rotation.axes = axes;
  // Angles beyond 360 degrees count modulo 360 (spec L4579: 400 is 40).
  rotation.degrees = std::fmod(scaled(*r, false), 360.0);
  for (std::size_t k = 0; k < 2; ++k) {
    const int axis = axes[k];
    const AxisWords aw = axis_words(axis);
    if (aw.error) {
      return false;
    }
    if (aw.word == nullptr) {
      // An omitted centre is the current position (spec L4502-4652, detail 4).
      const auto i = static_cast<std::size_t>(axis);
      rotation.centre[k] = machine_[i] - offset_sum(axis) - tool_offset(axis);
      continue;
    }
    aw.word->used = true;
    if (aw.incremental) {
      return fail(alarm::kWordNotAllowed,
                  "the centre of G68.1 is an absolute position (spec L4502-4652, detail 1)",
                  aw.word->column);
    }
    rotation.centre[k] = to_physical(axis, scaled_axis_word(axis, *aw.word));
  }
  rotation_ = rotation;
  rotated_ = true;
  modal_.codes[17] = 68.1;
  rebuild_frame();
  return true;
}

bool ProgramRun::run_mirror(GFunction f, int column) {
  const bool on = f == GFunction::mirror_on;
  if (contour_.active()) {
    return contour_forbids(on ? "G51.1" : "G50.1", column);
  }
  if (on && modal_.turret_mirror) {
    return fail(alarm::kFrameRestriction,
                "G51.1 is not allowed under the facing turret's mirror G68: cancel it first (G69)",
                column);
  }
  bool any = false;
  const bool ok = for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const auto i = static_cast<std::size_t>(axis);
    any = true;
    if (!on) {
      program_mirror_.mirrored[i] = false;  // the value of a G50.1 word is not used
      return true;
    }
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  "G51.1 takes the mirror position as an absolute coordinate", w.column);
    }
    program_mirror_.mirrored[i] = true;
    program_mirror_.centre(axis) = to_physical(axis, scaled_axis_word(axis, w));
    return true;
  });
  if (!ok) {
    return false;
  }
  if (!any) {
    if (on) {
      return fail(alarm::kCycleWordMissing, "G51.1 needs the axis to mirror and its position (X0)",
                  column);
    }
    program_mirror_ = transform::AxisMirror{};  // G50.1 alone ends every mirror
  }
  modal_.codes[22] = program_mirror_.active() ? 51.1 : 50.1;
  rebuild_frame();
  return true;
}

void ProgramRun::rebuild_frame() {
  map_to_machine();
  const transform::AxisPoint at = frame_.to_machine(transform::to_point(machine_));
  transform::TransformChain frame;
  if (frame_active()) {
    // machine_ = program point + offsets: off with the offsets, turn, mirror, on with them.
    // The mirror comes last, so that it mirrors whatever a mirrored subprogram turns.
    transform::AxisShift to_work;
    transform::AxisShift from_work;
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      const int axis = static_cast<int>(i);
      const double t = offset_sum(axis) + tool_offset(axis);
      to_work.offset(axis) = -t;
      from_work.offset(axis) = t;
    }
    frame.then(to_work);
    if (rotated_) {
      frame.then(rotation_);
    }
    frame.then(program_mirror_).then(from_work);
  }
  frame_ = frame;
  machine_ = transform::to_vector(frame_.to_program(at));
}

void ProgramRun::map_to_machine() {
  framed_commands_ = std::min(framed_commands_, out_.size());
  if (!frame_.identity()) {
    const std::array<int, 2> plane = plane_axis_indices();
    for (std::size_t k = framed_commands_; k < out_.size(); ++k) {
      Command& c = out_[k];
      const transform::AxisPoint at = transform::to_point(c.to);
      if (c.op == Op::arc || c.thread_arc) {
        const int a = c.center_axes[0];
        const int b = c.center_axes[1];
        transform::AxisPoint centre = at;
        centre(a) = c.center[0];
        centre(b) = c.center[1];
        centre = frame_.to_machine(centre);
        c.center = {centre(a), centre(b)};
        if (frame_.reverses(a, b)) {
          c.direction = c.direction == ArcDirection::cw ? ArcDirection::ccw : ArcDirection::cw;
        }
      }
      c.to = transform::to_vector(frame_.to_machine(at));
      // A mirrored path keeps the tool on the same side of the part: the side swaps.
      if (c.compensation != Command::Compensation::off && plane[0] >= 0 && plane[1] >= 0 &&
          frame_.reverses(plane[0], plane[1])) {
        c.compensation = c.compensation == Command::Compensation::left
                             ? Command::Compensation::right
                             : Command::Compensation::left;
      }
    }
  }
  framed_commands_ = out_.size();
}

}  // namespace mcnc::interp
