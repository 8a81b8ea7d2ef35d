// Tool-nose radius compensation on seeded random contours (spec dafeng §2.8 L3670-3798): the
// nose centre keeps exactly the nose radius from the programmed contour at every vertex of the
// compensated path, never comes closer anywhere along it, stays on the compensation side, and
// the path is continuous. Also the tip offsets of the ten tip numbers.
#include "channel/interp/path/nose_compensation.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "tests/unit/cycles/cycle_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mcnc::interp::path::test {
namespace {

using cycles::test::Uniform;

// Distance from p to the programmed element from `from` (a segment or an arc).
double distance_to(Point2 p, Point2 from, const PlaneMove& m) {
  if (m.kind == MoveKind::arc) {
    const double r = arc_radius(from, m);
    const Point2 on = m.center + r * unit(p - m.center);
    if (within_arc(from, m, on, 1e-9)) {
      return std::fabs(length(p - m.center) - r);
    }
    return std::min(length(p - from), length(p - m.to));
  }
  const Point2 d = m.to - from;
  const double t = std::clamp(dot(p - from, d) / dot(d, d), 0.0, 1.0);
  return length(p - (from + t * d));
}

double distance_to_contour(Point2 p, Point2 start, const PlanePath& contour) {
  double best = std::numeric_limits<double>::infinity();
  Point2 from = start;
  for (const PlaneMove& m : contour) {
    best = std::min(best, distance_to(p, from, m));
    from = m.to;
  }
  return best;
}

// An OD contour: Z falling; lines that rise or hold in X, and convex arcs (G02) of radius
// well above the nose radius, so that every corner can be compensated.
PlanePath random_contour(Uniform& u, Point2 start) {
  PlanePath c;
  Point2 at = start;
  const int n = 3 + u.below(6);
  for (int i = 0; i < n; ++i) {
    PlaneMove m;
    const Point2 to{at.a - u(2, 10), at.b + (u.chance(0.3) ? 0.0 : u(0.5, 6))};
    m.to = to;
    if (i > 0 && u.chance(0.35)) {
      m.kind = MoveKind::arc;
      m.ccw = false;
      const double chord = length(to - at);
      const double r = chord * u(0.6, 2.0);
      const Point2 mid = 0.5 * (at + to);
      const double h = std::sqrt(r * r - chord * chord / 4.0);
      const Point2 dir = unit(to - at);
      m.center = mid - h * left_normal(dir);  // right of the chord: a CW arc bulging left
    } else {
      m.kind = MoveKind::feed;
    }
    m.source = i;
    c.push_back(m);
    at = to;
  }
  return c;
}

TEST(NoseCompensationProperty, RadiusKeptAtEveryVertexAndNeverLess) {
  Uniform u(4142);
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    const double radius = u(0.2, 1.2);
    const Point2 start{5.0, u(5, 20)};
    const PlanePath contour = random_contour(u, start);
    const CompensationSide side = CompensationSide::right;  // G42: above an OD contour
    NoseCompensation nose;
    // Tip 0: the output is the nose centre itself.
    nose.start(start + Point2{0.0, 5.0}, side, radius, 0);
    PlanePath out;
    PlaneMove approach;
    approach.kind = MoveKind::feed;
    approach.to = start;
    approach.source = -2;
    ASSERT_FALSE(nose.push(approach, out)) << n;
    bool failed = false;
    for (const PlaneMove& m : contour) {
      if (nose.push(m, out)) {
        failed = true;  // a geometry the compensation refuses (alarm 1150) is allowed
        break;
      }
    }
    if (failed) {
      continue;
    }
    nose.flush(out);
    ASSERT_GE(out.size(), contour.size()) << n;
    ++checked;
    // Skip the start-up move (from the uncompensated start); check every later vertex and
    // samples along every later move.
    Point2 from = out.front().to;
    for (std::size_t i = 1; i < out.size(); ++i) {
      const PlaneMove& m = out[i];
      const double at_end = distance_to_contour(m.to, start, contour);
      EXPECT_NEAR(at_end, radius, 1e-6) << "case " << n << " vertex " << i;
      const double len = move_length(from, m);
      for (int k = 1; k < 8; ++k) {
        const Point2 q = point_along(from, m, len * k / 8.0);
        EXPECT_GE(distance_to_contour(q, start, contour), radius - 1e-6)
            << "case " << n << " move " << i << " comes closer than the nose radius";
      }
      // On the compensation side: above the contour (larger X) for this OD contour.
      EXPECT_GE(m.to.b, start.b - 1e-9) << n;
      from = m.to;
    }
  }
  EXPECT_GT(checked, 250);
}

TEST(NoseCompensationProperty, TipOffsetsOfTheTenTips) {
  const double r = 0.4;
  const Point2 want[10] = {{0, 0}, {r, r}, {-r, r}, {-r, -r}, {r, -r},
                           {r, 0}, {0, r}, {-r, 0}, {0, -r},  {0, 0}};
  for (int tip = 0; tip < 10; ++tip) {
    const Point2 got = tip_offset(tip, r);
    EXPECT_NEAR(got.a, want[tip].a, 1e-12) << "tip " << tip;
    EXPECT_NEAR(got.b, want[tip].b, 1e-12) << "tip " << tip;
  }
}

}  // namespace
}  // namespace mcnc::interp::path::test
