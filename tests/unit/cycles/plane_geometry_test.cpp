// The shared plane primitives of channel/interp/path/plane_geometry.hpp: arc sweep signs and
// full circles, directions, lengths, points along a move, arc membership and intersections
// (tangent cases included).
#include "channel/interp/path/plane_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::path::test {
namespace {

constexpr double kTol = 1e-9;

PlaneMove arc_to(Point2 to, Point2 center, bool ccw) {
  PlaneMove m;
  m.kind = MoveKind::arc;
  m.to = to;
  m.center = center;
  m.ccw = ccw;
  return m;
}

PlaneMove line_to(Point2 to) {
  PlaneMove m;
  m.kind = MoveKind::feed;
  m.to = to;
  return m;
}

void expect_point(Point2 p, double a, double b, double tol = kTol) {
  EXPECT_NEAR(p.a, a, tol);
  EXPECT_NEAR(p.b, b, tol);
}

TEST(ArcSweep, QuarterCircleSignFollowsTheDirection) {
  const Point2 from{10, 0};
  EXPECT_NEAR(arc_sweep(from, arc_to({0, 10}, {0, 0}, true)), kPi / 2, kTol);
  EXPECT_NEAR(arc_sweep(from, arc_to({0, 10}, {0, 0}, false)), -1.5 * kPi, kTol);
  EXPECT_NEAR(arc_sweep(from, arc_to({0, -10}, {0, 0}, false)), -kPi / 2, kTol);
  EXPECT_NEAR(arc_sweep(from, arc_to({0, -10}, {0, 0}, true)), 1.5 * kPi, kTol);
}

TEST(ArcSweep, HalfCircleIsPiBothWaysWhateverTheSignOfZero) {
  // (10, 0) -> (-10, 0) gives cross = +0; (-10, 0) -> (10, 0) about (0, 0) gives cross = -0.
  EXPECT_NEAR(arc_sweep({10, 0}, arc_to({-10, 0}, {0, 0}, true)), kPi, kTol);
  EXPECT_NEAR(arc_sweep({10, 0}, arc_to({-10, 0}, {0, 0}, false)), -kPi, kTol);
  EXPECT_NEAR(arc_sweep({-10, 0}, arc_to({10, 0}, {0, 0}, true)), kPi, kTol);
  EXPECT_NEAR(arc_sweep({-10, 0}, arc_to({10, 0}, {0, 0}, false)), -kPi, kTol);
  EXPECT_NEAR(arc_sweep({0, -5}, arc_to({0, 5}, {0, 0}, true)), kPi, kTol);
  EXPECT_NEAR(arc_sweep({0, -5}, arc_to({0, 5}, {0, 0}, false)), -kPi, kTol);
}

TEST(ArcSweep, StartEqualToEndIsAFullCircle) {
  EXPECT_NEAR(arc_sweep({3, 4}, arc_to({3, 4}, {0, 0}, true)), 2 * kPi, kTol);
  EXPECT_NEAR(arc_sweep({3, 4}, arc_to({3, 4}, {0, 0}, false)), -2 * kPi, kTol);
  EXPECT_NEAR(move_length({3, 4}, arc_to({3, 4}, {0, 0}, true)), 10 * kPi, 1e-9);
}

TEST(ArcSweep, TinyArcsStayTiny) {
  const double angle = 1e-6;
  const Point2 to{100 * std::cos(angle), 100 * std::sin(angle)};
  EXPECT_NEAR(arc_sweep({100, 0}, arc_to(to, {0, 0}, true)), angle, 1e-12);
  EXPECT_NEAR(arc_sweep({100, 0}, arc_to(to, {0, 0}, false)), angle - 2 * kPi, 1e-12);
}

TEST(MoveLength, LinesArcsAndDwells) {
  EXPECT_NEAR(move_length({0, 0}, line_to({3, 4})), 5.0, kTol);
  EXPECT_NEAR(move_length({10, 0}, arc_to({0, 10}, {0, 0}, true)), 5 * kPi, kTol);
  EXPECT_NEAR(move_length({10, 0}, arc_to({0, 10}, {0, 0}, false)), 15 * kPi, kTol);
  PlaneMove dwell;
  dwell.kind = MoveKind::dwell;
  dwell.to = {7, 7};
  EXPECT_EQ(move_length({0, 0}, dwell), 0.0);
}

TEST(Directions, ArcsAreTangentAndFollowTheSense) {
  const PlaneMove ccw = arc_to({0, 10}, {0, 0}, true);
  expect_point(start_direction({10, 0}, ccw), 0, 1);
  expect_point(end_direction({10, 0}, ccw), -1, 0);
  const PlaneMove cw = arc_to({0, -10}, {0, 0}, false);
  expect_point(start_direction({10, 0}, cw), 0, -1);
  expect_point(end_direction({10, 0}, cw), -1, 0);
  expect_point(start_direction({1, 1}, line_to({4, 5})), 0.6, 0.8);
  expect_point(end_direction({1, 1}, line_to({4, 5})), 0.6, 0.8);
  expect_point(unit({0, 0}), 0, 0);
  expect_point(left_normal({1, 0}), 0, 1);
}

TEST(PointAlong, LinesAndArcsClampedToTheirEnds) {
  expect_point(point_along({0, 0}, line_to({3, 4}), 2.5), 1.5, 2.0);
  expect_point(point_along({0, 0}, line_to({3, 4}), -1), 0, 0);
  expect_point(point_along({0, 0}, line_to({3, 4}), 99), 3, 4);
  const PlaneMove ccw = arc_to({-10, 0}, {0, 0}, true);
  expect_point(point_along({10, 0}, ccw, 5 * kPi), 0, 10);
  const PlaneMove cw = arc_to({-10, 0}, {0, 0}, false);
  expect_point(point_along({10, 0}, cw, 5 * kPi), 0, -10);
  expect_point(point_along({10, 0}, cw, 1e9), -10, 0);
  // A full circle: three quarters of the way round, clockwise from (10, 0).
  expect_point(point_along({10, 0}, arc_to({10, 0}, {0, 0}, false), 15 * kPi), 0, 10);
}

TEST(WithinArc, InsideOutsideAndEnds) {
  const Point2 from{10, 0};
  const PlaneMove quarter_ccw = arc_to({0, 10}, {0, 0}, true);
  EXPECT_TRUE(within_arc(from, quarter_ccw, {10, 0}));
  EXPECT_TRUE(within_arc(from, quarter_ccw, {0, 10}));
  EXPECT_TRUE(within_arc(from, quarter_ccw, {6, 8}));
  EXPECT_FALSE(within_arc(from, quarter_ccw, {6, -8}));
  EXPECT_FALSE(within_arc(from, quarter_ccw, {-6, 8}));
  EXPECT_FALSE(within_arc(from, quarter_ccw, {-10, 0}));
  // The same end points clockwise: three quarters through the lower half.
  const PlaneMove three_quarters_cw = arc_to({0, 10}, {0, 0}, false);
  EXPECT_FALSE(within_arc(from, three_quarters_cw, {6, 8}));
  EXPECT_TRUE(within_arc(from, three_quarters_cw, {6, -8}));
  EXPECT_TRUE(within_arc(from, three_quarters_cw, {-6, 8}));
  EXPECT_TRUE(within_arc(from, three_quarters_cw, {-10, 0}));
  EXPECT_TRUE(within_arc(from, three_quarters_cw, {0, 10}));
}

TEST(WithinArc, ToleranceAtTheEndsIsInMillimetres) {
  const Point2 from{10, 0};
  const PlaneMove quarter_ccw = arc_to({0, 10}, {0, 0}, true);
  const double just_before = -0.5e-9 / 10;  // 0.5 nm before the start
  const double far_before = -1e-6 / 10;     // 1 um before the start
  EXPECT_TRUE(
      within_arc(from, quarter_ccw, {10 * std::cos(just_before), 10 * std::sin(just_before)}));
  EXPECT_FALSE(
      within_arc(from, quarter_ccw, {10 * std::cos(far_before), 10 * std::sin(far_before)}));
  EXPECT_TRUE(
      within_arc(from, quarter_ccw, {10 * std::cos(far_before), 10 * std::sin(far_before)}, 2e-6));
}

TEST(WithinArc, FullCircleHoldsEveryPoint) {
  std::mt19937 rng(4711);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  const PlaneMove full_ccw = arc_to({5, 0}, {0, 0}, true);
  const PlaneMove full_cw = arc_to({5, 0}, {0, 0}, false);
  for (int i = 0; i < 200; ++i) {
    const double t = angle(rng);
    const Point2 p{5 * std::cos(t), 5 * std::sin(t)};
    EXPECT_TRUE(within_arc({5, 0}, full_ccw, p)) << t;
    EXPECT_TRUE(within_arc({5, 0}, full_cw, p)) << t;
  }
}

TEST(WithinArc, RandomArcsAgreeWithTheSweep) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> sweep(0.05, 2 * kPi - 0.05);
  for (int i = 0; i < 300; ++i) {
    const double start = angle(rng);
    const bool ccw = i % 2 == 0;
    const double s = ccw ? sweep(rng) : -sweep(rng);
    const Point2 from{20 * std::cos(start), 20 * std::sin(start)};
    const PlaneMove arc = arc_to({20 * std::cos(start + s), 20 * std::sin(start + s)}, {0, 0}, ccw);
    ASSERT_NEAR(arc_sweep(from, arc), s, 1e-9);
    const double inside = start + 0.5 * s;
    const double outside = start + s + (ccw ? 0.02 : -0.02);
    EXPECT_TRUE(within_arc(from, arc, {20 * std::cos(inside), 20 * std::sin(inside)}));
    EXPECT_FALSE(within_arc(from, arc, {20 * std::cos(outside), 20 * std::sin(outside)}));
  }
}

