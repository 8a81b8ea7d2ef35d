// The hole cycles G83/G87 (drilling), G84/G88 (tapping) and G85/G89 (boring) of spec dafeng
// §2.5 L1844-2198 and gsk A.6.34-A.6.35, and the mill's G73-G89 (gsk B.1): a modal cycle
// (the lathe's group 10, the mill's 09), repeated by every block that gives positioning words
// until G80 or a group 01 code.
#include "channel/interp/cycles/hole_cycles.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
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
    case GFunction::mill_tap:
    case GFunction::mill_tap_left:
      return cycles::HoleKind::tap;
    case GFunction::bore_face:
    case GFunction::bore_side:
    case GFunction::mill_bore:
    case GFunction::mill_bore_dwell:
      return cycles::HoleKind::bore;
    case GFunction::mill_bore_stop:
      return cycles::HoleKind::bore_stop;
    case GFunction::mill_fine_bore:
      return cycles::HoleKind::fine_bore;
    case GFunction::mill_back_bore:
      return cycles::HoleKind::back_bore;
    default:
      return cycles::HoleKind::drill;
  }
}

// The mill's cycles that dwell P at the bottom (FANUC 0i-M; the seed names them only); the
// others keep a P for the cycle that follows.
bool mill_dwells(GFunction f) {
  return f == GFunction::mill_drill_dwell || f == GFunction::mill_tap ||
         f == GFunction::mill_tap_left || f == GFunction::mill_bore_dwell ||
         f == GFunction::mill_fine_bore || f == GFunction::mill_back_bore;
}

// The mill's peck form: G73 backs off by the parameter's amount, G83 returns to R; G81 and the
// others feed to the bottom in one go.
cycles::PeckMode mill_peck_mode(GFunction f) {
  return f == GFunction::mill_peck_high_speed ? cycles::PeckMode::high_speed
         : f == GFunction::mill_peck_deep     ? cycles::PeckMode::deep
                                              : cycles::PeckMode::none;
}

}  // namespace

bool ProgramRun::hole_cycle_block(bool group10_in_block, bool motion_code_in_block) const {
  if (group10_in_block) {
    return true;
  }
  return hole_.active() && !motion_code_in_block;
}

bool ProgramRun::hole_axes(std::array<int, 2>& plane, int& drill, int column) {
  if (!require_plane_axes(plane, column)) {
    return false;  // a plane (G17/G19) whose axes this channel lacks: no drilling axis
  }
  if (config_.dialect != Dialect::fanuc_mill) {
    drill = side_cycle(hole_.function) ? plane[1] : plane[0];
    return true;
  }
  const char normal = modal_.plane == Plane::xy ? 'Z' : modal_.plane == Plane::zx ? 'Y' : 'X';
  drill = -1;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    drill = config_.axes[i].name == normal ? static_cast<int>(i) : drill;
  }
  if (drill < 0) {
    return fail(alarm::kNoPlaneAxis,
                std::string("the hole cycle drills along ") + normal +
                    ", the axis normal to the plane, which this channel lacks",
                column);
  }
  return true;
}

