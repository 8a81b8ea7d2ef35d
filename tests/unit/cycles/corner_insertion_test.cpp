// Automatic chamfer and corner rounding (channel/interp/path/corner_insertion.hpp): the spec
// examples of dafeng §2.4 and gsk D2-12 with points computed independently, every alarm, and
// random line/arc corners checked for geometry.
#include "channel/interp/path/corner_insertion.hpp"

#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace mcnc::interp::path::test {
namespace {

constexpr double kTol = 1e-6;  // golden points were computed to 1e-9 by a separate program

PlaneMove line_to(Point2 to, double feed = 500) {
  PlaneMove m;
  m.kind = MoveKind::feed;
  m.to = to;
  m.feed = feed;
  m.source = 4;
  return m;
}

// G02/G03 with R: the centre of the arc of at most 180 degrees (left of the chord for G03).
PlaneMove arc_r(Point2 from, Point2 to, double r, bool ccw) {
  const Point2 chord = to - from;
  const double h = std::sqrt(r * r - 0.25 * dot(chord, chord));
  PlaneMove m;
  m.kind = MoveKind::arc;
  m.to = to;
  m.ccw = ccw;
  m.center = 0.5 * (from + to) + (ccw ? h : -h) * left_normal(unit(chord));
  m.feed = 500;
  m.source = 4;
  return m;
}

void expect_point(Point2 p, double a, double b, double tol = kTol) {
  EXPECT_NEAR(p.a, a, tol);
  EXPECT_NEAR(p.b, b, tol);
}

// Alarm 1147 whose text contains `part`.
void expect_does_not_fit(const PathResult& e, const std::string& part) {
  ASSERT_TRUE(e.has_value()) << part;
  EXPECT_EQ(e->alarm, alarm::kCornerDoesNotFit);
  EXPECT_NE(e->text.find(part), std::string::npos) << e->text;
}

// dafeng §2.4 L473-477: all from G00 X40 Z150 (a = Z, b = X / 2), the corner at X110 Z120.
constexpr Point2 kStart{150, 20};
constexpr Point2 kCorner{120, 55};
constexpr Point2 kEnd{30, 60};  // X120 Z30

// The moves of the examples: the first ends at the corner, the second starts there.
enum class Example : std::uint8_t {
  line,         // G01 X110 Z120 (first) or G01 X120 Z30 (second)
  g03_r50,      // G03 X110 Z120 R50 (first)
  g02_r60_z20,  // G02 X110 Z20 R60 (second; the spec's R30 cannot span the 100 mm chord)
  g03_r60,      // G03 X120 Z30 R60 (second)
  g02_r60,      // G02 X120 Z30 R60 (second)
};

PlaneMove example_move(Example e) {
  switch (e) {
    case Example::g03_r50:
      return arc_r(kStart, kCorner, 50, true);
    case Example::g02_r60_z20:
      return arc_r(kCorner, {20, 55}, 60, false);
    case Example::g03_r60:
      return arc_r(kCorner, kEnd, 60, true);
    case Example::g02_r60:
      return arc_r(kCorner, kEnd, 60, false);
    case Example::line:
      break;
  }
  return line_to(kEnd);
}

struct Golden {
  const char* blocks;
  Example first;
  Example second;
  CornerKind kind;
  // The first move's new end, the second's new start and the round's centre (a, b), computed
  // to 1e-9 by a separate program (bisection along the moves).
  std::array<double, 6> points;
  bool ccw;  // round
};

class CornerGolden : public ::testing::TestWithParam<Golden> {};

TEST_P(CornerGolden, DafengExample) {
  const Golden& g = GetParam();
  SCOPED_TRACE(g.blocks);
  const PlaneMove first_before =
      g.first == Example::line ? line_to(kCorner) : example_move(g.first);
  const PlaneMove second_before = example_move(g.second);
  PlaneMove first = first_before;
  PlaneMove second = second_before;
  CornerResult r;
  ASSERT_EQ(insert_corner(kStart, first, second, g.kind, 10, 250, r), std::nullopt);
  ASSERT_TRUE(r.inserted);
  expect_point(first.to, g.points[0], g.points[1]);
  EXPECT_EQ(first.kind, first_before.kind);
  expect_point(first.center, first_before.center.a, first_before.center.b, 0.0);
  expect_point(r.corner.to, g.points[2], g.points[3]);
  expect_point(second.to, second_before.to.a, second_before.to.b, 0.0);
  EXPECT_EQ(second.kind, second_before.kind);
  EXPECT_EQ(r.corner.feed, 250);
  EXPECT_EQ(r.corner.source, -1);
  if (g.kind == CornerKind::round) {
    ASSERT_EQ(r.corner.kind, MoveKind::arc);
    expect_point(r.corner.center, g.points[4], g.points[5]);
    EXPECT_EQ(r.corner.ccw, g.ccw);
  } else {
    EXPECT_EQ(r.corner.kind, MoveKind::feed);
  }
}

// dafeng §2.4 L473-477, each with ,C10 and ,R10 (L474: "the same with ,R10").
INSTANTIATE_TEST_SUITE_P(
    Dafeng, CornerGolden,
    ::testing::Values(Golden{"G01 X110 Z120 ,C10; G01 X120 Z30",
                             Example::line,
                             Example::line,
                             CornerKind::chamfer_setback,
                             {126.507913735, 47.407433976, 110.015396468, 55.554700196, 0, 0},
                             false},
                      Golden{"G01 X110 Z120 ,R10; G01 X120 Z30 (turns left: G03)",
                             Example::line,
                             Example::line,
                             CornerKind::round,
                             {122.777127526, 51.760017886, 115.739261699, 55.236707683,
                              115.184561503, 45.252104151},
                             true},
                      Golden{"G01 X110 Z120 ,C10; G02 X110 Z20 R60",
                             Example::line,
                             Example::g02_r60_z20,
                             CornerKind::chamfer_setback,
                             {126.507913735, 47.407433976, 113.797074440, 47.156294594, 0, 0},
                             false},
                      Golden{"G01 X110 Z120 ,R10; G02 X110 Z20 R60",
                             Example::line,
                             Example::g02_r60_z20,
                             CornerKind::round,
                             {127.801375800, 45.898394900, 113.036122665, 46.358447843,
                              120.208809776, 39.390481166},
                             true},
                      Golden{"G03 X110 Z120 R50 ,C10; G01 X120 Z30",
                             Example::g03_r50,
                             Example::line,
                             CornerKind::chamfer_setback,
                             {128.854934610, 50.353481620, 110.015396468, 55.554700196, 0, 0},
                             false},
                      Golden{"G03 X110 Z120 R50 ,R10; G01 X120 Z30",
                             Example::g03_r50,
                             Example::line,
                             CornerKind::round,
                             {121.797649253, 54.234420857, 118.255085645, 55.096939686,
                              117.700385449, 45.112336154},
                             true},
                      Golden{"G03 X110 Z120 R50 ,C10; G03 X120 Z30 R60",
                             Example::g03_r50,
                             Example::g03_r60,
                             CornerKind::chamfer_setback,
                             {128.854934610, 50.353481620, 113.191550810, 62.324276048, 0, 0},
                             false},
                      Golden{"G03 X110 Z120 R50 ,R10; G03 X120 Z30 R60 (turns right: G02)",
                             Example::g03_r50,
                             Example::g03_r60,
                             CornerKind::round,
                             {122.049917018, 54.120272117, 118.569825755, 56.752956445,
                              126.197634374, 63.219527071},
                             false},
                      Golden{"G03 X110 Z120 R50 ,R10; G02 X120 Z30 R60",
                             Example::g03_r50,
                             Example::g02_r60,
                             CornerKind::round,
                             {126.817887526, 51.628828876, 115.356640338, 50.744806104,
                              121.716576067, 43.027862570},
                             true},
                      Golden{"G03 X110 Z120 R50 ,C10; G02 X120 Z30 R60",
                             Example::g03_r50,
                             Example::g02_r60,
                             CornerKind::chamfer_setback,
                             {128.854934610, 50.353481620, 112.422144535, 48.474963100, 0, 0},
                             false}));

// Line-line round by the textbook formula: setback R / tan(half the inner angle), centre on
// the bisector at R / sin(half the inner angle).
TEST(CornerFormula, DafengLineLineRoundIsTheTextbookFillet) {
  const Point2 u1 = unit(kStart - kCorner);
  const Point2 u2 = unit(kEnd - kCorner);
  const double half = 0.5 * std::acos(dot(u1, u2));
  PlaneMove first = line_to(kCorner);
  PlaneMove second = line_to(kEnd);
  CornerResult r;
  ASSERT_EQ(insert_corner(kStart, first, second, CornerKind::round, 10, 0, r), std::nullopt);
  const Point2 t1 = kCorner + (10 / std::tan(half)) * u1;
  const Point2 t2 = kCorner + (10 / std::tan(half)) * u2;
  const Point2 c = kCorner + (10 / std::sin(half)) * unit(u1 + u2);
  expect_point(first.to, t1.a, t1.b, 1e-9);
  expect_point(r.corner.to, t2.a, t2.b, 1e-9);
  expect_point(r.corner.center, c.a, c.b, 1e-9);
}

// gsk D2-12 (L1388-1393): G01 Z-20 L2; G01 X40; from X0 Z0: a perpendicular corner at Z-20.
class GskPerpendicularCorner : public ::testing::Test {
 protected:
  PlaneMove first = line_to({-20, 0});
  PlaneMove second = line_to({-20, 20});
  CornerResult r;
};

TEST_F(GskPerpendicularCorner, TypeTwoChamferPointsTwoFromTheCorner) {
  ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::chamfer_setback, 2, 0, r),
            std::nullopt);
  ASSERT_TRUE(r.inserted);
  expect_point(first.to, -18, 0, 1e-12);
  expect_point(r.corner.to, -20, 2, 1e-12);
  expect_point(second.to, -20, 20, 0.0);
}

