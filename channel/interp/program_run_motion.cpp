// Coordinates and motion: axis words to machine positions (spec dafeng §1.2, §1.4-§1.6, §2.9),
// G00/G01/G02/G03, G28/G30, G50/G92, G50.3, G52.
#include "channel/interp/axis_address.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::interp {

namespace {

constexpr double kMaxCoordinate = 999999.999;  // spec dafeng §1.3

std::string format_mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

}  // namespace

double ProgramRun::to_physical(int axis, double programmed, bool mirror) const {
  if (cylinder_axis(axis)) {
    // Degrees on the cylinder: the length around it (spec L612-710, detail 10).
    return transform::CylindricalInterpolation(cylinder_radius_).to_length(programmed);
  }
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  double v = programmed;
  if ((!a.rotary || polar_virtual(axis)) && !modal_.metric) {
    v *= 25.4;
  }
  if (diameter_[static_cast<std::size_t>(axis)]) {
    v /= 2.0;
  }
  if (mirror && modal_.turret_mirror && a.name == 'X') {
    v = -v;  // G68: the facing turret's X is mirrored about X0 (spec L4460-4501)
  }
  return v;
}

double ProgramRun::to_programmed(int axis, double physical, bool mirror) const {
  if (cylinder_axis(axis)) {
    return transform::CylindricalInterpolation(cylinder_radius_).to_degrees(physical);
  }
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  double v = physical;
  if (mirror && modal_.turret_mirror && a.name == 'X') {
    v = -v;
  }
  if (diameter_[static_cast<std::size_t>(axis)]) {
    v *= 2.0;
  }
  if ((!a.rotary || polar_virtual(axis)) && !modal_.metric) {
    v /= 25.4;
  }
  return v;
}

double ProgramRun::data_to_physical(int axis, double value) const {
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  double v = value;
  if (!a.rotary && !modal_.metric) {
    v *= 25.4;
  }
  return a.diameter ? v / 2.0 : v;
}

double ProgramRun::physical_to_data(int axis, double physical) const {
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  const double v = a.diameter ? physical * 2.0 : physical;
  return !a.rotary && !modal_.metric ? v / 25.4 : v;
}

bool ProgramRun::run_radius_switch(int column) {
  bool any = false;
  std::vector<int> axis_columns;
  const bool ok = for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    axis_columns.push_back(w.column);
    const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
    if (incremental) {
      return fail(alarm::kWordNotAllowed,
                  std::string("G10.9 names the axis by its own address: ") + a.name +
                      " instead of " + w.address.first,
                  w.column);
    }
    if (a.rotary) {
      return fail(
          alarm::kBadWordValue,
          std::string("G10.9: ") + a.name + " is a rotary axis, neither a diameter nor a radius",
          w.column);
    }
    if (w.value != 0.0 && w.value != 1.0) {
      return fail(alarm::kBadWordValue,
                  std::string("G10.9 ") + a.name + " takes 0 (radius) or 1 (diameter)", w.column);
    }
    diameter_[static_cast<std::size_t>(axis)] = w.value == 1.0;
    any = true;
    return true;
  });
  if (!ok) {
    return false;
  }
  for (const BlockWord& w : words_) {
    const bool axis_word =
        std::find(axis_columns.begin(), axis_columns.end(), w.column) != axis_columns.end();
    if (w.column != column && !axis_word && !w.address.is('N')) {
      return fail(alarm::kMustBeAlone,
                  "G10.9 stands alone in its block with the axes it switches (spec L3959-4023)",
                  w.column);
    }
  }
  if (!any) {
    return fail(alarm::kBadWordValue, "G10.9 needs an axis with 0 (radius) or 1 (diameter)",
                column);
  }
  return true;
}

double ProgramRun::offset_sum(int axis) const {
  return coordinates_.sum(axis);
}

double ProgramRun::tool_offset(int axis) const {
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  return config_.dialect == Dialect::fanuc_mill ? tools_.mill_length(a.name)
                                                : tools_.lathe_offset(a.name, a.diameter);
}

void ProgramRun::apply_tool_offset(int offset) {
  // No motion: the displayed position changes and the next move goes to the offset position
  // (spec dafeng L3574-3619). Incremental moves are measured from the displayed position.
  tools_.offset = offset;
  if (frame_active()) {
    rebuild_frame();
  }
}