TEST(IntersectLines, CrossingParallelAndShortDirections) {
  LineHits h = intersect_lines({0, 0}, {1, 1}, {4, 0}, {0, 1});
  ASSERT_EQ(h.count, 1);
  EXPECT_NEAR(h.t[0], 4.0, kTol);
  EXPECT_EQ(intersect_lines({0, 0}, {1, 1}, {0, 1}, {2, 2}).count, 0);
  EXPECT_EQ(intersect_lines({0, 0}, {1, 0}, {0, 0}, {0, 0}).count, 0);
  // Perpendicular direction vectors of 0.1 um are not parallel.
  h = intersect_lines({0, 0}, {1e-7, 0}, {3, 5}, {0, 1e-7});
  ASSERT_EQ(h.count, 1);
  EXPECT_NEAR(h.t[0], 3e7, 1e-3);
}

TEST(IntersectLineCircle, SecantTangentAndMiss) {
  LineHits h = intersect_line_circle({-10, 3}, {1, 0}, {0, 0}, 5);
  ASSERT_EQ(h.count, 2);
  EXPECT_NEAR(h.t[0], 6.0, kTol);
  EXPECT_NEAR(h.t[1], 14.0, kTol);
  h = intersect_line_circle({-10, 5}, {2, 0}, {0, 0}, 5);
  ASSERT_EQ(h.count, 1);
  EXPECT_NEAR(h.t[0], 5.0, kTol);
  EXPECT_EQ(intersect_line_circle({-10, 5.001}, {1, 0}, {0, 0}, 5).count, 0);
}