TEST_F(GskPerpendicularCorner, TypeOneChamferLineIsTwoLong) {
  ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::chamfer_length, 2, 0, r),
            std::nullopt);
  ASSERT_TRUE(r.inserted);
  expect_point(first.to, -20 + std::sqrt(2.0), 0, 1e-12);
  expect_point(r.corner.to, -20, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(length(r.corner.to - first.to), 2.0, 1e-12);
}

TEST_F(GskPerpendicularCorner, RoundThreeTouchesThreeFromTheCorner) {
  ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::round, 3, 0, r), std::nullopt);
  ASSERT_TRUE(r.inserted);
  expect_point(first.to, -17, 0, 1e-12);
  expect_point(r.corner.to, -20, 3, 1e-12);
  expect_point(r.corner.center, -17, 3, 1e-12);
  EXPECT_FALSE(r.corner.ccw);  // -Z then +X turns clockwise seen with Z right, X up
}

TEST_F(GskPerpendicularCorner, LargerThanASegmentIsAlarm1147) {
  for (CornerKind kind : {CornerKind::chamfer_setback, CornerKind::round}) {
    PlaneMove f = first;
    PlaneMove s = second;
    const PathResult e = insert_corner({0, 0}, f, s, kind, 20.5, 0, r);
    expect_does_not_fit(e, "20.500 does not fit");
    EXPECT_EQ(e->source, 4);
    EXPECT_FALSE(r.inserted);
    expect_point(f.to, -20, 0, 0.0);  // nothing changed
  }
  // Type I: the longest chamfer has its ends at (0, 0) and (-20, 20).
  PlaneMove f = first;
  PlaneMove s = second;
  EXPECT_EQ(insert_corner({0, 0}, f, s, CornerKind::chamfer_length, 20 * std::sqrt(2.0), 0, r),
            std::nullopt);
  expect_point(f.to, 0, 0, 1e-9);
  const PathResult e = insert_corner({0, 0}, first, second, CornerKind::chamfer_length, 28.3, 0, r);
  expect_does_not_fit(
      e, "chamfer length 28.300 does not fit between the moves (20.000 and 20.000 long)");
}

