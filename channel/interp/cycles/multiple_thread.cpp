#include "channel/interp/cycles/multiple_thread.hpp"

#include "channel/interp/cycles/cycle_moves.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::interp::cycles {

namespace {

using path::mm_text;
using path::PathError;
using path::PathResult;
using path::PlaneMove;
using path::PlanePath;
using path::Point2;

constexpr double kTolerance = 1e-9;  // mm
constexpr double kDegree = path::kPi / 180.0;
// Passes of all starts together: a bound against a first depth of a few microns that would
// make millions of moves; real threads need tens.
constexpr std::size_t kMaxPasses = 20000;

PathResult value_error(const MultipleThread& c, const std::string& text) {
  return PathError{alarm::kCycleValue, std::string(c.code) + " " + text, -1};
}

PathResult check_amounts(const MultipleThread& c) {
  const auto value_error = [&c](const std::string& text) { return cycles::value_error(c, text); };
  if (!(c.height > 0.0)) {
    return value_error("thread height P" + mm_text(c.height) + " must be positive");
  }
  if (!(c.first_depth > 0.0)) {
    return value_error("first depth Q" + mm_text(c.first_depth) + " must be positive");
  }
  if (c.first_depth > c.height + kTolerance) {
    return value_error("first depth Q" + mm_text(c.first_depth) + " is larger than the height P" +
                       mm_text(c.height));
  }
  if (c.min_depth < 0.0 || c.finish_allowance < 0.0 || c.chamfer < 0.0) {
    return value_error("minimum depth " + mm_text(c.min_depth) + ", finishing allowance " +
                       mm_text(c.finish_allowance) + " and chamfer " + mm_text(c.chamfer) +
                       " must not be negative");
  }
  if (c.screw_in < 0.0 || c.chip_break < 0.0) {
    return value_error("screw-in " + mm_text(c.screw_in) + " and chip break interval " +
                       mm_text(c.chip_break) + " must not be negative");
  }
  if (c.finish_allowance >= c.height) {
    return value_error("finishing allowance R" + mm_text(c.finish_allowance) +
                       " leaves nothing to rough of the height P" + mm_text(c.height));
  }
  if (c.finish_passes < 0 || c.finish_passes > 99) {
    return value_error("finishing passes " + std::to_string(c.finish_passes) + " outside 0-99");
  }
  if (c.tool_angle < 0.0 || c.tool_angle > 99.0) {
    return value_error("tool angle " + mm_text(c.tool_angle) + " outside 0-99 degrees");
  }
  if (c.starts < 1) {
    return value_error("number of starts L" + std::to_string(c.starts) + " must be at least 1");
  }
  if (!(c.lead > 0.0)) {
    return value_error("lead F" + mm_text(c.lead) + " must be positive");
  }
  return std::nullopt;
}

// The thread's root runs from (start.a, end.b + taper) to end; the crest lies `height` from it
// on the side of the start point.
struct ThreadLine {
  Point2 start;    // A
  Point2 end;      // root at the end
  double taper;    // root b at start.a minus root b at end.a
  double height;   // crest to root
  double along;    // +1 when the thread runs towards +a
  double outward;  // +1 when the crest lies at larger b than the root (an outside thread)