TEST(IntersectLineCircle, TangentLinesFoundWhateverTheirStartPoint) {
  // Tangent lines built in floating point, starting at the tangent point itself or far away,
  // on circles up to 1000 mm: one hit at the tangent point.
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> radius(0.1, 1000);
  std::uniform_real_distribution<double> along(-500, 500);
  for (int i = 0; i < 300; ++i) {
    const double t = angle(rng);
    const double r = radius(rng);
    const Point2 center{along(rng), along(rng)};
    const Point2 touch = center + r * Point2{std::cos(t), std::sin(t)};
    const Point2 dir = left_normal({std::cos(t), std::sin(t)});
    const double shift = i % 3 == 0 ? 0.0 : along(rng);
    const LineHits h = intersect_line_circle(touch + shift * dir, dir, center, r);
    ASSERT_GE(h.count, 1) << i;
    for (int k = 0; k < h.count; ++k) {
      const Point2 p = touch + (shift + h.t[k]) * dir;
      EXPECT_LT(length(p - touch), 1e-4) << i;
    }
  }
}

TEST(IntersectCircles, TwoPointsTangentsAndNone) {
  PointHits h = intersect_circles({0, 0}, 5, {8, 0}, 5);
  ASSERT_EQ(h.count, 2);
  expect_point(h.p[0], 4, 3);  // left of the line of centres
  expect_point(h.p[1], 4, -3);
  h = intersect_circles({0, 0}, 3, {8, 0}, 5);  // outside each other
  ASSERT_EQ(h.count, 1);
  expect_point(h.p[0], 3, 0);
  h = intersect_circles({0, 0}, 10, {4, 0}, 6);  // the second inside the first
  ASSERT_EQ(h.count, 1);
  expect_point(h.p[0], 10, 0);
  h = intersect_circles({4, 0}, 6, {0, 0}, 10);
  ASSERT_EQ(h.count, 1);
  expect_point(h.p[0], 10, 0);
  EXPECT_EQ(intersect_circles({0, 0}, 3, {9, 0}, 5).count, 0);
  EXPECT_EQ(intersect_circles({0, 0}, 10, {1, 0}, 5).count, 0);
  EXPECT_EQ(intersect_circles({1, 1}, 5, {1, 1}, 5).count, 0);
}