TEST_F(GskPerpendicularCorner, ExactlyTheSegmentFits) {
  ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::chamfer_setback, 20, 0, r),
            std::nullopt);
  expect_point(first.to, 0, 0, 1e-12);
  expect_point(r.corner.to, -20, 20, 1e-12);
}

TEST_F(GskPerpendicularCorner, SizeNotPositiveIsAlarm1147) {
  for (double size : {0.0, -2.0, std::numeric_limits<double>::quiet_NaN()}) {
    const PathResult e =
        insert_corner({0, 0}, first, second, CornerKind::chamfer_setback, size, 0, r);
    expect_does_not_fit(e, "not greater than 0");
  }
}

// gsk D2-12: two collinear lines in the same direction -> nothing inserted, nothing changed.
TEST(CornerSpecial, SameDirectionInsertsNothing) {
  PlaneMove first = line_to({-20, 0});
  PlaneMove second = line_to({-40, 0});
  CornerResult r;
  r.inserted = true;
  ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::chamfer_setback, 2, 0, r),
            std::nullopt);
  EXPECT_FALSE(r.inserted);
  expect_point(first.to, -20, 0, 0.0);
  expect_point(second.to, -40, 0, 0.0);
  // A line running on tangentially into an arc has no corner either.
  PlaneMove arc = arc_r({-20, 0}, {-30, 10}, 10, false);
  ASSERT_EQ(insert_corner({0, 0}, first, arc, CornerKind::round, 2, 0, r), std::nullopt);
  EXPECT_FALSE(r.inserted);
}