double ProgramRun::program_position(int axis) const {
  const auto i = static_cast<std::size_t>(axis);
  return to_programmed(axis, machine_[i] - offset_sum(axis) - tool_offset(axis));
}

ProgramRun::AxisWords ProgramRun::axis_words(int axis) {
  const AxisConfig& a = config_.axes[static_cast<std::size_t>(axis)];
  AxisWords out;
  BlockWord* abs = word(a.name);
  BlockWord* inc = nullptr;
  if (config_.system == GCodeSystem::a) {
    const AxisAddress address = lathe_axis_address(a.name, a.diameter);
    inc = address.incremental != 0 ? word(address.incremental) : nullptr;
  }
  BlockWord* extended = word('U', a.name);  // UX, UZ, UA ... (spec dafeng §1.6)
  if (extended != nullptr && inc != nullptr) {
    fail(alarm::kAbsoluteAndIncremental,
         std::string(1, inc->address.first) + " and U" + a.name + " in one block",
         extended->column);
    out.error = true;
    return out;
  }
  inc = inc != nullptr ? inc : extended;
  if (abs != nullptr && inc != nullptr) {
    fail(alarm::kAbsoluteAndIncremental,
         "absolute " + std::string(1, a.name) + " and its incremental address in one block",
         inc->column);
    out.error = true;
    return out;
  }
  if (abs != nullptr && config_.system == GCodeSystem::b && modal_.incremental) {
    out.word = abs;
    out.incremental = true;  // system B, G91
    return out;
  }
  out.word = abs != nullptr ? abs : inc;
  out.incremental = abs == nullptr && inc != nullptr;
  return out;
}

bool ProgramRun::read_axis_targets(AxisVector& target, std::array<bool, kMaxChannelAxes>& given,
                                   bool machine_coordinates) {
  target = machine_;
  given.fill(false);
  const bool ok = for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const auto i = static_cast<std::size_t>(axis);
    const int spindle = config_.axes[i].spindle;
    if (spindle > 0 && spindle < 10 &&
        !spindles_.position_control[static_cast<std::size_t>(spindle)]) {
      return fail(alarm::kSpindleControl,
                  std::string(1, config_.axes[i].name) + " is spindle " + std::to_string(spindle) +
                      " under speed control: " + position_code(spindle, true) +
                      " switches it to position control first",
                  w.column);
    }
    if (released_[i]) {
      return fail(alarm::kReleasedAxis,
                  std::string(1, config_.axes[i].name) +
                      " was released to another channel by G140; acquire it (G141) or restore "
                      "(G142) first",
                  w.column);
    }
    given[i] = true;
    const double v = scaled_axis_word(axis, w);
    if (std::fabs(v) > kMaxCoordinate) {
      return fail(alarm::kValueOutOfRange,
                  std::string(1, w.address.first) + " beyond +-999999.999 (spec L116)", w.column);
    }
    if (incremental) {
      if (machine_coordinates) {
        return fail(alarm::kWordNotAllowed, "G53 takes absolute machine positions only", w.column);
      }
      if (program_mirror_.mirrored[i]) {
        return fail(alarm::kFrameRestriction,
                    std::string("a mirrored axis is programmed in absolute coordinates under "
                                "G51.1 (spec L4233-4278): ") +
                        config_.axes[i].name + " instead of " + w.address.first,
                    w.column);
      }
      target[i] = machine_[i] + to_physical(axis, v);
    } else if (machine_coordinates) {
      target[i] = data_to_physical(axis, v);  // G53 is not switched by G10.9 (L3959-4023)
    } else {
      target[i] = to_physical(axis, v) + offset_sum(axis) + tool_offset(axis);
    }
    return true;
  });
  if (ok && polar_coords_ && !machine_coordinates && !polar_coordinate_target(target, given)) {
    return false;
  }
  if (ok && machine_coordinates && (frame_active() || inclined_on())) {
    // G53 is neither turned nor mirrored (spec L4387-4421) nor inclined (L4653-4767): the
    // named axes go to machine positions, the others stay where they are on the machine.
    AxisVector on_machine = machine();
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      on_machine[i] = given[i] ? target[i] : on_machine[i];
    }
    target =
        transform::to_vector(frame_.to_program(transform::to_point(from_inclined(on_machine))));
  }
  return ok;
}