  double root(double a) const { return end.b + taper * (a - end.a) / (start.a - end.a); }
  // b of the tool tip `depth` below the crest at `a`.
  double at_depth(double a, double depth) const { return root(a) + outward * (height - depth); }
};

PathResult check_start_outside(const MultipleThread& c, const ThreadLine& t) {
  for (double a : {t.start.a, t.end.a}) {
    const double crest = t.at_depth(a, 0.0);
    if (t.outward * (t.start.b - crest) < -kTolerance) {
      return value_error(c, "start point X" + mm_text(t.start.b) +
                                " (radius) lies inside the thread: crest X" + mm_text(crest) +
                                " at Z" + mm_text(a));
    }
  }
  return std::nullopt;
}

// Where along a the pass at `depth` starts, relative to A: flank infeed keeps one flank of the
// tool on one flank of the finished thread, whose bottom lies height * tan(angle / 2) ahead of A
// in the cutting direction; alternating infeed uses the other flank every second pass.
double infeed_shift(const MultipleThread& c, double depth, std::size_t pass) {
  const double flank = std::tan(c.tool_angle * kDegree / 2.0);
  switch (c.infeed) {
    case ThreadInfeed::radial:
      return 0.0;
    case ThreadInfeed::alternating:
      return pass % 2 == 0 ? depth * flank : (2.0 * c.height - depth) * flank;
    case ThreadInfeed::leading_flank:
      return (2.0 * c.height - depth) * flank;
    case ThreadInfeed::single_flank:
      break;
  }
  return depth * flank;
}

struct Pass {
  double depth;
  double start_a;
  double lift = 0.0;  // a chip break's rise: this pass's depth less the last one's; 0: none
};

// Chip breaks of all passes together: the bound of the other cycles' pecks.
constexpr std::size_t kMaxBreaks = 100000;

// The lead along a after `distance` of thread: lead + change * revolutions, with distance =
// lead * rev + change * rev^2 / 2.
double lead_after(const MultipleThread& c, double distance) {
  return std::sqrt(std::max(c.lead * c.lead + 2.0 * c.lead_change * distance, 0.0));
}

PathResult check_pass(const MultipleThread& c, const ThreadLine& t, const Pass& p) {
  const double chamfer_start = t.end.a - t.along * c.chamfer;
  if (t.along * (chamfer_start - p.start_a) <= kTolerance) {
    return value_error(c, "pass at depth " + mm_text(p.depth) + " starts at Z" +
                              mm_text(p.start_a) + ", not before the end of its thread at Z" +
                              mm_text(chamfer_start) + " (chamfer " + mm_text(c.chamfer) + ")");
  }
  if (c.screw_in > 0.0 && t.along * (chamfer_start - p.start_a) - c.screw_in <= kTolerance) {
    return value_error(c, "screw-in E" + mm_text(c.screw_in) + " of the pass at depth " +
                              mm_text(p.depth) + " from Z" + mm_text(p.start_a) +
                              " does not end before the end of its thread at Z" +
                              mm_text(chamfer_start));
  }
  const double length = std::fabs(t.end.a - p.start_a);
  if (c.lead * c.lead + 2.0 * c.lead_change * length <= kTolerance) {
    return PathError{alarm::kThreadLead,
                     std::string(c.code) + " lead F" + mm_text(c.lead) + " changing by K" +
                         mm_text(c.lead_change) +
                         " per revolution reaches 0 within the thread of length " + mm_text(length),
                     -1};
  }
  return std::nullopt;
}

// The thread moves of one pass, from its rapid in to its rapid back to A.
class PassBuilder {
 public:
  PassBuilder(const MultipleThread& c, const ThreadLine& t, const Pass& p, double start_angle,
              PlanePath& out)
      : c_(c), t_(t), p_(p), start_angle_(start_angle), out_(out) {}

  // Returns the number of chip breaks made, at most `budget` + 1 (then the pass is unfinished:
  // the caller refuses the cycle).
  std::size_t build(std::size_t budget) {
    const double chamfer_start = t_.end.a - t_.along * c_.chamfer;
    at_ = {p_.start_a, t_.at_depth(p_.start_a, p_.depth - c_.screw_in)};
    out_.push_back(rapid_to(at_));
    if (c_.screw_in > 0.0) {
      const double a = p_.start_a + t_.along * c_.screw_in;
      thread_to({a, t_.at_depth(a, p_.depth)});
    }
    std::size_t breaks = 0;
    if (c_.chip_break > 0.0 && p_.lift > 0.0) {
      // Each break: up at 45 degrees to the depth of the pass before, down again, as far
      // along a as it rises each way.
      while (breaks <= budget) {
        const double up = at_.a + t_.along * c_.chip_break;
        const double top = up + t_.along * p_.lift;
        const double down = top + t_.along * p_.lift;
        if (t_.along * (chamfer_start - down) <= kTolerance) {
          break;
        }
        thread_to({up, t_.at_depth(up, p_.depth)});
        thread_to({top, t_.at_depth(top, p_.depth - p_.lift)});
        thread_to({down, t_.at_depth(down, p_.depth)});
        ++breaks;
      }
    }
    thread_to({chamfer_start, t_.at_depth(chamfer_start, p_.depth)});
    if (c_.chamfer > 0.0) {
      // Out at 45 degrees: as far along b as along a (J/K of G78: its own rise).
      thread_to(
          {t_.end.a, at_.b + t_.outward * (c_.chamfer_rise >= 0.0 ? c_.chamfer_rise : c_.chamfer)});
    }
    out_.push_back(rapid_to({t_.end.a, t_.start.b}));
    out_.push_back(rapid_to(t_.start));
    return breaks;
  }