TEST(CornerAlarm, ReversalRapidAndZeroLength) {
  CornerResult r;
  PlaneMove first = line_to({-20, 0});
  PlaneMove back = line_to({-10, 0});
  PathResult e = insert_corner({0, 0}, first, back, CornerKind::chamfer_setback, 2, 0, r);
  expect_does_not_fit(e, "turns back");

  PlaneMove rapid = line_to({-20, 20});
  rapid.kind = MoveKind::rapid;
  e = insert_corner({0, 0}, first, rapid, CornerKind::chamfer_setback, 2, 0, r);
  expect_does_not_fit(e, "G01/G02/G03");

  PlaneMove still = line_to({-20, 0});
  e = insert_corner({0, 0}, first, still, CornerKind::round, 2, 0, r);
  expect_does_not_fit(e, "length 0");
}

TEST(CornerAlarm, TextNamesTheSizeAndWhatFits) {
  PlaneMove first = line_to({-20, 0});
  PlaneMove second = line_to({-20, 5});
  CornerResult r;
  const PathResult e = insert_corner({0, 0}, first, second, CornerKind::chamfer_setback, 6, 0, r);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->text,
            "chamfer 6.000 does not fit: at most 20.000 on the first move and 5.000 on "
            "the second");
}

// A round as large as the arc it would touch from the inside has its centre on the arc's
// centre: no touching point. G03 of radius 5, then a line turning left, R5.
TEST(CornerAlarm, RoundAsLargeAsTheArcInside) {
  PlaneMove first;
  first.kind = MoveKind::arc;
  first.center = {0, 0};
  first.ccw = true;
  first.to = {0, 5};  // quarter circle from (5, 0)
  PlaneMove second = line_to({-10, 4});
  CornerResult r;
  const PathResult e = insert_corner({5, 0}, first, second, CornerKind::round, 5, 0, r);
  expect_does_not_fit(e, "corner radius 5.000 does not fit");
  // A smaller round fits inside.
  first.to = {0, 5};
  EXPECT_EQ(insert_corner({5, 0}, first, second, CornerKind::round, 1, 0, r), std::nullopt);
  EXPECT_NEAR(length(first.to), 5, 1e-12);
  EXPECT_NEAR(length(r.corner.center), 4, 1e-12);
}