bool ProgramRun::check_feed(int column) {
  if (modal_.feed <= 0.0) {
    return fail(alarm::kFeedMissing, "cutting move without feed: program F greater than 0", column);
  }
  return true;
}

bool ProgramRun::run_motion(GFunction motion, bool machine_coordinates, int column) {
  switch (motion) {
    case GFunction::thread:
    case GFunction::thread_interpolated:
    case GFunction::thread_arc_cw:
    case GFunction::thread_arc_ccw:
    case GFunction::thread_variable:
      return run_thread(motion, column);
    case GFunction::flexible_tap:
      return run_flexible_tap(column);
    case GFunction::turning_cycle:
    case GFunction::thread_cycle:
    case GFunction::thread_cycle_interpolated:
    case GFunction::facing_cycle:
      return run_single_cycle(motion, block_motion_code_, column);
    default:
      break;
  }
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, machine_coordinates)) {
    return false;
  }
  const bool three_point =
      motion == GFunction::arc_three_point || motion == GFunction::arc_three_point_absolute;
  const bool cutting = motion == GFunction::linear || motion == GFunction::arc_cw ||
                       motion == GFunction::arc_ccw || three_point;
  if (interpolation_mode() && !cutting) {
    return fail(alarm::kInterpolationModeRestriction,
                "polar and cylindrical interpolation move with G01, G02 or G03 only (spec "
                "L612-849)",
                column);
  }
  if (cutting && !machine_coordinates && !take_corner_request()) {
    return false;
  }
  if (angle_start_.active && motion != GFunction::linear) {
    return fail(alarm::kAngleProgramming,
                "an angle-only G01 (line " + std::to_string(angle_start_.line) +
                    ") must be followed by a G01 with its end point and angle",
                column);
  }
  if ((motion == GFunction::linear ||
       (motion == GFunction::rapid && config_.dialect == Dialect::gsk)) &&
      !machine_coordinates) {
    bool deferred = false;
    if (!apply_line_angle(target, given, deferred, column)) {
      return false;
    }
    if (deferred) {
      return true;
    }
  }
  bool any = false;
  int first_column = column;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    any = any || given[i];
  }
  for (const BlockWord& w : words_) {
    if (w.used && first_column == 0 && w.address.second == 0) {
      first_column = w.column;
    }
  }
  if (any && contour_.capturing()) {
    // Type II of G71/G72 is told by the plane axes of the contour's first block.
    const std::array<int, 2> plane = plane_axis_indices();
    const auto gives = [&](int axis) { return axis >= 0 && given[static_cast<std::size_t>(axis)]; };
    contour_.note_motion(gives(plane[0]), gives(plane[1]));
  }
  if (motion == GFunction::arc_cw || motion == GFunction::arc_ccw) {
    const bool arc_words = word('R') != nullptr || word('I') != nullptr || word('J') != nullptr ||
                           word('K') != nullptr;
    if (polar_coords_ && word('R') == nullptr && arc_words) {
      return fail(alarm::kInterpolationModeRestriction,
                  "under G16 an arc is given by its radius R, not by I/J (its centre in polar "
                  "coordinates would be ambiguous)",
                  column != 0 ? column : first_column);
    }
    if (!any && !arc_words) {
      return true;
    }
    return run_arc(motion, target, column != 0 ? column : first_column);
  }
  if (three_point) {
    return run_three_point_arc(motion, target, any, column != 0 ? column : first_column);
  }
  if (!any) {
    return true;
  }
  if (motion == GFunction::linear) {
    BlockWord* f = word('F');
    if (!check_feed(f != nullptr ? f->column : first_column)) {
      return false;
    }
  }
  Command& c = emit(motion == GFunction::linear ? Op::linear : Op::rapid);
  c.to = target;
  c.feed = modal_.feed;
  c.feed_mode = modal_.feed_mode;
  c.exact_stop = motion == GFunction::linear && (block_exact_stop_ || modal_.exact_stop);
  if (motion == GFunction::linear) {
    mark_corner(c);
  }
  machine_ = target;
  block_moved_ = true;
  return true;
}

