#include "channel/interp/cycles/rough_turning.hpp"

#include "channel/interp/cycles/cycle_moves.hpp"
#include "channel/interp/path/path_text.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace mcnc::interp::cycles {

namespace {

using path::MoveKind;
using path::PlaneMove;
using path::PlanePath;
using path::Point2;

constexpr double kEps = 1e-9;

// The cycle in its own terms: c is the cutting axis (a for G71, b for G72), s the stepping axis.
struct Axes {
  bool cut_along_a = true;
  double c(Point2 p) const { return cut_along_a ? p.a : p.b; }
  double s(Point2 p) const { return cut_along_a ? p.b : p.a; }
  Point2 point(double c, double s) const { return cut_along_a ? Point2{c, s} : Point2{s, c}; }
};

path::PathError error(int alarm, std::string text, int source = -1) {
  return path::PathError{alarm, std::move(text), source};
}

// Points along a move (its end included) for the monotonicity checks of arcs.
void sample(Point2 from, const PlaneMove& m, std::vector<Point2>& out) {
  out.clear();
  const int n = m.kind == MoveKind::arc ? 32 : 1;
  const double length = path::move_length(from, m);
  for (int i = 1; i <= n; ++i) {
    out.push_back(path::point_along(from, m, length * i / n));
  }
}

// Where the line s = level meets the move from `from`: the hits' c values, appended.
void crossings(const Axes& x, Point2 from, const PlaneMove& m, double level,
               std::vector<double>& out) {
  const Point2 p = x.point(0.0, level);
  const Point2 d = x.point(1.0, 0.0);
  if (m.kind == MoveKind::arc) {
    const path::LineHits h = path::intersect_line_circle(p, d, m.center, path::arc_radius(from, m));
    for (int i = 0; i < h.count; ++i) {
      const Point2 q = p + h.t[static_cast<std::size_t>(i)] * d;
      if (path::within_arc(from, m, q, 1e-9)) {
        out.push_back(x.c(q));
      }
    }
    return;
  }
  const double s0 = x.s(from);
  const double s1 = x.s(m.to);
  if (std::fabs(s1 - s0) < kEps) {
    if (std::fabs(s0 - level) < kEps) {  // along the level: both ends touch it
      out.push_back(x.c(from));
      out.push_back(x.c(m.to));
    }
    return;
  }
  const double t = (level - s0) / (s1 - s0);
  if (t >= -kEps && t <= 1.0 + kEps) {
    out.push_back(x.c(from) + t * (x.c(m.to) - x.c(from)));
  }
}

// The contour moved by the allowance, from B' (the first move's end) on.
struct Rough {
  Point2 b_prime;
  PlanePath moves;  // from B' to C'
};

}  // namespace

