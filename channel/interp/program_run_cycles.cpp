// The multiple repetitive cycles G71-G76 (spec dafeng §2.5 L1480-1843, gsk A.6.30-A.6.32) and
// the hole cycles G83-G89 (dafeng L1844-2198, gsk A.6.34-A.6.35): their words, their modal
// amounts, and the moves of the pure expansions in channel/interp/cycles/.
#include "channel/interp/cycles/hole_cycles.hpp"
#include "channel/interp/cycles/multiple_thread.hpp"
#include "channel/interp/cycles/pattern_repeat.hpp"
#include "channel/interp/cycles/peck_grooving.hpp"
#include "channel/interp/cycles/rough_turning.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

bool ProgramRun::require_turning_plane(const char* code, std::array<int, 2>& axes, int column) {
  if (modal_.plane != Plane::zx) {
    return fail(alarm::kNoPlaneAxis, std::string(code) + " works in the ZX plane (G18) only",
                column);  // gsk D2-14
  }
  return require_plane_axes(axes, column);
}

bool ProgramRun::cycle_end_point(const char* code, std::array<int, 2>& axes, AxisVector& target,
                                 bool& second_block, int column) {
  if (!require_turning_plane(code, axes, column)) {
    return false;
  }
  std::array<bool, kMaxChannelAxes> given{};
  if (!read_axis_targets(target, given, false)) {
    return false;
  }
  // The block with an end point is the cycle's second block (gsk D1-4).
  second_block =
      given[static_cast<std::size_t>(axes[0])] || given[static_cast<std::size_t>(axes[1])];
  return true;
}

double ProgramRun::cycle_amount(const BlockWord& w) const {
  const double inch = modal_.metric ? 1.0 : 25.4;
  if (w.literal && !w.has_point) {
    return w.value * length_increment() * inch;
  }
  return w.value * inch;
}

bool ProgramRun::run_contour_cycle(const path::PlanePath& moves, const std::array<int, 2>& axes,
                                   int first, int last) {
  emit_plane_path(moves, axes, modal_.feed);
  // The contour follows the cycle block: execution goes on after N(Q) (gsk A.6.30 step 8).
  Frame& f = frames_.back();
  if (first >= f.pc) {
    f.pc = last + 1;
  }
  return true;
}

bool ProgramRun::run_rough_cycle(GFunction f, int column) {
  const char* code = f == GFunction::rough_turning ? "G71" : "G72";
  std::array<int, 2> axes{};
  if (!require_turning_plane(code, axes, column)) {
    return false;
  }
  CycleDefaults& m = cycle_memory_;
  BlockWord* u = word('U');
  BlockWord* w = word('W');
  BlockWord* r = word('R');
  if (word('P') == nullptr && word('Q') == nullptr) {
    // First block: depth of cut (G71 U, G72 W) and retract R, modal (spec L1488-1500).
    BlockWord* depth = f == GFunction::rough_turning ? u : w;
    BlockWord* other = f == GFunction::rough_turning ? w : u;
    if (other != nullptr) {
      return fail(alarm::kWordNotAllowed,
                  std::string(code) + "'s first block takes " +
                      (f == GFunction::rough_turning ? "U" : "W") + " (depth) and R (retract)",
                  other->column);
    }
    if (depth != nullptr) {
      depth->used = true;
      if (scaled(*depth, true) <= 0.0) {
        return fail(alarm::kCycleValue, std::string(code) + " depth of cut must be > 0",
                    depth->column);
      }
      m.rough_depth = length_of(*depth);
    }
    if (r != nullptr) {
      r->used = true;
      if (scaled(*r, true) < 0.0) {
        return fail(alarm::kCycleValue, std::string(code) + " retract R must be >= 0", r->column);
      }
      m.rough_retract = length_of(*r);
    }
    if (BlockWord* j = word('J'); j != nullptr && config_.dialect == Dialect::dafeng) {
      j->used = true;
      if (j->value != 0.0 && j->value != 1.0) {
        return fail(alarm::kCycleValue, "J must be 0 (45-degree retract) or 1 (along the contour)",
                    j->column);
      }
      m.rough_retract_along_contour = j->value == 1.0;
    }
    return true;
  }
  cycles::RoughingParams p;
  p.axis = f == GFunction::rough_turning ? cycles::RoughingAxis::a : cycles::RoughingAxis::b;
  p.depth = m.rough_depth;
  p.retract = m.rough_retract;
  p.retract_along_contour = m.rough_retract_along_contour;
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  // Allowances: U in X's programming unit (a diameter on a diameter axis), W along Z.
  if (u != nullptr) {
    u->used = true;
    p.allowance_b = to_physical(axes[1], scaled(*u, true), false);
  }
  if (w != nullptr) {
    w->used = true;
    p.allowance_a = to_physical(axes[0], scaled(*w, true), false);
  }
  if (r != nullptr) {
    return fail(alarm::kWordNotAllowed, std::string(code) + " P Q block takes no R", r->column);
  }
  if (BlockWord* k = word('K'); k != nullptr && config_.dialect == Dialect::gsk) {
    k->used = true;
    p.check_monotonic = k->value == 1.0;
  }
  BlockWord* fw = word('F');
  if (!check_feed(fw != nullptr ? fw->column : column)) {
    return false;
  }
  p.feed = modal_.feed;
  path::PlanePath contour;
  if (!capture_contour(code, axes, contour, p.type2, column)) {
    return false;
  }
  path::PlanePath moves;
  if (const path::PathResult e =
          cycles::expand_rough_turning({machine_[a], machine_[b]}, contour, p, moves)) {
    return fail_path(*e, column);
  }
  return run_contour_cycle(moves, axes, contour_.first, contour_.last);
}