// Type I on a corner of inner angle theta: setback L / (2 sin(theta / 2)) on both lines.
TEST(CornerTypeOne, LineLineSetbackFormula) {
  for (double theta_deg : {30.0, 60.0, 90.0, 120.0, 150.0}) {
    const double theta = theta_deg * kPi / 180;
    const Point2 end = Point2{-20, 0} + 15.0 * Point2{std::cos(theta), std::sin(theta)};
    PlaneMove first = line_to({-20, 0});
    PlaneMove second = line_to(end);
    CornerResult r;
    ASSERT_EQ(insert_corner({0, 0}, first, second, CornerKind::chamfer_length, 3, 0, r),
              std::nullopt);
    const double setback = 3 / (2 * std::sin(theta / 2));
    expect_point(first.to, -20 + setback, 0, 1e-9);
    EXPECT_NEAR(length(r.corner.to - Point2{-20, 0}), setback, 1e-9) << theta_deg;
    EXPECT_NEAR(length(r.corner.to - first.to), 3, 1e-9) << theta_deg;
  }
}

// The chamfer takes the whole second arc: the arc left over would be a full circle, so it
// becomes a feed of length 0 to its end.
TEST(CornerDegenerate, SecondArcUsedUpBecomesAnEmptyFeed) {
  PlaneMove first = line_to({0, 0});
  PlaneMove second;
  second.kind = MoveKind::arc;
  second.center = {0, 10};
  second.ccw = true;
  second.to = {10, 10};  // quarter circle; chord sqrt(200)
  CornerResult r;
  ASSERT_EQ(
      insert_corner({0, -20}, first, second, CornerKind::chamfer_setback, std::sqrt(200.0), 0, r),
      std::nullopt);
  expect_point(r.corner.to, 10, 10, 1e-9);
  EXPECT_EQ(second.kind, MoveKind::feed);
  expect_point(second.to, 10, 10, 0.0);
}

// A full circle before the corner keeps all but the chamfered piece.
TEST(CornerDegenerate, FullCircleFirstKeepsItsRest) {
  PlaneMove first;
  first.kind = MoveKind::arc;
  first.center = {0, 0};
  first.ccw = true;
  first.to = {10, 0};
  PlaneMove second = line_to({20, 0});
  CornerResult r;
  ASSERT_EQ(insert_corner({10, 0}, first, second, CornerKind::chamfer_setback, 2, 0, r),
            std::nullopt);
  EXPECT_NEAR(length(first.to - Point2{10, 0}), 2, 1e-12);
  EXPECT_NEAR(length(first.to), 10, 1e-12);
  EXPECT_LT(first.to.b, 0);  // just before the end of a counter-clockwise turn
  EXPECT_NEAR(arc_sweep({10, 0}, first), 2 * kPi - 2 * std::asin(0.1), 1e-12);
  expect_point(r.corner.to, 12, 0, 1e-12);
}

// ---- Random corners --------------------------------------------------------------------------

struct RandomCorner {
  Point2 start;
  PlaneMove first;
  PlaneMove second;
};

Point2 polar(double r, double angle) {
  return {r * std::cos(angle), r * std::sin(angle)};
}

RandomCorner make_corner(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> len(10, 80);
  std::uniform_real_distribution<double> radius(2, 100);
  std::uniform_real_distribution<double> sweep(0.3, 1.8 * kPi);
  std::uniform_int_distribution<int> coin(0, 1);
  const Point2 corner = polar(len(rng), angle(rng));
  // An arc through the corner; `to` is `sweep` further round in its direction (backwards for
  // `behind`: the start of a first move).
  const auto arc_through_corner = [&](bool behind) {
    const double r = radius(rng);
    const double at = angle(rng);
    PlaneMove m;
    m.kind = MoveKind::arc;
    m.ccw = coin(rng) == 0;
    const double s = (m.ccw != behind ? 1.0 : -1.0) * sweep(rng);
    m.center = corner - polar(r, at);
    m.to = m.center + polar(r, at + s);
    return m;
  };
  RandomCorner c;
  if (coin(rng) == 0) {
    c.start = corner - polar(len(rng), angle(rng));
    c.first = line_to(corner);
  } else {
    c.first = arc_through_corner(true);
    c.start = c.first.to;
    c.first.to = corner;
  }
  c.second =
      coin(rng) == 0 ? line_to(corner + polar(len(rng), angle(rng))) : arc_through_corner(false);
  return c;
}