std::array<int, 2> ProgramRun::plane_axis_indices() const {
  if (polar_) {
    return polar_axes_;  // the polar plane (spec L711-849: params 5530/5531, not G17-G19)
  }
  const char first = modal_.plane == Plane::xy ? 'X' : modal_.plane == Plane::zx ? 'Z' : 'Y';
  const char second = modal_.plane == Plane::xy ? 'Y' : modal_.plane == Plane::zx ? 'X' : 'Z';
  std::array<int, 2> axes{-1, -1};
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    axes[0] = config_.axes[i].name == first ? static_cast<int>(i) : axes[0];
    axes[1] = config_.axes[i].name == second ? static_cast<int>(i) : axes[1];
  }
  if (cylindrical_) {
    // The rotary axis takes the place of the linear axis it is parallel to (param 0016).
    axes[0] = first == config_.cylindrical_parallel ? cylinder_axis_ : axes[0];
    axes[1] = second == config_.cylindrical_parallel ? cylinder_axis_ : axes[1];
  }
  return axes;
}

bool ProgramRun::require_plane_axes(std::array<int, 2>& axes, int column) {
  axes = plane_axis_indices();
  if (axes[0] >= 0 && axes[1] >= 0) {
    return true;
  }
  const char* name = modal_.plane == Plane::xy ? "XY" : modal_.plane == Plane::zx ? "ZX" : "YZ";
  return fail(alarm::kNoPlaneAxis,
              std::string("this block works in the ") + name + " plane (G17/G18/G19), whose axes " +
                  name[0] + " and " + name[1] + " this channel lacks",
              column);
}

bool ProgramRun::arc_center(bool ccw, const std::array<int, 2>& axes, const AxisVector& target,
                            std::array<double, 2>& center, int column) {
  // The centre words of the plane: I/J (G17), K/I (G18), J/K (G19), first axis first.
  const Plane words = polar_ ? Plane::xy : modal_.plane;  // the polar plane takes I and J
  const char ca = words == Plane::xy ? 'I' : words == Plane::zx ? 'K' : 'J';
  const char cb = words == Plane::xy ? 'J' : words == Plane::zx ? 'I' : 'K';
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  const double sa = machine_[a];
  const double sb = machine_[b];
  const double ea = target[a];
  const double eb = target[b];
  const double inch = modal_.metric ? 1.0 : 25.4;
  BlockWord* r = word('R');
  BlockWord* wa = word(ca);
  BlockWord* wb = word(cb);
  const double tol = config_.arc_tolerance;
  if (r != nullptr) {
    r->used = true;
    if (wa != nullptr) {
      wa->used = true;  // R wins over I/K (gsk D2-9)
    }
    if (wb != nullptr) {
      wb->used = true;
    }
    const double radius = scaled(*r, true) * inch;
    const double dx = ea - sa;
    const double dy = eb - sb;
    const double d = std::hypot(dx, dy);
    if (d < 1e-9) {
      return fail(alarm::kArcFullCircleWithR,
                  "a full circle cannot be programmed with R; give the centre with I/K", r->column);
    }
    double rr = std::fabs(radius);
    const double half = d / 2.0;
    if (rr < half) {
      if (half - rr > tol) {
        return fail(alarm::kArcGeometry,
                    "arc radius R" + format_mm(std::fabs(radius)) +
                        " is smaller than half the distance to the end point (" + format_mm(half) +
                        ")",
                    r->column);
      }
      rr = half;
    }
    const double h = std::sqrt(std::max(0.0, rr * rr - half * half));
    // The centre of the shorter arc lies left of the chord for CCW, right for CW; R < 0 takes
    // the longer arc (spec dafeng L475-560).
    double side = ccw ? 1.0 : -1.0;
    if (radius < 0.0) {
      side = -side;
    }
    center = {sa + dx / 2.0 + side * h * (-dy / d), sb + dy / 2.0 + side * h * (dx / d)};
    return true;
  }
  if (wa == nullptr && wb == nullptr) {
    return fail(alarm::kArcGeometry,
                std::string("arc needs R or its centre (") + ca + "/" + cb + ")", column);
  }
  auto offset = [&](BlockWord* w, std::size_t axis) {
    if (w == nullptr) {
      return 0.0;
    }
    w->used = true;
    double v = scaled(*w, true) * inch;  // I/J/K are radius values (spec L119-167)
    if (modal_.turret_mirror && config_.axes[axis].name == 'X') {
      v = -v;
    }
    return v;
  };
  center = {sa + offset(wa, a), sb + offset(wb, b)};
  const double r0 = std::hypot(sa - center[0], sb - center[1]);
  const double r1 = std::hypot(ea - center[0], eb - center[1]);
  if (r0 < 1e-9) {
    return fail(alarm::kArcGeometry, "arc centre at the start point (radius 0)", column);
  }
  if (config_.arc_check && std::fabs(r0 - r1) > tol) {
    return fail(alarm::kArcGeometry,
                "arc end point is not on the circle: radius " + format_mm(r0) + " at the start, " +
                    format_mm(r1) + " at the end (tolerance " + format_mm(tol) + ")",
                column);
  }
  return true;
}

