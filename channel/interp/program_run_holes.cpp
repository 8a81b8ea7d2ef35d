// The hole cycles G83/G87 (drilling), G84/G88 (tapping) and G85/G89 (boring) of spec dafeng
// §2.5 L1844-2198 and gsk A.6.34-A.6.35: a modal group 10 cycle, repeated by every block that
// gives positioning words until G80 or a group 01 code.
#include "channel/interp/cycles/hole_cycles.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

namespace {

bool side_cycle(GFunction f) {
  return f == GFunction::drill_side || f == GFunction::tap_side || f == GFunction::bore_side;
}

cycles::HoleKind hole_kind(GFunction f) {
  switch (f) {
    case GFunction::tap_face:
    case GFunction::tap_side:
      return cycles::HoleKind::tap;
    case GFunction::bore_face:
    case GFunction::bore_side:
      return cycles::HoleKind::bore;
    default:
      return cycles::HoleKind::drill;
  }
}

}  // namespace

bool ProgramRun::hole_cycle_block(bool group10_in_block, bool motion_code_in_block) const {
  if (group10_in_block) {
    return true;
  }
  return hole_.function != GFunction::unknown && !motion_code_in_block;
}

bool ProgramRun::take_hole_words(int column) {
  const bool gsk = config_.dialect == Dialect::gsk;
  HoleMode& h = hole_;
  const bool tap = hole_kind(h.function) == cycles::HoleKind::tap;
  if (BlockWord* m = word('M')) {
    // Mxx: the clamp before each hole, Mxx+1 the unclamp after it (spec L1870-1873).
    std::int64_t code = 0;
    if (m->value < 0.0 || m->value > 9998.0 || m->value != std::floor(m->value)) {
      return fail(alarm::kBadWordValue, "the clamp code M of a hole cycle must be 0-9998",
                  m->column);
    }
    code = static_cast<std::int64_t>(m->value);
    m->used = true;
    h.clamp = static_cast<int>(code);
  }
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (gsk) {
      h.retract = std::fabs(length_of(*r));  // gsk: the back-off after each peck (gsk D2-30)
    } else {
      h.has_r = true;  // Dafeng: the R point, an absolute coordinate of the drilling axis
      std::array<int, 2> axes{};
      if (!require_plane_axes(axes, r->column)) {
        return false;  // a plane (G17/G19) whose axes this channel lacks: no drilling axis
      }
      const int drill = side_cycle(h.function) ? axes[1] : axes[0];
      h.r_level = to_physical(drill, scaled(*r, true)) + offset_sum(drill) + tool_offset(drill);
    }
  }
  if (BlockWord* q = word('Q')) {
    q->used = true;
    h.peck = gsk ? std::fabs(cycle_amount(*q)) : std::fabs(scaled(*q, true));
  }
  if (BlockWord* p = word('P')) {
    p->used = true;
    if (p->value < 0.0) {
      return fail(alarm::kNegativeDwell, "the dwell P (ms) at the hole bottom must be >= 0",
                  p->column);
    }
    h.dwell_s = p->value / 1000.0;
  }
  if (BlockWord* j = word('J')) {
    if (gsk && !tap) {
      j->used = true;
      if (j->value != 0.0 && j->value != 1.0) {
        return fail(alarm::kCycleValue, "J must be 0 (high-speed peck) or 1 (deep hole)",
                    j->column);
      }
      h.peck_type = static_cast<int>(j->value);
    } else if (tap) {
      return fail(alarm::kNotInThisVersion,
                  "J (retract speed of tapping) needs the spindle control of a later release",
                  j->column);
    }
  }
  if (tap) {
    BlockWord* f = word('F');
    BlockWord* i = word('I');
    if (f != nullptr || i != nullptr) {
      // The tapping lead: F in mm (negative: left hand, gsk A.6.35) or I threads per inch.
      if (f != nullptr && i != nullptr) {
        return fail(alarm::kWordNotAllowed, "tapping takes F (lead) or I (threads per inch)",
                    i->column);
      }
      if (f != nullptr) {
        f->used = true;
        h.lead = f->value * (metric_ ? 1.0 : 25.4);
      } else {
        i->used = true;
        if (i->value == 0.0) {
          return fail(alarm::kThreadLead, "threads per inch I must not be 0", i->column);
        }
        h.lead = 25.4 / i->value;
      }
    }
    if (h.lead == 0.0) {
      return fail(alarm::kThreadLead, "tapping needs the lead F (mm) or I (threads per inch)",
                  column);
    }
  }
  if (BlockWord* k = word('K')) {
    k->used = true;
    if (k->value < 0.0 || k->value > 9999.0 || k->value != std::floor(k->value)) {
      return fail(alarm::kBadWordValue, "K (number of holes) must be a whole number 0-9999",
                  k->column);
    }
    h.repeat = static_cast<int>(k->value);
  } else {
    h.repeat = 1;  // K is not modal
  }
  return true;
}