// `p` lies on the line or circle of the move `m` from `from`, within the move.
void expect_on_move(Point2 from, const PlaneMove& m, Point2 p, const char* what) {
  if (m.kind == MoveKind::arc) {
    EXPECT_NEAR(length(p - m.center), arc_radius(from, m), 1e-9) << what;
    EXPECT_TRUE(within_arc(from, m, p, 1e-7)) << what;
  } else {
    const Point2 d = m.to - from;
    EXPECT_NEAR(cross(unit(d), p - from), 0, 1e-9) << what;
    const double t = dot(p - from, d) / dot(d, d);
    EXPECT_GE(t, -1e-9) << what;
    EXPECT_LE(t, 1 + 1e-9) << what;
  }
}

void expect_same_direction(Point2 u, Point2 v, const char* what) {
  EXPECT_NEAR(u.a, v.a, 1e-9) << what;
  EXPECT_NEAR(u.b, v.b, 1e-9) << what;
}

// The piece of the move between `from` and `cut` (along the move) stays closer than `limit` to
// the corner: the chamfer point is the nearest one at that distance.
void expect_piece_within(Point2 from, const PlaneMove& m, double begin, double end, Point2 corner,
                         double limit) {
  for (int i = 1; i < 20; ++i) {
    const Point2 p = point_along(from, m, begin + (end - begin) * i / 20.0);
    EXPECT_LT(length(p - corner), limit + 1e-9);
  }
}

// Independent search for the round: walk back along the first move in small steps, put the
// circle of radius r on the turning side of it, and look for where it touches the second move.
// Returns the distance from the corner along the first move of the nearest touching point, or
// -1 when there is none.
double scan_for_round(const RandomCorner& c, double r) {
  const Point2 corner = c.first.to;
  const double side =
      cross(end_direction(c.start, c.first), start_direction(corner, c.second)) > 0 ? 1.0 : -1.0;
  const double total = move_length(c.start, c.first);
  const auto centre_at = [&](double u) {
    const Point2 p = point_along(c.start, c.first, total - u);
    const Point2 dir =
        c.first.kind == MoveKind::arc ? start_direction(p, c.first) : unit(c.first.to - c.start);
    return p + side * r * left_normal(dir);
  };
  const PlaneMove& s = c.second;
  const double r2 = s.kind == MoveKind::arc ? arc_radius(corner, s) : 0.0;
  const double k = s.ccw ? r2 - side * r : r2 + side * r;  // arcs: centre circle, signed
  const auto gap = [&](double u) {
    const Point2 centre = centre_at(u);
    if (s.kind != MoveKind::arc) {
      return side * cross(unit(s.to - corner), centre - corner) - r;
    }
    return length(centre - s.center) - std::fabs(k);
  };
  const auto touches_second = [&](Point2 centre) {
    if (s.kind != MoveKind::arc) {
      const Point2 d = s.to - corner;
      const double t = dot(centre - corner, d) / dot(d, d);
      return t >= -1e-9 && t <= 1 + 1e-9;
    }
    const Point2 touch = s.center + (k < 0 ? -r2 : r2) * unit(centre - s.center);
    return within_arc(corner, s, touch, 1e-7);
  };
  constexpr int kSteps = 4000;
  double low = 0.0;
  double g_low = gap(0.0);
  for (int i = 1; i <= kSteps; ++i) {
    const double high = total * i / kSteps;
    const double g_high = gap(high);
    if ((g_low > 0) != (g_high > 0)) {
      double a = low;
      double b = high;
      for (int n = 0; n < 100; ++n) {
        const double m = 0.5 * (a + b);
        ((gap(m) > 0) == (g_low > 0) ? a : b) = m;
      }
      if (touches_second(centre_at(a))) {
        return a;
      }
    }
    low = high;
    g_low = g_high;
  }
  return -1.0;
}