bool ProgramRun::take_hole_words(int column) {
  const bool gsk = config_.dialect == Dialect::gsk;
  const bool mill = config_.dialect == Dialect::fanuc_mill;
  state::HoleMode& h = hole_;
  const bool tap = hole_kind(h.function) == cycles::HoleKind::tap;
  std::array<int, 2> plane{};
  int drill = -1;
  if (mill && !h.has_initial) {
    if (!hole_axes(plane, drill, column)) {
      return false;
    }
    h.initial = machine_[static_cast<std::size_t>(drill)];  // G98's level (FANUC)
    h.has_initial = true;
  }
  if (BlockWord* m = word('M'); m != nullptr && !mill) {
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
      // Dafeng and the mill: the R point, an absolute coordinate of the drilling axis; in the
      // mill's G91 the distance from the initial level (FANUC).
      h.has_r = true;
      if (!hole_axes(plane, drill, r->column)) {
        return false;
      }
      h.r_level = mill && modal_.incremental ? h.initial + length_of(*r)
                                             : to_physical(drill, scaled(*r, true)) +
                                                   offset_sum(drill) + tool_offset(drill);
    }
  }
  if (BlockWord* q = word('Q')) {
    q->used = true;
    // The mill's Q, as GSK's: mm with a point, else least increments (`Q5000` = 5 mm).
    h.peck = gsk || mill ? std::fabs(cycle_amount(*q)) : std::fabs(scaled(*q, true));
    h.shift = h.peck;  // G76/G87 read it as the shift off the wall
  }
  if (BlockWord* p = word('P')) {
    p->used = true;
    if (p->value < 0.0) {
      return fail(alarm::kNegativeDwell, "the dwell P (ms) at the hole bottom must be >= 0",
                  p->column);
    }
    h.dwell_s = p->value / 1000.0;
  }
  if (BlockWord* j = word('J'); j != nullptr && !mill) {
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
  if (tap && !mill) {  // the mill's lead is F/S (run_hole_cycle)
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
        h.lead = f->value * (modal_.metric ? 1.0 : 25.4);
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
  BlockWord* k = word('K');
  if (BlockWord* l = word('L'); l != nullptr && mill) {
    // The mill's older spelling of the repeat count (FANUC 0-M), K's synonym.
    if (k != nullptr) {
      return fail(alarm::kWordNotAllowed, "K and L both repeat the hole: give one", l->column);
    }
    k = l;
  }
  if (k != nullptr) {
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
  int drill_axis = -1;
  if (!hole_axes(axes, drill_axis, column)) {
    return false;
  }
  state::HoleMode& h = hole_;
  const bool mill = config_.dialect == Dialect::fanuc_mill;
  if (h.function == GFunction::mill_bore_manual) {
    return fail(alarm::kNotInThisVersion,
                "G88: the tool leaves the hole by hand, which the runtime has no mode for", column);
  }
  const auto drill = static_cast<std::size_t>(drill_axis);
  const cycles::HoleKind kind = hole_kind(h.function);
  if (kind != cycles::HoleKind::tap || mill) {
    BlockWord* fw = word('F');
    if (!check_feed(fw != nullptr ? fw->column : column)) {
      return false;
    }
  }
  if (mill && kind == cycles::HoleKind::tap) {
    // G84/G74: F is the feed; the lead is F/S (FANUC 0i-M's rigid tapping in G94).
    const double rpm = spindles_.reference_rpm();
    if (modal_.feed_mode == FeedMode::per_min && rpm <= 0.0) {
      return fail(alarm::kThreadLead, "tapping needs the spindle speed S: the lead is F/S", column);
    }
    h.lead = (modal_.feed_mode == FeedMode::per_min ? modal_.feed / rpm : modal_.feed) *
             (h.function == GFunction::mill_tap_left ? -1.0 : 1.0);
  }
  bool first = true;
  overload_block_ = 0;  // G10 L14 P7/P8: this block's in-feeds get a number of their own
  // Reset on every way out: the alarms below return early, and an alarm ends the run anyway.
  struct CycleOutput {
    bool& flag;
    ~CycleOutput() { flag = false; }
  } cycle_output{cycle_output_ = true};
  // K0 reads the block's words (the bottom, modal) and makes no hole (FANUC: data only).
  for (int k = 0; k < std::max(h.repeat, 1); ++k) {
    AxisVector target{};
    std::array<bool, kMaxChannelAxes> given{};
    if (!read_axis_targets(target, given, false)) {
      return false;
    }
    if (first && given[drill]) {
      // The mill's G91: Z is the distance from R to the bottom (FANUC).
      h.bottom = mill && modal_.incremental
                     ? (h.has_r ? h.r_level : h.initial) + target[drill] - machine_[drill]
                     : target[drill];
      h.has_bottom = true;
    }
    first = false;
    if (!h.has_bottom) {
      return fail(
          alarm::kCycleWordMissing,
          "the hole cycle needs the hole bottom (" + std::string(1, config_.axes[drill].name) + ")",
          column);
    }
    if (h.repeat == 0) {
      break;
    }
    // Position on the hole at rapid, the drilling axis staying at the initial level.
    target[drill] = machine_[drill];
    if (target != machine_) {
      emit(Op::rapid).to = target;
      machine_ = target;
      block_moved_ = true;
    }
    const AxisVector centre = machine_;
    cycles::HoleCycle c;
    c.kind = kind;
    c.initial = machine_[drill];
    c.has_initial_level = mill;
    c.initial_level = h.initial;
    c.r_level = h.has_r ? h.r_level : machine_[drill];
    c.bottom = h.bottom;
    c.peck = h.peck;
    c.dwell_s = !mill || mill_dwells(h.function) ? h.dwell_s : 0.0;
    c.shift = h.shift;
    c.feed = modal_.feed;
    c.lead = h.lead;
    c.clamp_code = h.clamp;
    c.return_to_initial = config_.system == GCodeSystem::b && modal_.codes[11] == 98.0;
    const CycleDefaults& d = config_.cycles;
    const int variant = h.code10 % 10;  // G83.5 -> 5
    if (mill && kind == cycles::HoleKind::tap) {
      // Peck tapping with Q (FANUC 0i-M, param 5200.5): high-speed backs off `tap_retract`,
      // the other form returns to R, as the lathe's G84.5/G84.6.
      c.retract = d.tap_retract;
      c.peck_mode = h.peck <= 0.0      ? cycles::PeckMode::none
                    : d.tap_high_speed ? cycles::PeckMode::high_speed
                                       : cycles::PeckMode::deep;
    } else if (mill) {
      c.peck_mode = mill_peck_mode(h.function);
      c.retract = d.drill_retract;
      c.clearance = d.drill_clearance;
    } else if (kind == cycles::HoleKind::tap) {
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
    const SpindleDirection turning = spindles_.reference_direction();
    // Rigid tapping (M29): the spindle stands and follows the thread move; G10 L14 P8 watches
    // only that form (L4902).
    const bool rigid = turning != SpindleDirection::cw && turning != SpindleDirection::ccw;
    // A step deeper into the hole than where the drilling axis stands: an in-feed.
    const double inward = c.bottom < c.r_level ? -1.0 : 1.0;
    const auto into_hole = [&](double to) { return (to - machine_[drill]) * inward > 0.0; };
    for (const cycles::HoleStep& s : steps) {
      AxisVector to = machine_;
      to[drill] = s.to;
      switch (s.kind) {
        case cycles::HoleStep::Kind::rapid:
          emit(Op::rapid).to = to;
          machine_ = to;
          break;
        case cycles::HoleStep::Kind::feed: {
          const bool in_feed = into_hole(s.to);
          Command& cmd = emit(Op::linear);
          cmd.to = to;
          cmd.feed = modal_.feed;
          cmd.feed_mode = modal_.feed_mode;
          if (in_feed && kind == cycles::HoleKind::drill && !mill) {
            watch_overload(cmd, false, std::fabs(s.to - c.r_level));  // G10 L14 P7
          }
          machine_ = to;
          break;
        }
        case cycles::HoleStep::Kind::tap: {
          const bool in_feed = into_hole(s.to);
          Command& cmd = emit(Op::thread);
          cmd.to = to;
          cmd.lead = std::fabs(c.lead);
          cmd.spindle = spindles_.reference;
          if (in_feed && rigid && !mill) {
            watch_overload(cmd, true, std::fabs(s.to - c.r_level));  // G10 L14 P8, M29 only
          }
          machine_ = to;
          break;
        }
        case cycles::HoleStep::Kind::dwell:
          emit(Op::dwell).seconds = s.seconds;
          break;
        case cycles::HoleStep::Kind::aux:
          emit(Op::aux).code = s.code;
          break;
        case cycles::HoleStep::Kind::spindle_stop:
        case cycles::HoleStep::Kind::orient: {
          Command& cmd = emit(Op::spindle);
          cmd.spindle = spindles_.reference;
          cmd.rpm = spindles_.reference_rpm();
          cmd.spindle_direction = s.kind == cycles::HoleStep::Kind::orient
                                      ? SpindleDirection::orient
                                      : SpindleDirection::stop;
          break;
        }
        case cycles::HoleStep::Kind::shift: {
          // Off the hole's centre along the plane axis of param 5101 (its sign by the parameter).
          const int dir = config_.cycles.bore_shift_direction;
          const auto axis = static_cast<std::size_t>(axes[static_cast<std::size_t>(dir / 2)]);
          to[drill] = machine_[drill];  // `to` of a shift is its amount, not a depth
          to[axis] = centre[axis] + (dir % 2 == 0 ? s.to : -s.to);
          emit(Op::rapid).to = to;
          machine_ = to;
          break;
        }
        case cycles::HoleStep::Kind::reverse:
        case cycles::HoleStep::Kind::restore: {
          // Follow tapping (M28): the PLC reverses a turning spindle for the way out; a
          // position-controlled spindle (M29, stopped) follows the thread move itself.
          if (turning != SpindleDirection::cw && turning != SpindleDirection::ccw) {
            break;
          }
          const bool reverse = s.kind == cycles::HoleStep::Kind::reverse;
          Command& cmd = emit(Op::spindle);
          cmd.spindle = spindles_.reference;
          cmd.rpm = spindles_.reference_rpm();
          cmd.spindle_direction = !reverse                          ? turning
                                  : turning == SpindleDirection::cw ? SpindleDirection::ccw
                                                                    : SpindleDirection::cw;
          break;
        }
      }
    }
    block_moved_ = true;
  }
  // A watched block's commands carry its number: an overload that ends the block drops those
  // after the in-feed (set_overload_result).
  for (std::size_t k = block_out_start_; overload_block_ != 0 && k < out_.size(); ++k) {
    out_[k].overload_block = overload_block_;
  }
  return true;
}

}  // namespace mcnc::interp