 private:
  void thread_to(Point2 to) {
    PlaneMove m;
    m.kind = path::MoveKind::thread;
    m.to = to;
    const double along_a = std::fabs(to.a - at_.a);
    const double along_b = std::fabs(to.b - at_.b);
    // The lead (and its change) is counted along the longer axis; at 45 degrees a stays it,
    // whatever the rounding of b says.
    const double longer = along_b > along_a + kTolerance && along_a > 0.0 ? along_b / along_a : 1.0;
    m.lead = lead_after(c_, std::fabs(at_.a - p_.start_a)) * longer;
    m.lead_change = c_.lead_change * longer;
    m.start_angle = start_angle_;
    out_.push_back(m);
    at_ = to;
  }

  const MultipleThread& c_;
  const ThreadLine& t_;
  const Pass& p_;
  double start_angle_;
  PlanePath& out_;
  Point2 at_{};
};

}  // namespace

std::vector<double> thread_pass_depths(const MultipleThread& cycle) {
  std::vector<double> depths;
  const double last = cycle.height - cycle.finish_allowance;
  if (!(cycle.first_depth > 0.0) || !(last > 0.0)) {
    return depths;
  }
  const double min_step = std::max(cycle.min_depth, 0.0);
  double depth = 0.0;
  // One pass beyond the bound tells the caller that there are too many.
  for (std::size_t n = 1; depth < last && depths.size() <= kMaxPasses; ++n) {
    const double scheduled = cycle.constant_depth
                                 ? cycle.first_depth * static_cast<double>(n)
                                 : cycle.first_depth * std::sqrt(static_cast<double>(n));
    depth = std::max(scheduled, depth + min_step);
    if (depth >= last - kTolerance) {
      depth = last;
    }
    depths.push_back(depth);
  }
  return depths;
}

path::PathResult expand_multiple_thread(path::Point2 start, const MultipleThread& cycle,
                                        path::PlanePath& out) {
  if (PathResult e = check_amounts(cycle)) {
    return e;
  }
  const auto value_error = [&cycle](const std::string& text) {
    return cycles::value_error(cycle, text);
  };
  if (std::fabs(cycle.end.a - start.a) <= kTolerance) {
    return value_error("thread has no length: end Z" + mm_text(cycle.end.a) +
                       " equals the start Z");
  }
  const double root_at_start = cycle.end.b + cycle.taper;
  if (std::fabs(start.b - root_at_start) <= kTolerance) {
    return value_error("start point X" + mm_text(start.b) + " (radius) lies on the thread's root");
  }
  const ThreadLine line{.start = start,
                        .end = cycle.end,
                        .taper = cycle.taper,
                        .height = cycle.height,
                        .along = cycle.end.a > start.a ? 1.0 : -1.0,
                        .outward = start.b > root_at_start ? 1.0 : -1.0};
  if (PathResult e = check_start_outside(cycle, line)) {
    return e;
  }

  const std::vector<double> roughing = thread_pass_depths(cycle);
  const std::size_t finishing = cycle.finish_passes == 0 ? 1 : cycle.finish_passes;
  const std::size_t starts = static_cast<std::size_t>(cycle.starts);
  if ((roughing.size() + finishing) * starts > kMaxPasses) {
    return value_error("needs more than " + std::to_string(kMaxPasses) + " passes (first depth Q" +
                       mm_text(cycle.first_depth) + ", minimum depth " + mm_text(cycle.min_depth) +
                       ", " + std::to_string(starts) + " starts)");
  }
  std::vector<Pass> passes;
  double last_depth = 0.0;
  for (double depth : roughing) {
    passes.push_back({depth, 0.0, depth - last_depth});
    last_depth = depth;
  }
  // The first finishing pass removes the allowance, the others are spring passes.
  passes.insert(passes.end(), finishing, Pass{cycle.height, 0.0});
  for (std::size_t i = 0; i < passes.size(); ++i) {
    passes[i].start_a = start.a + line.along * infeed_shift(cycle, passes[i].depth, i);
    if (PathResult e = check_pass(cycle, line, passes[i])) {
      return e;
    }
  }

  PlanePath moves;
  std::size_t breaks = 0;
  for (const Pass& p : passes) {
    for (std::size_t s = 0; s < starts && breaks <= kMaxBreaks; ++s) {
      const double angle = 360.0 * static_cast<double>(s) / static_cast<double>(starts);
      breaks += PassBuilder(cycle, line, p, angle, moves).build(kMaxBreaks - breaks);
    }
  }
  if (breaks > kMaxBreaks) {
    return value_error("needs more than " + std::to_string(kMaxBreaks) + " chip breaks (every " +
                       mm_text(cycle.chip_break) + ")");
  }
  out.insert(out.end(), moves.begin(), moves.end());
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