void check_random(CornerKind kind, double min_size, double max_size, int min_inserted) {
  std::mt19937 rng(kind == CornerKind::round            ? 31337
                   : kind == CornerKind::chamfer_length ? 4242
                                                        : 7);
  std::uniform_real_distribution<double> size(min_size, max_size);
  int inserted = 0;
  for (int i = 0; i < 400; ++i) {
    SCOPED_TRACE(i);
    const RandomCorner c = make_corner(rng);
    const double s = size(rng);
    PlaneMove first = c.first;
    PlaneMove second = c.second;
    CornerResult r;
    const PathResult e = insert_corner(c.start, first, second, kind, s, 0, r);
    const double scanned = kind == CornerKind::round ? scan_for_round(c, s) : -1.0;
    if (e.has_value()) {
      EXPECT_EQ(e->alarm, alarm::kCornerDoesNotFit);
      EXPECT_FALSE(r.inserted);
      EXPECT_LT(scanned, 0) << "the scan found a round";
      continue;
    }
    ASSERT_TRUE(r.inserted);
    ++inserted;
    const Point2 corner = c.first.to;
    // Both moves keep their geometry: the new ends lie on the original moves.
    expect_on_move(c.start, c.first, first.to, "first end");
    expect_on_move(corner, c.second, r.corner.to, "second start");
    EXPECT_EQ(first.kind, c.first.kind);
    expect_point(first.center, c.first.center.a, c.first.center.b, 0.0);
    expect_point(second.to, c.second.to.a, c.second.to.b, 0.0);
    expect_point(second.center, c.second.center.a, c.second.center.b, 0.0);
    if (first.kind == MoveKind::arc) {
      EXPECT_LT(std::fabs(arc_sweep(c.start, first)), std::fabs(arc_sweep(c.start, c.first)));
      EXPECT_GT(arc_sweep(c.start, first) * arc_sweep(c.start, c.first), 0);
    }
    const double cut1 = move_length(c.start, c.first) - move_length(c.start, first);
    const double cut2 = move_length(corner, c.second) - move_length(r.corner.to, second);
    EXPECT_GT(cut1, 0);
    EXPECT_GT(cut2, 0);
    const Point2 corner_start = first.to;
    if (kind == CornerKind::round) {
      ASSERT_EQ(r.corner.kind, MoveKind::arc);
      EXPECT_NEAR(cut1, scanned, 1e-6) << "not the round the scan found";
      EXPECT_EQ(r.corner.ccw,
                cross(end_direction(c.start, c.first), start_direction(corner, c.second)) > 0);
      EXPECT_NEAR(arc_radius(corner_start, r.corner), s, 1e-9);
      EXPECT_NEAR(length(r.corner.to - r.corner.center), s, 1e-9);
      expect_same_direction(end_direction(c.start, first), start_direction(corner_start, r.corner),
                            "into the round");
      expect_same_direction(end_direction(corner_start, r.corner),
                            start_direction(r.corner.to, second), "out of the round");
    } else {
      ASSERT_EQ(r.corner.kind, MoveKind::feed);
      const double d1 = length(corner_start - corner);
      const double d2 = length(r.corner.to - corner);
      if (kind == CornerKind::chamfer_setback) {
        EXPECT_NEAR(d1, s, 1e-9);
        EXPECT_NEAR(d2, s, 1e-9);
      } else {
        EXPECT_NEAR(length(r.corner.to - corner_start), s, 1e-9);
        EXPECT_NEAR(d1, d2, 1e-9);
      }
      const double l1 = move_length(c.start, c.first);
      expect_piece_within(c.start, c.first, l1 - cut1, l1, corner, d1);
      expect_piece_within(corner, c.second, 0, cut2, corner, d2);
    }
  }
  EXPECT_GE(inserted, min_inserted);
}

TEST(CornerProperty, SetbackChamfers) {
  check_random(CornerKind::chamfer_setback, 0.2, 5, 390);
}
TEST(CornerProperty, LengthChamfers) {
  check_random(CornerKind::chamfer_length, 0.2, 5, 380);
}
TEST(CornerProperty, Rounds) {
  check_random(CornerKind::round, 0.2, 5, 350);
}

}  // namespace
}  // namespace mcnc::interp::path::test