bool ProgramRun::run_arc(GFunction motion, const AxisVector& target, int column) {
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  ArcDirection dir = motion == GFunction::arc_cw ? ArcDirection::cw : ArcDirection::ccw;
  if (modal_.turret_mirror && (config_.axes[a].name == 'X' || config_.axes[b].name == 'X')) {
    dir = dir == ArcDirection::cw ? ArcDirection::ccw : ArcDirection::cw;  // mirrored X
  }
  if (word('R') != nullptr && config_.dialect == Dialect::gsk &&
      std::hypot(target[a] - machine_[a], target[b] - machine_[b]) < 1e-9) {
    for (const char c : {'R', 'I', 'J', 'K'}) {
      if (BlockWord* w = word(c)) {
        w->used = true;
      }
    }
    return true;  // GSK: R with no end point is a 0-degree arc, no motion (gsk D2-9)
  }
  std::array<double, 2> center{};
  if (!arc_center(dir == ArcDirection::ccw, axes, target, center, column)) {
    return false;
  }
  int turns = 0;
  BlockWord* l = config_.dialect == Dialect::gsk ? nullptr : word('L');  // GSK L: a chamfer
  if (l != nullptr) {
    l->used = true;
    const double v = l->value;
    if (v < 1.0 || std::fabs(v - std::round(v)) > 1e-9) {
      return fail(alarm::kBadWordValue, "L (helical turns) must be a whole number >= 1", l->column);
    }
    turns = static_cast<int>(std::lround(v)) - 1;
  }
  return emit_arc(target, axes, dir, center, turns, column);
}

bool ProgramRun::emit_arc(const AxisVector& target, const std::array<int, 2>& axes,
                          ArcDirection dir, const std::array<double, 2>& center, int turns,
                          int column) {
  BlockWord* f = word('F');
  if (!check_feed(f != nullptr ? f->column : column)) {
    return false;
  }
  Command& c = emit(Op::arc);
  c.to = target;
  c.plane = modal_.plane;
  c.direction = dir;
  c.center_axes = axes;
  c.center = center;
  c.turns = turns;
  c.feed = modal_.feed;
  c.feed_mode = modal_.feed_mode;
  c.exact_stop = block_exact_stop_ || modal_.exact_stop;
  mark_corner(c);
  machine_ = target;
  block_moved_ = true;
  return true;
}