bool ProgramRun::run_pattern_cycle(int column) {
  std::array<int, 2> axes{};
  if (!require_turning_plane("G73", axes, column)) {
    return false;
  }
  CycleDefaults& m = cycle_memory_;
  BlockWord* u = word('U');
  BlockWord* w = word('W');
  BlockWord* r = word('R');
  if (word('P') == nullptr && word('Q') == nullptr) {
    // First block: the total relief U(i) W(k) and the number of passes R(d), modal.
    if (u != nullptr) {
      u->used = true;
      m.pattern_relief_x = length_of(*u);  // a radius (spec L1672), not X's diameter
    }
    if (w != nullptr) {
      w->used = true;
      m.pattern_relief_z = length_of(*w);
    }
    if (r != nullptr) {
      r->used = true;
      if (r->value < 1.0 || r->value != std::floor(r->value)) {
        return fail(alarm::kCycleValue, "G73 R (number of passes) must be a whole number >= 1",
                    r->column);
      }
      m.pattern_passes = static_cast<int>(r->value);
    }
    return true;
  }
  cycles::PatternParams p;
  p.relief_a = m.pattern_relief_z;
  p.relief_b = m.pattern_relief_x;
  p.passes = m.pattern_passes;
  if (u != nullptr) {
    u->used = true;
    p.allowance_b = to_physical(axes[1], scaled(*u, true), false);
  }
  if (w != nullptr) {
    w->used = true;
    p.allowance_a = to_physical(axes[0], scaled(*w, true), false);
  }
  BlockWord* fw = word('F');
  if (!check_feed(fw != nullptr ? fw->column : column)) {
    return false;
  }
  p.feed = modal_.feed;
  path::PlanePath contour;
  bool type2 = false;
  if (!capture_contour("G73", axes, contour, type2, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  path::PlanePath moves;
  if (const path::PathResult e =
          cycles::expand_pattern_repeat({machine_[a], machine_[b]}, contour, p, moves)) {
    return fail_path(*e, column);
  }
  return run_contour_cycle(moves, axes, contour_.first, contour_.last);
}

bool ProgramRun::run_groove_cycle(GFunction f, int column) {
  const char* code = f == GFunction::face_grooving ? "G74" : "G75";
  std::array<int, 2> axes{};
  AxisVector target{};
  bool second_block = false;
  if (!cycle_end_point(code, axes, target, second_block, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  BlockWord* r = word('R');
  if (!second_block) {
    // First block: R(e), the back-off after each peck, modal.
    if (r != nullptr) {
      r->used = true;
      if (length_of(*r) < 0.0) {
        return fail(alarm::kCycleValue, std::string(code) + " R (retract) must be >= 0", r->column);
      }
      cycle_memory_.groove_retract = length_of(*r);
    }
    return true;
  }
  cycles::PeckGrooving g;
  g.axis = f == GFunction::face_grooving ? cycles::PeckAxis::a : cycles::PeckAxis::b;
  g.end = {target[a], target[b]};
  g.retract = cycle_memory_.groove_retract;
  // G74: P the X shift, Q the Z peck; G75: P the X peck, Q the Z shift (radius amounts).
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  double shift = 0.0;
  double peck = 0.0;
  if (p != nullptr) {
    p->used = true;
    (f == GFunction::face_grooving ? shift : peck) = std::fabs(cycle_amount(*p));
  }
  if (q != nullptr) {
    q->used = true;
    (f == GFunction::face_grooving ? peck : shift) = std::fabs(cycle_amount(*q));
  }
  g.peck = peck;
  g.step = shift;
  if (r != nullptr) {
    r->used = true;
    g.relief = std::fabs(length_of(*r));
  }
  BlockWord* fw = word('F');
  if (!check_feed(fw != nullptr ? fw->column : column)) {
    return false;
  }
  g.feed = modal_.feed;
  path::PlanePath moves;
  if (const path::PathResult e =
          cycles::expand_peck_grooving({machine_[a], machine_[b]}, g, moves)) {
    return fail_path(*e, column);
  }
  emit_plane_path(moves, axes, modal_.feed);
  return true;
}

bool ProgramRun::packed_thread_word(const char* code, BlockWord& p, std::array<int, 3>& fields) {
  p.used = true;
  const auto packed = static_cast<long>(std::lround(p.value));
  if (packed < 0 || packed > 999999 || p.value != std::floor(p.value)) {
    return fail(alarm::kCycleValue, std::string(code) + " P must be 6 digits mmrraa", p.column);
  }
  fields = {static_cast<int>(packed / 10000), static_cast<int>(packed / 100 % 100),
            static_cast<int>(packed % 100)};
  return true;
}

bool ProgramRun::thread_second_block(cycles::MultipleThread& t, int column) {
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  if (BlockWord* r = word('R')) {
    r->used = true;
    t.taper = length_of(*r);
  }
  if (p == nullptr || q == nullptr) {
    return fail(
        alarm::kCycleWordMissing,
        std::string(t.code) + " needs P (thread height) and Q (first depth) in its second block",
        column);
  }
  p->used = true;
  q->used = true;
  t.height = std::fabs(cycle_amount(*p));
  t.first_depth = std::fabs(cycle_amount(*q));
  return thread_lead(t.lead, column);
}

bool ProgramRun::emit_multiple_thread(const cycles::MultipleThread& t,
                                      const std::array<int, 2>& axes, int column) {
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  path::PlanePath moves;
  if (const path::PathResult e =
          cycles::expand_multiple_thread({machine_[a], machine_[b]}, t, moves)) {
    return fail_path(*e, column);
  }
  emit_plane_path(moves, axes, modal_.feed);
  return true;
}

bool ProgramRun::run_multiple_thread(int column) {
  std::array<int, 2> axes{};
  AxisVector target{};
  bool second_block = false;
  if (!cycle_end_point("G76", axes, target, second_block, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  CycleDefaults& m = cycle_memory_;
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  BlockWord* r = word('R');
  if (!second_block) {
    // First block: P mmrraa, Q the minimum depth, R the finishing allowance, J the infeed.
    if (std::array<int, 3> mra{}; p != nullptr) {
      if (!packed_thread_word("G76", *p, mra)) {
        return false;
      }
      m.thread_finish_passes = mra[0];
      m.thread_chamfer = mra[1];
      m.thread_angle = mra[2];
    }
    if (q != nullptr) {
      q->used = true;
      m.thread_min_depth = std::fabs(cycle_amount(*q));
    }
    if (r != nullptr) {
      r->used = true;
      m.thread_allowance = std::fabs(length_of(*r));
    }
    if (BlockWord* j = word('J'); j != nullptr && config_.dialect == Dialect::dafeng) {
      j->used = true;
      if (j->value != 0.0 && j->value != 1.0 && j->value != 3.0) {
        return fail(alarm::kCycleValue, "G76 J (infeed) must be 0, 1 or 3", j->column);
      }
      m.thread_alternating = j->value != 0.0;
    }
    if (BlockWord* pq = word('P', 'Q')) {
      // The chip-break interval, mm along the thread (dafeng L1795); PQ0 ends it.
      pq->used = true;
      if (length_of(*pq) < 0.0) {
        return fail(alarm::kCycleValue, "G76 PQ (chip-break interval) must not be negative",
                    pq->column);
      }
      m.thread_chip_break = length_of(*pq);
    }
    return true;
  }
  cycles::MultipleThread t;
  t.end = {target[a], target[b]};
  t.finish_passes = m.thread_finish_passes;
  t.tool_angle = m.thread_angle;
  t.min_depth = m.thread_min_depth;
  t.finish_allowance = m.thread_allowance;
  t.infeed =
      m.thread_alternating ? cycles::ThreadInfeed::alternating : cycles::ThreadInfeed::single_flank;
  t.chip_break = m.thread_chip_break;
  if (!thread_second_block(t, column)) {
    return false;
  }
  t.chamfer = m.thread_chamfer * t.lead / 10.0;
  if (config_.dialect == Dialect::dafeng) {
    if (BlockWord* k = word('K')) {
      k->used = true;
      t.lead_change = k->value * (modal_.metric ? 1.0 : 25.4);
    }
    if (BlockWord* l = word('L')) {
      l->used = true;
      if (l->value < 1.0 || l->value > 99.0 || l->value != std::floor(l->value)) {
        return fail(alarm::kCycleValue, "L (number of starts) must be a whole number 1-99",
                    l->column);
      }
      t.starts = static_cast<int>(l->value);
    }
  }
  return emit_multiple_thread(t, axes, column);
}

bool ProgramRun::run_extended_thread(int column) {
  std::array<int, 2> axes{};
  AxisVector target{};
  bool second_block = false;
  if (!cycle_end_point("G78", axes, target, second_block, column)) {
    return false;
  }
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  ExtendedThread& m = extended_thread_;
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  BlockWord* r = word('R');
  if (!second_block) {
    // First block (gsk A.6.33): P m r a, Q the minimum depth, R the finishing allowance, J/K
    // the run-out, D the finishing passes, L the starts, E the screw-in.
    if (std::array<int, 3> mra{}; p != nullptr) {
      if (!packed_thread_word("G78", *p, mra)) {
        return false;
      }
      if (mra[0] > 1 || mra[1] > 3) {
        return fail(alarm::kCycleValue,
                    "G78 P mmrraa: m is 0 (constant-distance infeed) or 1 (decreasing), r 0-3 "
                    "(centre, left, right, alternating)",
                    p->column);
      }
      m.constant_depth = mra[0] == 0;
      m.entry = mra[1];
      m.angle = mra[2];
    }
    if (q != nullptr) {
      q->used = true;
      m.min_depth = std::fabs(cycle_amount(*q));
    }
    if (r != nullptr) {
      r->used = true;
      m.allowance = std::fabs(length_of(*r));
    }
    if (BlockWord* e = word('E')) {
      // The screw-in along X, radius (gsk A.6.33); E0 ends it.
      e->used = true;
      if (length_of(*e) < 0.0) {
        return fail(alarm::kCycleValue, "G78 E (screw-in) must not be negative", e->column);
      }
      m.screw_in = length_of(*e);
    }
    for (const char w : {'D', 'L'}) {
      if (BlockWord* x = word(w)) {
        x->used = true;
        const double lo = w == 'D' ? 0.0 : 1.0;
        if (x->value < lo || x->value > 99.0 || x->value != std::floor(x->value)) {
          return fail(alarm::kCycleValue,
                      std::string("G78 ") + w + " must be a whole number " +
                          (w == 'D' ? "0-99 (finishing passes)" : "1-99 (starts)"),
                      x->column);
        }
        (w == 'D' ? m.finish_passes : m.starts) = static_cast<int>(x->value);
      }
    }
    BlockWord* j = word('J');
    BlockWord* k = word('K');
    if (j != nullptr || k != nullptr) {
      // As G92's run-out (gsk A.6.28): J the rise along X (radius), K the length along Z.
      m.runout_rise = j != nullptr ? std::fabs(length_of(*j)) : 0.0;
      m.runout_length = k != nullptr ? std::fabs(length_of(*k)) : 0.0;
      for (BlockWord* w : {j, k}) {
        if (w != nullptr) {
          w->used = true;
        }
      }
    }
    return true;
  }
  cycles::MultipleThread t;
  t.code = "G78";
  t.end = {target[a], target[b]};
  t.finish_passes = m.finish_passes;
  t.tool_angle = m.angle;
  t.min_depth = m.min_depth;
  t.finish_allowance = m.allowance;
  t.starts = m.starts;
  t.constant_depth = m.constant_depth;
  t.screw_in = m.screw_in;
  // Left (r = 1) and right (r = 2) name the flank of the groove the tool goes in along, the
  // one towards -Z and the one towards +Z as the ZX plane is drawn (decision 61): the flank
  // behind the cut is the single-flank infeed's, the one ahead the leading flank's.
  const bool towards_minus = t.end.a < machine_[a];
  switch (m.entry) {
    case 0:
      t.infeed = cycles::ThreadInfeed::radial;
      break;
    case 1:
      t.infeed =
          towards_minus ? cycles::ThreadInfeed::leading_flank : cycles::ThreadInfeed::single_flank;
      break;
    case 2:
      t.infeed =
          towards_minus ? cycles::ThreadInfeed::single_flank : cycles::ThreadInfeed::leading_flank;
      break;
    default:
      t.infeed = cycles::ThreadInfeed::alternating;
      break;
  }
  if (!thread_second_block(t, column)) {
    return false;
  }
  if (m.runout_length >= 0.0) {
    t.chamfer = m.runout_length;
    t.chamfer_rise = m.runout_rise;
  } else {
    t.chamfer = config_.thread_chamfer_leads * t.lead;  // param №19, at 45 degrees
  }
  return emit_multiple_thread(t, axes, column);
}

}  // namespace mcnc::interp
