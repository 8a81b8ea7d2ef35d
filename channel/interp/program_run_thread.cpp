// Threading G32/G34/G32.1/G32.2/G32.3 (spec dafeng §2.2 L850-1203, gsk A.6.37-A.6.40) and the
// single cycles G90/G92/G94 (dafeng §2.5 L2199-2376, gsk A.6.26-A.6.28), and the emission of
// plane paths that every cycle shares.
#include "channel/interp/cycles/single_cycles.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::interp {

namespace {

std::string format_value(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

}  // namespace

bool ProgramRun::fail_path(const path::PathError& e, int column) {
  if (const std::optional<int> line = contour_.line_of(e.source)) {
    return fail(e.alarm, e.text + " (contour block at line " + std::to_string(*line) + ")", column);
  }
  return fail(e.alarm, e.text, column);
}

bool ProgramRun::thread_lead(double& lead, int column) {
  BlockWord* f = word('F');
  BlockWord* i = word('I');
  if (f != nullptr && i != nullptr) {
    return fail(alarm::kWordNotAllowed, "a thread takes the lead F or threads per inch I, not both",
                i->column);
  }
  bool left_hand = left_hand_thread_;
  if (f != nullptr) {
    f->used = true;
    lead = f->value * (modal_.metric ? 1.0 : 25.4);
    left_hand = lead < 0.0 && signed_lead();
    lead = left_hand ? -lead : lead;
  } else if (i != nullptr) {
    i->used = true;
    if (i->value <= 0.0) {
      return fail(alarm::kThreadLead, "threads per inch I must be greater than 0", i->column);
    }
    lead = 25.4 / i->value;
    left_hand = false;
  } else {
    lead = thread_lead_;  // continuous threading may omit the lead (spec L908-913)
  }
  if (lead <= 0.0) {
    return fail(alarm::kThreadLead, "a thread needs its lead F (mm) or I (threads per inch) > 0",
                f != nullptr ? f->column : column);
  }
  thread_lead_ = lead;
  left_hand_thread_ = left_hand;
  return true;
}

bool ProgramRun::signed_lead() const {
  return config_.dialect == Dialect::gsk &&
         (modal_.motion == GFunction::thread_cycle_interpolated ||
          modal_.motion == GFunction::thread_interpolated);
}

bool ProgramRun::thread_repair_word(const std::string& code, bool cycle_code_in_block, int column) {
  BlockWord* p = word('P');
  if (p != nullptr) {
    p->used = true;
  }
  if (!config_.thread_repair) {
    cycle_repair_ = false;  // the function is off (№174.4 = 0): P1 is ignored (rule 1)
    return true;
  }
  if (p != nullptr && p->value != 0.0 && p->value != 1.0) {
    return fail(alarm::kBadWordValue, code + " P must be 0 (no repair) or 1 (thread repair)",
                p->column);
  }
  // A block with the code repairs with P1 only (rule 2); the blocks that repeat the modal
  // cycle keep what its first block said (rule 4: P1 only in the first).
  if (cycle_code_in_block || p != nullptr) {
    cycle_repair_ = p != nullptr && p->value == 1.0;
  }
  if (cycle_repair_ && !config_.thread_repair_recorded) {
    return fail(alarm::kThreadRepair,
                code +
                    " P1: no thread repair position is recorded (gsk A.6.41 rule 3: record it "
                    "on the position page with the tool tip in the groove)",
                p != nullptr ? p->column : column);
  }
  return true;
}

bool ProgramRun::thread_repair_angle(const std::array<double, 2>& start,
                                     const std::array<double, 2>& end,
                                     const std::array<int, 2>& axes, double lead, double& angle,
                                     int column) {
  // The recorded position is the long axis's (rule 5), Z of a turning thread.
  const int along = std::fabs(end[0] - start[0]) >= std::fabs(end[1] - start[1]) ? 0 : 1;
  const int axis = axes[static_cast<std::size_t>(along)];
  if (config_.axes[static_cast<std::size_t>(axis)].name != 'Z') {
    return fail(alarm::kThreadRepair,
                "thread repair records Z: a thread longer along " +
                    std::string(1, config_.axes[static_cast<std::size_t>(axis)].name) +
                    " than along Z cannot be repaired (gsk A.6.41 rule 5)",
                column);
  }
  const double z =
      to_physical(axis, config_.thread_repair_z) + offset_sum(axis) + tool_offset(axis);
  const double from = start[static_cast<std::size_t>(along)];
  const double to = end[static_cast<std::size_t>(along)];
  if (z < std::min(from, to) - 1e-9 || z > std::max(from, to) + 1e-9) {
    return fail(alarm::kThreadRepair,
                "the recorded thread repair position Z" + path::mm_text(config_.thread_repair_z) +
                    " is not between the thread's start and end (gsk A.6.41 rule 5)",
                column);
  }
  // The groove passes the recorded Z at the recorded angle: the thread starts as many
  // revolutions before it as the tool travels from the start to there.
  // A left-hand thread's spindle turns the negative way, its angle counting down.
  const double revolutions = std::fabs(z - from) / lead;
  const double turn = left_hand_thread_ && signed_lead() ? -1.0 : 1.0;
  angle = std::fmod(config_.thread_repair_degrees - turn * 360.0 * revolutions, 360.0);
  if (angle < 0.0) {
    angle += 360.0;
  }
  return true;
}

bool ProgramRun::thread_start_angle(double& angle) {
  angle = 0.0;
  BlockWord* q = word('Q');
  if (q == nullptr) {
    return true;
  }
  q->used = true;
  // Dafeng: whole degrees (param 5000.3 = 0); GSK: 0.001 degree (gsk A.6.37).
  const double degrees = config_.dialect == Dialect::gsk ? q->value / 1000.0 : q->value;
  angle = std::fmod(degrees, 360.0);
  if (angle < 0.0) {
    angle += 360.0;
  }
  return true;
}

bool ProgramRun::run_thread(GFunction f, int column) {
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  bool any = false;
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    any = any || given[i];
  }
  if (!any) {
    return true;  // G32 alone selects the mode
  }
  double lead = 0.0;
  double angle = 0.0;
  if (!thread_lead(lead, column) || !thread_start_angle(angle)) {
    return false;
  }
  const bool gsk = config_.dialect == Dialect::gsk;
  double lead_change = 0.0;
  // The lead change per revolution: K in the Dafeng dialect (G32 and G34), R of G34 in GSK.
  BlockWord* change = gsk ? (f == GFunction::thread_variable ? word('R') : nullptr) : word('K');
  if (change != nullptr) {
    change->used = true;
    lead_change = change->value * (modal_.metric ? 1.0 : 25.4);
  }
  if (f == GFunction::thread_variable && change == nullptr) {
    return fail(alarm::kWordNotAllowed,
                std::string("G34 needs the lead change per revolution ") + (gsk ? "R" : "K"),
                column);
  }
  if (BlockWord* j = word('J'); j != nullptr && !gsk) {
    return fail(alarm::kNotInThisVersion,
                "J (thread pull-out length) needs the high-precision threading mode of the "
                "planner, not yet available",
                j->column);
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  // Over the length of the thread the lead must stay > 0: lead^2 = F^2 + 2 K s (gsk D2-34).
  const double travel =
      std::max(std::fabs(target[a] - machine_[a]), std::fabs(target[b] - machine_[b]));
  if (lead * lead + 2.0 * lead_change * travel <= 0.0) {
    return fail(alarm::kThreadLead,
                "the lead change " + format_value(lead_change) + " brings the lead " +
                    format_value(lead) + " to 0 within the thread",
                change != nullptr ? change->column : column);
  }
  double rpm = 0.0;
  if (f == GFunction::thread_interpolated) {
    BlockWord* s = word('S');
    if (s == nullptr || s->value <= 0.0) {
      return fail(alarm::kWordNotAllowed, "G32.1 needs the spindle speed S > 0",
                  s != nullptr ? s->column : column);
    }
    s->used = true;
    rpm = s->value;
    if (word('Q') != nullptr && !gsk) {
      return fail(alarm::kWordNotAllowed,
                  "G32.1 has no start angle Q: position the spindle with G00 first",
                  word('Q')->column);
    }
  }
  const bool arc = f == GFunction::thread_arc_cw || f == GFunction::thread_arc_ccw;
  std::array<double, 2> center{};
  if (arc) {
    if (!arc_center(f == GFunction::thread_arc_ccw, axes, target, center, column)) {
      return false;
    }
    if (BlockWord* s = word('S')) {
      s->used = true;  // S given: interpolated like G32.1 (spec L1109-1159)
      rpm = s->value;
    }
  }
  // GSK run-out: over the last K of the long axis the short axis moves J (gsk A.6.37).
  double runout_long = 0.0;
  double runout_short = 0.0;
  if (gsk && !arc) {
    if (BlockWord* k = word('K')) {
      k->used = true;
      runout_long = std::fabs(length_of(*k));
    }
    if (BlockWord* j = word('J')) {
      j->used = true;
      runout_short = length_of(*j);
    }
  }
  const bool continuous = last_op_ == Op::thread;
  auto emit_thread = [&](const AxisVector& to, double lead_here, double start_angle, bool joins) {
    Command& c = emit(Op::thread);
    c.to = to;
    c.lead = lead_here;
    c.lead_change = lead_change;
    c.start_angle = start_angle;
    c.spindle = spindles_.reference;
    c.continuous = joins;
    c.rpm = rpm;
    c.left_hand = rpm > 0.0 && left_hand_thread_ && signed_lead();
    if (arc) {
      c.thread_arc = true;
      c.plane = modal_.plane;
      c.direction = f == GFunction::thread_arc_ccw ? ArcDirection::ccw : ArcDirection::cw;
      c.center_axes = axes;
      c.center = center;
    }
  };
  if (runout_long > 0.0 || runout_short != 0.0) {
    const bool a_long = std::fabs(target[a] - machine_[a]) >= std::fabs(target[b] - machine_[b]);
    const std::size_t lng = a_long ? a : b;
    const std::size_t sht = a_long ? b : a;
    const double length = std::fabs(target[lng] - machine_[lng]);
    if (runout_long > length) {
      return fail(alarm::kCycleValue,
                  "run-out K" + format_value(runout_long) + " is longer than the thread (" +
                      format_value(length) + ")",
                  word('K') != nullptr ? word('K')->column : column);
    }
    AxisVector before = target;
    const double dir = target[lng] >= machine_[lng] ? 1.0 : -1.0;
    const double fraction = length > 0.0 ? (length - runout_long) / length : 1.0;
    before[lng] = target[lng] - dir * runout_long;
    before[sht] = machine_[sht] + fraction * (target[sht] - machine_[sht]);
    AxisVector after = target;
    after[sht] = target[sht] + runout_short;
    emit_thread(before, lead, angle, continuous);
    emit_thread(after, lead, 0.0, true);
    machine_ = after;
  } else {
    emit_thread(target, lead, angle, continuous);
    machine_ = target;
  }
  block_moved_ = true;
  return true;
}

bool ProgramRun::run_flexible_tap(int column) {
  // GSK G33 (gsk A.6.36, D2-32): tap in synchronised, stop the spindle, reverse it, tap out,
  // stop; L times. The Dafeng manual has no G33.
  if (config_.dialect != Dialect::gsk) {
    return fail(alarm::kUnsupportedG, "G33 (flexible tapping) is a code of the GSK dialect",
                column);
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const auto drill = static_cast<std::size_t>(axes[0]);
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  for (std::size_t i = 0; i < config_.axes.size(); ++i) {
    if (given[i] && i != drill) {
      return fail(alarm::kWordNotAllowed, "G33 taps along Z only: give the hole bottom Z/W",
                  column);
    }
  }
  if (!given[drill]) {
    return true;  // G33 alone selects the mode
  }
  double lead = 0.0;
  if (!thread_lead(lead, column)) {
    return false;
  }
  int times = 1;
  if (BlockWord* l = word('L')) {
    l->used = true;
    if (l->value < 1.0 || l->value > 99.0 || l->value != std::floor(l->value)) {
      return fail(alarm::kCycleValue, "G33 L must be a whole number 1-99", l->column);
    }
    times = static_cast<int>(l->value);
  }
  const auto s = static_cast<std::size_t>(spindles_.reference);
  const SpindleDirection turning = spindles_.direction[s];
  if (turning != SpindleDirection::cw && turning != SpindleDirection::ccw) {
    return fail(alarm::kWordNotAllowed, "G33 needs the spindle turning (M03/M04) before it",
                column);
  }
  const SpindleDirection back =
      turning == SpindleDirection::cw ? SpindleDirection::ccw : SpindleDirection::cw;
  const AxisVector top = machine_;
  auto spindle = [&](SpindleDirection d) {
    Command& c = emit(Op::spindle);
    c.spindle = spindles_.reference;
    c.spindle_direction = d;
    c.rpm = spindles_.rpm[s];
  };
  auto tap = [&](const AxisVector& to) {
    Command& c = emit(Op::thread);
    c.to = to;
    c.lead = lead;
    c.spindle = spindles_.reference;
  };
  for (int i = 0; i < times; ++i) {
    if (i > 0) {
      spindle(turning);  // each repetition starts like the first, the spindle turning
    }
    tap(target);
    spindle(SpindleDirection::stop);
    spindle(back);
    tap(top);
    spindle(SpindleDirection::stop);
  }
  spindles_.direction[s] = SpindleDirection::stop;  // the cycle leaves the spindle stopped
  machine_ = top;
  block_moved_ = true;
  return true;
}

void ProgramRun::emit_plane_path(const path::PlanePath& moves, const std::array<int, 2>& axes,
                                 double feed, double thread_rpm) {
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  cycle_output_ = true;
  bool after_thread = false;
  for (const path::PlaneMove& m : moves) {
    AxisVector to = machine_;
    to[a] = m.to.a;
    to[b] = m.to.b;
    switch (m.kind) {
      case path::MoveKind::rapid:
        emit(Op::rapid).to = to;
        break;
      case path::MoveKind::feed:
      case path::MoveKind::arc: {
        Command& c = emit(m.kind == path::MoveKind::arc ? Op::arc : Op::linear);
        c.to = to;
        c.feed = m.feed > 0.0 ? m.feed : feed;
        c.feed_mode = modal_.feed_mode;
        if (m.kind == path::MoveKind::arc) {
          c.plane = modal_.plane;
          c.direction = m.ccw ? ArcDirection::ccw : ArcDirection::cw;
          c.center_axes = axes;
          c.center = {m.center.a, m.center.b};
        }
        break;
      }
      case path::MoveKind::thread: {
        Command& c = emit(Op::thread);
        c.to = to;
        c.lead = m.lead;
        c.lead_change = m.lead_change;
        c.start_angle = m.start_angle;
        c.spindle = spindles_.reference;
        c.continuous = after_thread;  // a chamfer-out continues its thread
        c.rpm = thread_rpm;
        c.left_hand = thread_rpm > 0.0 && left_hand_thread_ && signed_lead();
        break;
      }
      case path::MoveKind::dwell: {
        Command& c = emit(Op::dwell);
        c.seconds = m.seconds;
        break;
      }
    }
    after_thread = m.kind == path::MoveKind::thread;
    machine_ = to;
  }
  cycle_output_ = false;
  block_moved_ = block_moved_ || !moves.empty();
}

bool ProgramRun::run_single_cycle(GFunction f, bool cycle_code_in_block, int column) {
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  AxisVector target{};
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  if (!given[a] && !given[b]) {
    return true;  // the code alone selects the cycle
  }
  // Blocks that repeat the modal cycle keep its other end coordinate and taper (spec L2199-
  // 2265: "later blocks may give only X/U"); a block with the code starts from scratch.
  if (!cycle_code_in_block) {
    target[a] = given[a] ? target[a] : cycle_end_[a];
    target[b] = given[b] ? target[b] : cycle_end_[b];
  }
  double taper = cycle_code_in_block ? 0.0 : cycle_taper_;
  if (BlockWord* r = word('R')) {
    r->used = true;
    // R is a radius difference in X (G90/G92) or a Z difference (G94): physical either way.
    const double inch = modal_.metric ? 1.0 : 25.4;
    taper = scaled(*r, true) * inch;
  }
  cycle_end_ = target;
  cycle_taper_ = taper;

  cycles::SingleCycle c;
  c.kind = f == GFunction::turning_cycle  ? cycles::SingleCycleKind::turning
           : f == GFunction::facing_cycle ? cycles::SingleCycleKind::facing
                                          : cycles::SingleCycleKind::thread;
  c.end = {target[a], target[b]};
  c.taper = taper;
  double rpm = 0.0;  // G92.1: the interpolated spindle's speed
  if (f == GFunction::thread_cycle_interpolated) {
    // S: the threading speed (gsk A.6.29); without it the speed in force.
    BlockWord* s = word('S');
    rpm = s != nullptr ? s->value : spindles_.reference_rpm();
    if (s != nullptr) {
      s->used = true;
    }
    if (!(rpm > 0.0)) {
      return fail(alarm::kWordNotAllowed, "G92.1 needs the spindle speed S > 0",
                  s != nullptr ? s->column : column);
    }
    for (const char w : {'J', 'K', 'Q'}) {
      if (BlockWord* x = word(w)) {
        // The spindle stops with the feed at the end (gsk A.6.29 step 2): no run-out; the
        // spindle is positioned for each start, not told an angle.
        return fail(alarm::kWordNotAllowed,
                    std::string("G92.1 takes no ") + w + " (gsk A.6.29: X Z R F/I L S P)",
                    x->column);
      }
    }
  }
  if (c.kind == cycles::SingleCycleKind::thread) {
    if (!thread_lead(c.lead, column) || !thread_start_angle(c.start_angle)) {
      return false;
    }
    const bool gsk = config_.dialect == Dialect::gsk;
    const std::string code = f == GFunction::thread_cycle_interpolated ? "G92.1" : "G92";
    if (!gsk) {
      if (BlockWord* p = word('P')) {
        // The manual says no more than its name (dafeng L2285): the spec's decision D29 is to
        // ignore it with a warning (decision 87).
        p->used = true;
        warn("G92 P" + path::mm_text(length_of(*p)) +
                 " (thread feed start height) is ignored: the manual does not say what it does",
             p->column);
      }
    } else if (!thread_repair_word(code, cycle_code_in_block, column)) {
      return false;
    }
    if (cycle_repair_ && !thread_repair_angle({machine_[a], machine_[b]}, {target[a], target[b]},
                                              axes, c.lead, c.start_angle, column)) {
      return false;
    }
    if (BlockWord* l = word('L')) {
      l->used = true;
      if (l->value < 1.0 || l->value > 99.0 || l->value != std::floor(l->value)) {
        return fail(alarm::kCycleValue, "L (number of starts) must be a whole number 1-99",
                    l->column);
      }
      c.starts = static_cast<int>(l->value);
    }
    // The chamfer-out: Dafeng J = its length along Z at 45 degrees (param 5017); GSK J = the
    // rise along X (radius) and K = the length along Z. Without them the parameter, in leads.
    const double chamfer = config_.thread_chamfer_leads * c.lead;
    c.chamfer_a = chamfer;
    c.chamfer_b = chamfer;
    if (BlockWord* j = word('J')) {
      j->used = true;
      const double v = std::fabs(length_of(*j));
      if (gsk) {
        c.chamfer_b = v;
      } else {
        c.chamfer_a = v;
        c.chamfer_b = v;
      }
    }
    if (BlockWord* k = word('K')) {
      k->used = true;
      if (gsk) {
        c.chamfer_a = std::fabs(length_of(*k));
      } else {
        c.lead_change = k->value * (modal_.metric ? 1.0 : 25.4);
      }
    }
    if (f == GFunction::thread_cycle_interpolated) {
      c.chamfer_a = 0.0;  // the feed and the spindle stop together at the end (gsk A.6.29)
      c.chamfer_b = 0.0;
    }
  } else {
    BlockWord* fw = word('F');
    if (!check_feed(fw != nullptr ? fw->column : column)) {
      return false;
    }
    c.feed = modal_.feed;
  }
  path::PlanePath moves;
  if (const path::PathResult r =
          cycles::expand_single_cycle({machine_[a], machine_[b]}, c, moves)) {
    return fail_path(*r, column);
  }
  emit_plane_path(moves, axes, modal_.feed, rpm);
  return true;
}

}  // namespace mcnc::interp