TEST(IntersectCircles, TangentCirclesFoundInFloatingPoint) {
  // Circles touching from outside or inside, built in floating point: one hit (or two a
  // rounding error apart) at the touching point.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> radius(0.1, 1000);
  std::uniform_real_distribution<double> coord(-500, 500);
  for (int i = 0; i < 300; ++i) {
    const Point2 c0{coord(rng), coord(rng)};
    const double r0 = radius(rng);
    const double r1 = radius(rng);
    const Point2 dir{std::cos(angle(rng)), std::sin(angle(rng))};
    const Point2 u = unit(dir);
    const bool outside = i % 2 == 0;
    const Point2 c1 = c0 + (outside ? r0 + r1 : r0 - r1) * u;
    if (!outside && std::fabs(r0 - r1) < 1e-3) {
      continue;
    }
    const Point2 touch = c0 + r0 * u;
    const PointHits h = intersect_circles(c0, r0, c1, r1);
    ASSERT_GE(h.count, 1) << i;
    for (int k = 0; k < h.count; ++k) {
      EXPECT_LT(length(h.p[k] - touch), 1e-4) << i;
    }
  }
}

TEST(IntersectCircles, RandomPairsHitBothCircles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-100, 100);
  std::uniform_real_distribution<double> radius(0.5, 150);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const Point2 c0{coord(rng), coord(rng)};
    const Point2 c1{coord(rng), coord(rng)};
    const double r0 = radius(rng);
    const double r1 = radius(rng);
    const PointHits h = intersect_circles(c0, r0, c1, r1);
    const double d = length(c1 - c0);
    const bool meet = d <= r0 + r1 && d >= std::fabs(r0 - r1);
    ASSERT_EQ(h.count, meet ? 2 : 0) << i;
    for (int k = 0; k < h.count; ++k) {
      EXPECT_NEAR(length(h.p[k] - c0), r0, 1e-9) << i;
      EXPECT_NEAR(length(h.p[k] - c1), r1, 1e-9) << i;
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
}

// G05 (gsk A.6.4): the circle through three points, and the sense the middle point gives.
TEST(PlaneGeometry, ArcThroughThreePointsFindsTheCentreAndTheSense) {
  const auto cw = arc_through({50, 9}, {38, 13}, {30, 29});
  ASSERT_TRUE(cw.has_value());
  EXPECT_NEAR(cw->center.a, 50, kTol);
  EXPECT_NEAR(cw->center.b, 29, kTol);
  EXPECT_FALSE(cw->ccw);
  const auto ccw = arc_through({30, 29}, {38, 13}, {50, 9});
  ASSERT_TRUE(ccw.has_value());
  EXPECT_TRUE(ccw->ccw);
  // The middle point beyond the end takes the long way round: the other sense.
  const auto around = arc_through({50, 9}, {70, 29}, {30, 29});
  ASSERT_TRUE(around.has_value());
  EXPECT_TRUE(around->ccw);
  EXPECT_NEAR(around->center.b, 29, kTol);
}

TEST(PlaneGeometry, ArcThroughCollinearOrRepeatedPointsIsNone) {
  EXPECT_FALSE(arc_through({0, 0}, {1, 1}, {2, 2}).has_value());
  EXPECT_FALSE(arc_through({0, 0}, {0, 0}, {2, 2}).has_value());
  EXPECT_FALSE(arc_through({0, 0}, {3, 1}, {0, 0}).has_value());
}

TEST(PlaneGeometry, ArcThroughSeededPointsOfACircle) {
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> coord(-500.0, 500.0);
  std::uniform_real_distribution<double> radius(0.5, 300.0);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi);
  for (int i = 0; i < 500; ++i) {
    const Point2 c{coord(rng), coord(rng)};
    const double r = radius(rng);
    const double t0 = angle(rng);
    const double sweep = std::uniform_real_distribution<double>(0.05, 2.0 * kPi - 0.05)(rng);
    const double dir = i % 2 == 0 ? 1.0 : -1.0;
    auto at = [&](double t) { return Point2{c.a + r * std::cos(t), c.b + r * std::sin(t)}; };
    const auto arc = arc_through(at(t0), at(t0 + dir * sweep / 3.0), at(t0 + dir * sweep));
    ASSERT_TRUE(arc.has_value()) << i;
    EXPECT_NEAR(arc->center.a, c.a, 1e-6 * (1.0 + r)) << i;
    EXPECT_NEAR(arc->center.b, c.b, 1e-6 * (1.0 + r)) << i;
    EXPECT_EQ(arc->ccw, dir > 0.0) << i;
  }
}

}  // namespace
}  // namespace mcnc::interp::path::test