bool ProgramRun::run_hole_cycle(int column) {
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  HoleMode& h = hole_;
  const auto drill = static_cast<std::size_t>(side_cycle(h.function) ? axes[1] : axes[0]);
  const cycles::HoleKind kind = hole_kind(h.function);
  if (kind != cycles::HoleKind::tap) {
    BlockWord* fw = word('F');
    if (!check_feed(fw != nullptr ? fw->column : column)) {
      return false;
    }
  }
  bool first = true;
  // Reset on every way out: the alarms below return early, and an alarm ends the run anyway.
  struct CycleOutput {
    bool& flag;
    ~CycleOutput() { flag = false; }
  } cycle_output{cycle_output_ = true};
  for (int k = 0; k < h.repeat; ++k) {
    AxisVector target{};
    std::array<bool, kMaxChannelAxes> given{};
    if (!read_axis_targets(target, given, false)) {
      return false;
    }
    if (first && given[drill]) {
      h.bottom = target[drill];
      h.has_bottom = true;
    }
    first = false;
    if (!h.has_bottom) {
      return fail(
          alarm::kCycleWordMissing,
          "the hole cycle needs the hole bottom (" + std::string(1, config_.axes[drill].name) + ")",
          column);
    }
    // Position on the hole at rapid, the drilling axis staying at the initial level.
    target[drill] = machine_[drill];
    if (target != machine_) {
      emit(Op::rapid).to = target;
      machine_ = target;
      block_moved_ = true;
    }
    cycles::HoleCycle c;
    c.kind = kind;
    c.initial = machine_[drill];
    c.r_level = h.has_r ? h.r_level : machine_[drill];
    c.bottom = h.bottom;
    c.peck = h.peck;
    c.dwell_s = h.dwell_s;
    c.feed = feed_;
    c.lead = h.lead;
    c.clamp_code = h.clamp;
    c.return_to_initial = config_.system == GCodeSystem::b && modal_codes_[11] == 98.0;
    const CycleDefaults& d = config_.cycles;
    const int variant = h.code10 % 10;  // G83.5 -> 5
    if (kind == cycles::HoleKind::tap) {
      c.retract = d.tap_retract;
      c.peck_mode = h.peck <= 0.0      ? cycles::PeckMode::none
                    : variant == 5     ? cycles::PeckMode::high_speed
                    : variant == 6     ? cycles::PeckMode::deep
                    : d.tap_high_speed ? cycles::PeckMode::high_speed
                                       : cycles::PeckMode::deep;
    } else if (kind == cycles::HoleKind::drill) {
      c.retract = h.retract >= 0.0 ? h.retract : d.drill_retract;
      c.clearance = h.retract >= 0.0 ? h.retract : d.drill_clearance;
      c.full_retract_depth = d.drill_full_retract;
      const bool high_speed = h.peck_type >= 0 ? h.peck_type == 0 : d.drill_high_speed;
      c.peck_mode = h.peck <= 0.0  ? cycles::PeckMode::none
                    : variant == 5 ? cycles::PeckMode::high_speed
                    : variant == 6 ? cycles::PeckMode::deep
                    : variant == 7 ? cycles::PeckMode::high_speed_deep
                    : high_speed   ? cycles::PeckMode::high_speed
                                   : cycles::PeckMode::deep;
    }
    std::vector<cycles::HoleStep> steps;
    if (const path::PathResult e = cycles::expand_hole(c, steps)) {
      return fail_path(*e, column);
    }
    const SpindleDirection turning =
        spindle_direction_[static_cast<std::size_t>(reference_spindle_)];
    for (const cycles::HoleStep& s : steps) {
      AxisVector to = machine_;
      to[drill] = s.to;
      switch (s.kind) {
        case cycles::HoleStep::Kind::rapid:
          emit(Op::rapid).to = to;
          machine_ = to;
          break;
        case cycles::HoleStep::Kind::feed: {
          Command& cmd = emit(Op::linear);
          cmd.to = to;
          cmd.feed = feed_;
          cmd.feed_mode = feed_mode_;
          machine_ = to;
          break;
        }
        case cycles::HoleStep::Kind::tap: {
          Command& cmd = emit(Op::thread);
          cmd.to = to;
          cmd.lead = std::fabs(c.lead);
          cmd.spindle = reference_spindle_;
          machine_ = to;
          break;
        }
        case cycles::HoleStep::Kind::dwell:
          emit(Op::dwell).seconds = s.seconds;
          break;
        case cycles::HoleStep::Kind::aux:
          emit(Op::aux).code = s.code;
          break;
        case cycles::HoleStep::Kind::reverse:
        case cycles::HoleStep::Kind::restore: {
          // Follow tapping (M28): the PLC reverses a turning spindle for the way out; a
          // position-controlled spindle (M29, stopped) follows the thread move itself.
          if (turning != SpindleDirection::cw && turning != SpindleDirection::ccw) {
            break;
          }
          const bool reverse = s.kind == cycles::HoleStep::Kind::reverse;
          Command& cmd = emit(Op::spindle);
          cmd.spindle = reference_spindle_;
          cmd.rpm = rpm_[static_cast<std::size_t>(reference_spindle_)];
          cmd.spindle_direction = !reverse                          ? turning
                                  : turning == SpindleDirection::cw ? SpindleDirection::ccw
                                                                    : SpindleDirection::cw;
          break;
        }
      }
    }
    block_moved_ = true;
  }
  return true;
}

}  // namespace mcnc::interp