bool ProgramRun::run_three_point_arc(GFunction motion, const AxisVector& target, bool any,
                                     int column) {
  const bool absolute = motion == GFunction::arc_three_point_absolute;
  const std::string code = absolute ? "G05.1" : "G05";
  // The middle point's words are the plane's centre words: K/I in G18 (gsk A.6.4 rule 4).
  const char ca = modal_.plane == Plane::xy ? 'I' : modal_.plane == Plane::zx ? 'K' : 'J';
  const char cb = modal_.plane == Plane::xy ? 'J' : modal_.plane == Plane::zx ? 'I' : 'K';
  BlockWord* wa = word(ca);
  BlockWord* wb = word(cb);
  if (!any && wa == nullptr && wb == nullptr) {
    return true;  // a block of the mode without a move (F only)
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  if (wa == nullptr && wb == nullptr) {
    return fail(alarm::kArcGeometry,
                code + " needs its middle point: " + ca + " and/or " + cb + " (gsk A.6.4 rule 3)",
                column);
  }
  // An omitted word leaves the middle point on the start's coordinate: G05's increment 0, and
  // for G05.1 the start's position as an omitted axis word keeps it (decision 56).
  AxisVector middle = machine_;
  const double inch = modal_.metric ? 1.0 : 25.4;
  const std::array<BlockWord*, 2> mw{wa, wb};
  for (std::size_t k = 0; k < 2; ++k) {
    BlockWord* w = mw[k];
    if (w == nullptr) {
      continue;
    }
    w->used = true;
    const int axis = axes[k];
    const auto i = static_cast<std::size_t>(axis);
    if (absolute) {
      // In the axis's programming unit (X a diameter), as the end point.
      middle[i] =
          to_physical(axis, scaled_axis_word(axis, *w)) + offset_sum(axis) + tool_offset(axis);
      continue;
    }
    double v = scaled(*w, true) * inch;  // a radius value, as G02/G03's I (gsk A.6.4)
    if (modal_.turret_mirror && config_.axes[i].name == 'X') {
      v = -v;
    }
    middle[i] = machine_[i] + v;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  const path::Point2 start{machine_[a], machine_[b]};
  const path::Point2 end{target[a], target[b]};
  if (path::same_point(start, end)) {
    return fail(alarm::kArcGeometry,
                code + " cannot cut a full circle: its end point is its start (gsk A.6.4 rule 5)",
                column);
  }
  const std::optional<path::ThreePointArc> arc =
      path::arc_through(start, {middle[a], middle[b]}, end);
  if (!arc) {
    return fail(alarm::kArcGeometry,
                code + ": the start, middle and end points lie on one line (gsk A.6.4 rule 2)",
                column);
  }
  return emit_arc(target, axes, arc->ccw ? ArcDirection::ccw : ArcDirection::cw,
                  {arc->center.a, arc->center.b}, 0, column);
}

bool ProgramRun::run_reference_return(GFunction f, int column) {
  int point = 1;
  if (f == GFunction::reference_2_4) {
    point = 2;
    if (BlockWord* p = word('P')) {
      p->used = true;
      if (p->value != 2.0 && p->value != 3.0 && p->value != 4.0) {
        return fail(alarm::kBadWordValue, "G30 P must be 2, 3 or 4", p->column);
      }
      point = static_cast<int>(p->value);
    }
  }
  AxisVector via{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(via, given, false)) {
    return false;
  }
  bool any = false;
  // The reference points are machine positions, not inclined (L4653-4767): the axes not named
  // stay where they are on the machine.
  AxisVector home = to_inclined(via);
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (given[i]) {
      any = true;
      home[i] = config_.axes[i].reference[static_cast<std::size_t>(point - 1)];
    }
  }
  home = from_inclined(home);
  if (!any) {
    (void)column;
    return true;
  }
  emit(Op::rapid).to = via;  // the intermediate point first
  emit(Op::rapid).to = home;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (given[i]) {  // G29's way back, per axis: an axis not named keeps its earlier point
      reference_via_[i] = via[i];
      reference_via_given_[i] = true;
    }
  }
  machine_ = home;
  block_moved_ = true;
  if (f == GFunction::reference_return) {
    // Homing clears the G50 shift and the G52 local systems of the homed axes (L4083-4129).
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      if (given[i]) {
        coordinates_.clear_shift_and_local(static_cast<int>(i));
      }
    }
  }
  return true;
}

bool ProgramRun::run_coordinate_set(int /*column*/) {
  return for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const double v = to_physical(axis, scaled_axis_word(axis, w));
    if (incremental) {
      coordinates_.shift_by(axis, v);  // G50 U: the position reads U more (L4219-4232)
      return true;
    }
    // The position before the tool offset reads v; G52 of this axis ends in every system.
    coordinates_.set_position(axis, machine_[static_cast<std::size_t>(axis)], v);
    return true;
  });
}

bool ProgramRun::run_local_system(int /*column*/) {
  return for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    const double v = to_physical(axis, scaled_axis_word(axis, w));
    // U/W: relative to the current position in the work system (spec L4302-4386).
    if (incremental) {
      coordinates_.set_local_from(axis, machine_[static_cast<std::size_t>(axis)], tool_offset(axis),
                                  v);
    } else {
      coordinates_.set_local(axis, v);
    }
    return true;
  });
}

bool ProgramRun::run_restore_origin(int /*column*/) {
  return for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
    if (incremental || w.value != 0.0) {
      // G50.3 in system A, G92.1 in system B: name the code the programmer wrote.
      return fail(alarm::kBadWordValue,
                  config_.system == GCodeSystem::a
                      ? "G50.3 restores the origin of an axis written with 0, e.g. X0"
                      : "G92.1 restores the origin of an axis written with 0, e.g. X0",
                  w.column);
    }
    coordinates_.clear_shift_and_local(axis);
    return true;
  });
}

}  // namespace mcnc::interp