path::PathResult expand_rough_turning(Point2 start, const PlanePath& contour,
                                      const RoughingParams& p, PlanePath& out) {
  const Axes x{p.axis == RoughingAxis::a};
  const char* code = p.axis == RoughingAxis::a ? "G71" : "G72";
  const std::string name(code);
  if (contour.size() < 2) {
    return error(alarm::kContourMissing,
                 name + " contour needs a first move to B and at least one move after it");
  }
  if (static_cast<int>(contour.size()) > p.max_elements) {
    return error(alarm::kContourTooLong, name + " contour has " + std::to_string(contour.size()) +
                                             " moves, more than " + std::to_string(p.max_elements));
  }
  if (!(p.depth > 0.0) || p.retract < 0.0) {
    return error(alarm::kCycleValue, name + " depth of cut " + path::mm_text(p.depth) +
                                         " must be > 0 and the retract " +
                                         path::mm_text(p.retract) + " >= 0");
  }
  const PlaneMove& first = contour.front();
  if (first.kind != MoveKind::rapid && first.kind != MoveKind::feed) {
    return error(alarm::kContourStart, name + " contour must start with G00 or G01", 0);
  }
  const Point2 shift{p.allowance_a, p.allowance_b};
  const Point2 a_prime = start + shift;
  Rough rough;
  rough.b_prime = first.to + shift;
  for (std::size_t i = 1; i < contour.size(); ++i) {
    PlaneMove m = contour[i];
    if (m.kind != MoveKind::rapid && m.kind != MoveKind::feed && m.kind != MoveKind::arc) {
      return error(alarm::kContourStart, name + " contour may hold G00, G01, G02 and G03 only",
                   static_cast<int>(i));
    }
    m.to = m.to + shift;
    m.center = m.center + shift;
    if (m.kind == MoveKind::rapid) {
      m.kind = MoveKind::feed;  // the semi-finishing pass cuts every element
    }
    m.feed = p.feed;
    rough.moves.push_back(m);
  }
  const Point2 c_end = rough.moves.back().to;
  const double cut_dir = x.c(c_end) >= x.c(rough.b_prime) ? 1.0 : -1.0;
  const double in_dir = x.s(rough.b_prime) < x.s(a_prime) ? -1.0 : 1.0;  // towards the part
  if (std::fabs(x.c(c_end) - x.c(rough.b_prime)) < kEps) {
    return error(alarm::kContourNotMonotonic,
                 name + " contour does not advance along " + (x.cut_along_a ? "Z" : "X"));
  }

  // Monotonicity (spec L1516-1523, gsk A.6.30 rule 3): the cutting axis always; the stepping
  // axis too for type I (away from the part, as the passes' ends need a single crossing).
  std::vector<Point2> points;
  Point2 at = rough.b_prime;
  for (std::size_t i = 0; i < rough.moves.size(); ++i) {
    const PlaneMove& m = rough.moves[i];
    sample(at, m, points);
    Point2 prev = at;
    for (const Point2 q : points) {
      const double dc = (x.c(q) - x.c(prev)) * cut_dir;
      const double ds = (x.s(q) - x.s(prev)) * -in_dir;
      if (dc < -1e-7 || ((!p.type2 || p.check_monotonic) && ds < -1e-7)) {
        const bool along_c = dc < -1e-7;
        return error(alarm::kContourNotMonotonic,
                     name + " contour goes back in " +
                         ((along_c == x.cut_along_a) ? std::string("Z") : std::string("X")) +
                         " at element " + std::to_string(i + 1) +
                         (along_c ? "" : " (a pocket needs type II: the first block with X and Z)"),
                     static_cast<int>(i + 1));
      }
      prev = q;
    }
    at = m.to;
  }
  // The stock lies between A' and the contour: no contour point beyond A' on the stock side.
  at = rough.b_prime;
  for (std::size_t i = 0; i < rough.moves.size(); ++i) {
    sample(at, rough.moves[i], points);
    for (const Point2 q : points) {
      if ((x.s(q) - x.s(a_prime)) * -in_dir > 1e-7) {
        return error(alarm::kCycleValue,
                     name + " start point is inside the stock: the contour reaches " +
                         path::mm_text(x.s(q)) + " beyond the start's " +
                         path::mm_text(x.s(a_prime)),
                     static_cast<int>(i + 1));
      }
    }
    at = rough.moves[i].to;
  }

  const MoveKind infeed = first.kind;  // the speed type of the first block (gsk A.6.30 step 2)
  Point2 at_pos = start;               // where the moves so far end
  auto push = [&](MoveKind kind, Point2 to) {
    if (path::same_point(at_pos, to)) {
      return;  // a move that goes nowhere is left out
    }
    PlaneMove m;
    m.kind = kind;
    m.to = to;
    m.feed = kind == MoveKind::feed ? p.feed : 0.0;
    out.push_back(m);
    at_pos = to;
  };
  if (!path::same_point(start, a_prime)) {
    push(MoveKind::rapid, a_prime);
  }
  const double s_a = x.s(a_prime);
  const double c_a = x.c(a_prime);
  // The passes go down to the contour's deepest point: B' for type I, a pocket's bottom for
  // type II.
  double s_limit = x.s(rough.b_prime);
  at = rough.b_prime;
  for (const PlaneMove& m : rough.moves) {
    sample(at, m, points);
    for (const Point2 q : points) {
      s_limit = (x.s(q) - s_limit) * in_dir > 0.0 ? x.s(q) : s_limit;
    }
    at = m.to;
  }
  const double total = std::fabs(s_limit - s_a);
  const auto passes = static_cast<long>(std::ceil(total / p.depth - 1e-9)) - 1;
  if (passes > 100000) {
    return error(alarm::kCycleValue,
                 name + " needs more than 100000 passes of depth " + path::mm_text(p.depth));
  }
  // The contour's s where it passes c (the contour is monotonic along c); nullopt outside it.
  const Axes across{!x.cut_along_a};
  std::vector<double> found;
  auto contour_s = [&](double c) -> std::optional<double> {
    found.clear();
    Point2 from = rough.b_prime;
    for (const PlaneMove& m : rough.moves) {
      crossings(across, from, m, c, found);
      from = m.to;
    }
    if (found.empty()) {
      return std::nullopt;
    }
    double best = found.front();  // the one nearest the part: the contour's surface there
    for (const double v : found) {
      best = (v - best) * in_dir > 0.0 ? v : best;
    }
    return best;
  };
  const double c_first = x.c(rough.b_prime);
  const double c_last = x.c(c_end);
  std::vector<double> hits;
  for (long k = 1; k <= passes; ++k) {
    const double level = s_a + in_dir * p.depth * static_cast<double>(k);
    const double prev_level = level - in_dir * p.depth;
    // Where stock lies along this level: between consecutive crossings with the roughing
    // contour, where the contour is on the part's side of the level (beyond the contour's ends
    // there is no part). Type I stops at the first crossing.
    hits.clear();
    at = rough.b_prime;
    for (const PlaneMove& m : rough.moves) {
      crossings(x, at, m, level, hits);
      at = m.to;
    }
    hits.push_back(c_a);
    hits.push_back(c_last);
    std::sort(hits.begin(), hits.end(), [&](double u, double v) { return (u - v) * cut_dir < 0; });
    std::vector<std::pair<double, double>> cuts;
    for (std::size_t i = 0; i + 1 < hits.size(); ++i) {
      const double u = hits[i];
      const double v = hits[i + 1];
      if ((u - c_a) * cut_dir < -kEps || (v - u) * cut_dir < kEps) {
        continue;  // behind the start, or no length
      }
      const double mid = (u + v) / 2.0;
      const std::optional<double> surface =
          (mid - c_first) * cut_dir < 0.0 ? std::nullopt : contour_s(mid);
      const bool stock = !surface || (*surface - level) * in_dir > 0.0;
      if (!stock) {
        if (!p.type2 && !cuts.empty()) {
          break;  // type I: the first contact ends the pass
        }
        continue;
      }
      if (!cuts.empty() && std::fabs(cuts.back().second - u) < kEps) {
        cuts.back().second = v;  // continuous stock
      } else {
        cuts.emplace_back(u, v);
      }
    }
    if (!p.type2 && cuts.size() > 1) {
      cuts.resize(1);
    }
    const double lift = -in_dir * p.retract;  // away from the part
    bool detour = false;
    for (std::size_t j = 0; j < cuts.size(); ++j) {
      const auto [c0, c1] = cuts[j];
      if (j == 0 && std::fabs(c0 - c_a) < kEps) {
        push(infeed, x.point(c0, level));
      } else {
        // Into a pocket: over the part at the start level, down at rapid to the last level
        // (cut by the passes before), then in at feed.
        detour = true;
        push(MoveKind::rapid, x.point(x.c(at_pos), s_a));
        push(MoveKind::rapid, x.point(c0, s_a));
        push(MoveKind::rapid, x.point(c0, prev_level));
        push(MoveKind::feed, x.point(c0, level));
      }
      push(MoveKind::feed, x.point(c1, level));
      // The retract: 45 degrees back off the contour, but within the cut just made (a narrow
      // pocket's entry wall stands right behind it), or along the contour (J1) where the
      // straight lift stays off the part.
      const double back_off = std::min(p.retract, std::fabs(c1 - c0));
      Point2 lifted = x.point(c1 - cut_dir * back_off, level + lift);
      if (p.retract_along_contour && p.retract > 0.0) {
        std::vector<double> ahead;
        Point2 from = rough.b_prime;
        for (const PlaneMove& m : rough.moves) {
          crossings(x, from, m, level + lift, ahead);
          from = m.to;
        }
        bool any = false;
        double best = 0.0;
        for (const double b : ahead) {
          if ((b - c1) * cut_dir >= -kEps && (!any || (b - best) * cut_dir < 0.0)) {
            best = b;
            any = true;
          }
        }
        bool clear = any;
        for (int k = 1; clear && k < 16; ++k) {
          const double c = c1 + (best - c1) * k / 16.0;
          const double line_s = level + lift * k / 16.0;
          const std::optional<double> surface = contour_s(c);
          clear = !surface || (line_s - *surface) * -in_dir >= -1e-9;
        }
        if (clear) {
          lifted = x.point(best, level + lift);
        }
      }
      if (p.retract > 0.0) {
        push(MoveKind::feed, lifted);
      }
    }
    if (cuts.empty()) {
      continue;
    }
    const Point2 here = at_pos;
    if (detour) {
      push(MoveKind::rapid, x.point(x.c(here), s_a));  // out over the part
      push(MoveKind::rapid, x.point(c_a, s_a));
    } else {
      push(MoveKind::rapid, x.point(c_a, x.s(here)));
    }
  }
  // To B' and along the contour moved by the allowance, then back to A.
  push(infeed, rough.b_prime);
  for (const PlaneMove& m : rough.moves) {
    out.push_back(m);
    at_pos = m.to;
  }
  push(MoveKind::rapid, start);
  return std::nullopt;
}

}  // namespace mcnc::interp::cycles
