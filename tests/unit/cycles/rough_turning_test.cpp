// G71/G72 stock removal and G73 pattern repeating (spec dafeng §2.5 L1480-1708, gsk A.6.30,
// D2-24..D2-26): goldens, alarms and properties on seeded random contours.
#include "channel/interp/cycles/rough_turning.hpp"
#include "channel/interp/cycles/pattern_repeat.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"
#include "tests/unit/cycles/cycle_test_support.hpp"

#include <cmath>
#include <vector>

namespace mcnc::interp::cycles::test {
namespace {

using path::MoveKind;
using path::PlaneMove;
using path::PlanePath;
using path::Point2;

PlaneMove mv(MoveKind kind, double a, double b) {
  PlaneMove m;
  m.kind = kind;
  m.to = {a, b};
  return m;
}

PlaneMove arc(double a, double b, double ca, double cb, bool ccw) {
  PlaneMove m = mv(MoveKind::arc, a, b);
  m.center = {ca, cb};
  m.ccw = ccw;
  return m;
}

// gsk D2-24 (L1496-1511): from (X102, Z2), U2 R1, contour X80 / Z-30 / X100: cuts at X98, 94,
// 90, 86, 82 (radius 49..41) from Z2 to Z-30, 45-degree retracts of 1, then B' and the contour.
TEST(RoughTurning, GskD2_24FivePassesAndTheContour) {
  const PlanePath contour{mv(MoveKind::rapid, 2, 40), mv(MoveKind::feed, -30, 40),
                          mv(MoveKind::feed, -30, 50)};
  RoughingParams p;
  p.depth = 2;
  p.retract = 1;
  p.feed = 0.2;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({2, 51}, contour, p, out));
  std::vector<double> cut_levels;
  for (std::size_t i = 1; i < out.size(); ++i) {
    const PlaneMove& m = out[i];
    if (m.kind == MoveKind::feed && std::fabs(m.to.b - out[i - 1].to.b) < 1e-12 &&
        m.to.a < out[i - 1].to.a - 1.0) {
      cut_levels.push_back(m.to.b);
      EXPECT_NEAR(m.to.a, -30, 1e-9);
    }
  }
  // The five roughing cuts, then the contour's Z cut at X80.
  ASSERT_EQ(cut_levels.size(), 6u);
  const double want[] = {49, 47, 45, 43, 41, 40};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(cut_levels[i], want[i], 1e-9);
  }
  expect_move(out[0], MoveKind::rapid, 2, 49);   // infeed at rapid: the first block is G00
  expect_move(out[2], MoveKind::feed, -29, 50);  // the 45-degree retract
  expect_move(out[3], MoveKind::rapid, 2, 50);
  expect_move(out.back(), MoveKind::rapid, 2, 51);
  expect_move(out[out.size() - 2], MoveKind::feed, -30, 50);
}

// Dafeng L1544-1568: G71 U7 R3; P10 Q20 U4 W1 from X160 Z10. The roughing contour is the
// finishing contour moved by (W1, U4/2 = 2); A' = (Z11, X82); levels 75, 68, ... 26 (radius),
// the next (19) would pass B' (X22): 8 passes, then the contour pass.
TEST(RoughTurning, DafengExampleLevels) {
  const PlanePath contour{mv(MoveKind::rapid, 10, 20), mv(MoveKind::feed, -30, 20),
                          mv(MoveKind::feed, -60, 30), mv(MoveKind::feed, -80, 30),
                          mv(MoveKind::feed, -90, 50), mv(MoveKind::feed, -110, 50),
                          mv(MoveKind::feed, -130, 70)};
  RoughingParams p;
  p.depth = 7;
  p.retract = 3;
  p.allowance_a = 1;
  p.allowance_b = 2;
  p.feed = 300;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({10, 80}, contour, p, out));
  expect_move(out[0], MoveKind::rapid, 11, 82);
  std::vector<std::pair<double, double>> cuts;  // (level, end)
  for (std::size_t i = 1; i + contour.size() < out.size(); ++i) {
    const PlaneMove& m = out[i];
    if (m.kind == MoveKind::feed && std::fabs(m.to.b - out[i - 1].to.b) < 1e-12 &&
        std::fabs(out[i - 1].to.a - 11) < 1e-12) {
      cuts.emplace_back(m.to.b, m.to.a);
    }
  }
  ASSERT_EQ(cuts.size(), 8u);
  // Each cut ends on the roughing contour: X75 beyond its end (Z-129), X47 on the taper
  // from (Z-79, X32) to (Z-89, X52): Z = -79 - 10 * 15/20 = -86.5.
  EXPECT_NEAR(cuts[0].first, 75, 1e-9);
  EXPECT_NEAR(cuts[0].second, -129, 1e-9);
  EXPECT_NEAR(cuts[4].first, 47, 1e-9);
  EXPECT_NEAR(cuts[4].second, -86.5, 1e-9);
  EXPECT_NEAR(cuts[7].first, 26, 1e-9);
  EXPECT_NEAR(cuts[7].second, -41, 1e-9);
}

// G72 (dafeng L1633-1655): facing passes along X, stepping in Z by W7 from Z2 (+W2).
TEST(RoughTurning, G72FacesAlongX) {
  const PlanePath contour{mv(MoveKind::rapid, -70, 88), mv(MoveKind::feed, -70, 80),
                          mv(MoveKind::feed, -60, 60),  arc(-40, 40, -40, 60, true),
                          mv(MoveKind::feed, -20, 40),  mv(MoveKind::feed, 0, 20)};
  RoughingParams p;
  p.axis = RoughingAxis::b;
  p.depth = 7;
  p.retract = 2;
  p.allowance_a = 2;
  p.allowance_b = 2;
  p.feed = 300;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({2, 88}, contour, p, out));
  // Passes at Z -3, -10, ... -66: each a feed along X at a constant Z from X90 inwards.
  int passes = 0;
  for (std::size_t i = 1; i + contour.size() < out.size(); ++i) {
    if (out[i].kind == MoveKind::feed && std::fabs(out[i].to.a - out[i - 1].to.a) < 1e-12 &&
        std::fabs(out[i - 1].to.b - 90) < 1e-12) {
      EXPECT_NEAR(out[i].to.a, -3 - 7 * passes, 1e-9);
      ++passes;
    }
  }
  EXPECT_EQ(passes, 10);
  // The cut at Z-45 ends on the arc moved by the allowance: centre (-38, 62), radius 20.
  bool on_arc = false;
  for (const PlaneMove& m : out) {
    if (m.kind == MoveKind::feed && std::fabs(m.to.a + 45) < 1e-12 && m.to.b < 89) {
      EXPECT_NEAR(std::hypot(m.to.a + 38, m.to.b - 62), 20, 1e-9);
      on_arc = true;
      break;
    }
  }
  EXPECT_TRUE(on_arc);
}

TEST(RoughTurning, TypeTwoCutsThePocket) {
  // An OD contour with a groove: X30 to Z-10, down to X20 to Z-20, up to X30 to Z-30, X40.
  const PlanePath contour{mv(MoveKind::rapid, 2, 15),  mv(MoveKind::feed, -10, 15),
                          mv(MoveKind::feed, -12, 10), mv(MoveKind::feed, -20, 10),
                          mv(MoveKind::feed, -22, 15), mv(MoveKind::feed, -30, 15),
                          mv(MoveKind::feed, -30, 20)};
  RoughingParams p;
  p.depth = 1;
  p.retract = 0.5;
  p.feed = 0.2;
  p.type2 = true;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({2, 21}, contour, p, out));
  // Somewhere a feed at X 11-14 (radius) runs between Z-12 and Z-20: the groove is cut.
  bool groove = false;
  for (std::size_t i = 1; i < out.size(); ++i) {
    const PlaneMove& m = out[i];
    groove = groove || (m.kind == MoveKind::feed && m.to.b > 10.5 && m.to.b < 14.5 &&
                        std::fabs(m.to.b - out[i - 1].to.b) < 1e-12 && m.to.a < -15);
  }
  EXPECT_TRUE(groove);
  // Type I refuses the same contour: it goes back in X.
  p.type2 = false;
  out.clear();
  const auto e = expand_rough_turning({2, 21}, contour, p, out);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->alarm, alarm::kContourNotMonotonic);
}

// A pocket narrower than the retract: the 45-degree lift must not reach behind the pocket's
// entry wall into the part.
TEST(RoughTurning, NarrowPocketRetractStaysInThePocket) {
  const PlanePath contour{mv(MoveKind::rapid, 2, 22),    mv(MoveKind::feed, -10, 22),
                          mv(MoveKind::feed, -10, 19),   mv(MoveKind::feed, -10.5, 19),
                          mv(MoveKind::feed, -10.5, 22), mv(MoveKind::feed, -20, 22),
                          mv(MoveKind::feed, -20, 25)};
  RoughingParams p;
  p.depth = 1;
  p.retract = 1;
  p.feed = 0.2;
  p.type2 = true;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({2, 26}, contour, p, out));
  auto surface = [](double c) { return c < -10 + 1e-9 && c > -10.5 - 1e-9 ? 19.0 : 22.0; };
  Point2 from{2, 26};
  bool pocket_cut = false;
  for (const PlaneMove& m : out) {
    for (int k = 1; k <= 20; ++k) {
      const Point2 q = from + (k / 20.0) * (m.to - from);
      if (q.a > -20 && q.a < 2) {
        EXPECT_GE(q.b, surface(q.a) - 1e-9) << "(" << q.a << ", " << q.b << ") inside the part";
      }
    }
    pocket_cut = pocket_cut || (m.kind == MoveKind::feed && std::fabs(m.to.b - 19) < 1e-9 &&
                                std::fabs(m.to.a + 10.5) < 1e-9);
    from = m.to;
  }
  EXPECT_TRUE(pocket_cut);
  for (std::size_t i = 1; i < out.size(); ++i) {
    EXPECT_FALSE(path::same_point(out[i - 1].to, out[i].to)) << "a move that goes nowhere at " << i;
  }
}

// J1: the retract follows a taper up to the lifted level instead of backing off at 45 degrees.
TEST(RoughTurning, RetractAlongTheContourFollowsATaper) {
  const PlanePath contour{mv(MoveKind::rapid, 2, 10), mv(MoveKind::feed, -10, 10),
                          mv(MoveKind::feed, -20, 20), mv(MoveKind::feed, -30, 20)};
  RoughingParams p;
  p.depth = 1;
  p.retract = 1;
  p.feed = 0.2;
  p.retract_along_contour = true;
  PlanePath out;
  ASSERT_FALSE(expand_rough_turning({2, 25}, contour, p, out));
  bool along = false;
  for (std::size_t i = 1; i < out.size(); ++i) {
    along = along ||
            (path::same_point(out[i - 1].to, {-19, 19}) && path::same_point(out[i].to, {-20, 20}));
  }
  EXPECT_TRUE(along);
}

TEST(RoughTurning, Alarms) {
  RoughingParams p;
  p.depth = 1;
  p.feed = 1;
  PlanePath out;
  const PlanePath good{mv(MoveKind::rapid, 2, 10), mv(MoveKind::feed, -10, 10)};
  EXPECT_EQ(expand_rough_turning({2, 20}, {mv(MoveKind::rapid, 2, 10)}, p, out)->alarm,
            alarm::kContourMissing);
  EXPECT_EQ(
      expand_rough_turning({2, 20}, {arc(0, 10, 0, 0, true), mv(MoveKind::feed, -10, 10)}, p, out)
          ->alarm,
      alarm::kContourStart);
  RoughingParams shallow = p;
  shallow.depth = 0;
  EXPECT_EQ(expand_rough_turning({2, 20}, good, shallow, out)->alarm, alarm::kCycleValue);
  RoughingParams few = p;
  few.max_elements = 1;
  EXPECT_EQ(expand_rough_turning({2, 20}, good, few, out)->alarm, alarm::kContourTooLong);
  // The start inside the stock: the contour reaches beyond the start's X.
  const PlanePath high{mv(MoveKind::rapid, 2, 10), mv(MoveKind::feed, -10, 30)};
  EXPECT_EQ(expand_rough_turning({2, 20}, high, p, out)->alarm, alarm::kCycleValue);
  // Back along Z.
  const PlanePath back{mv(MoveKind::rapid, 2, 10), mv(MoveKind::feed, -10, 10),
                       mv(MoveKind::feed, -5, 12)};
  const auto e = expand_rough_turning({2, 20}, back, p, out);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->alarm, alarm::kContourNotMonotonic);
  EXPECT_EQ(e->source, 2);
}

// Random monotonic OD contours of lines and arcs: every roughing cut stays on the stock side
// of the roughing contour and ends on it; the last pass is the contour moved by the allowance.
TEST(RoughTurning, PropertiesOnRandomContours) {
  Uniform u(71);
  for (int n = 0; n < 300; ++n) {
    const bool g72 = u.chance(0.5);
    PlanePath contour;
    // Built for G71 in (c, s) = (a, b); for G72 mirrored onto (b, a).
    double c = 0.0;
    double s = u(5, 15);
    std::vector<std::pair<double, double>> pts{{c, s}};
    const int count = 2 + u.below(8);
    for (int i = 0; i < count; ++i) {
      c -= u(1, 8);
      s += u.chance(0.3) ? 0.0 : u(0, 6);
      pts.emplace_back(c, s);
    }
    auto at = [&](double cc, double ss) { return g72 ? Point2{ss, cc} : Point2{cc, ss}; };
    contour.push_back(
        mv(MoveKind::rapid, at(pts[0].first, pts[0].second).a, at(pts[0].first, pts[0].second).b));
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const Point2 q = at(pts[i].first, pts[i].second);
      contour.push_back(mv(MoveKind::feed, q.a, q.b));
    }
    RoughingParams p;
    p.axis = g72 ? RoughingAxis::b : RoughingAxis::a;
    p.depth = u(0.3, 2.0);
    p.retract = u(0, 0.5);
    p.allowance_a = u(0, 0.3);
    p.allowance_b = u(0, 0.3);
    p.feed = 1;
    const double top = pts.back().second + u(1, 10);
    const Point2 start = at(2.0, top);
    PlanePath out;
    const auto e = expand_rough_turning(start, contour, p, out);
    ASSERT_FALSE(e) << n << ": " << e->text;
    const Point2 shift{p.allowance_a, p.allowance_b};
    const double shift_c = g72 ? shift.b : shift.a;
    const double shift_s = g72 ? shift.a : shift.b;
    // s of the roughing contour as a function of c (monotonic, piecewise linear).
    auto rough_s = [&](double cc) {
      for (std::size_t i = 1; i < pts.size(); ++i) {
        const double c0 = pts[i - 1].first + shift_c;
        const double c1 = pts[i].first + shift_c;
        if (cc <= c0 + 1e-12 && cc >= c1 - 1e-12) {
          const double t = c0 == c1 ? 1.0 : (cc - c0) / (c1 - c0);
          return pts[i - 1].second + shift_s + t * (pts[i].second - pts[i - 1].second);
        }
      }
      return -1e9;  // beyond the contour's end: no part there
    };
    auto c_of = [&](Point2 q) { return g72 ? q.b : q.a; };
    auto s_of = [&](Point2 q) { return g72 ? q.a : q.b; };
    const std::size_t finish = out.size() - 1 - (contour.size() - 1);
    for (std::size_t i = 1; i < finish; ++i) {
      const PlaneMove& m = out[i];
      if (m.kind != MoveKind::feed) {
        continue;
      }
      for (int k = 0; k <= 10; ++k) {
        const Point2 q = out[i - 1].to + (k / 10.0) * (m.to - out[i - 1].to);
        EXPECT_GE(s_of(q), rough_s(c_of(q)) - 1e-7) << "case " << n << " move " << i << " gouges";
      }
    }
    for (std::size_t i = 1; i < contour.size(); ++i) {
      const PlaneMove& m = out[finish + i - 1];
      EXPECT_NEAR(m.to.a, contour[i].to.a + shift.a, 1e-9) << n;
      EXPECT_NEAR(m.to.b, contour[i].to.b + shift.b, 1e-9) << n;
    }
    expect_move(out.back(), MoveKind::rapid, start.a, start.b);
    // Pass levels: from A' by exactly the depth.
    double last_level = s_of(start) + shift_s;
    for (std::size_t i = 1; i < finish; ++i) {
      if (out[i].kind == MoveKind::feed &&
          std::fabs(s_of(out[i].to) - s_of(out[i - 1].to)) < 1e-12 &&
          std::fabs(c_of(out[i - 1].to) - (c_of(start) + shift_c)) < 1e-12) {
        EXPECT_NEAR(last_level - s_of(out[i].to), p.depth, 1e-9) << n;
        last_level = s_of(out[i].to);
      }
    }
  }
}

// gsk D2-26: G73 U3 W0 R3: three passes 3, 1.5 and 0 off the contour, then back to A.
TEST(PatternRepeat, GskD2_26ThreePasses) {
  const PlanePath contour{mv(MoveKind::rapid, 2, 40), mv(MoveKind::feed, -30, 40),
                          mv(MoveKind::feed, -30, 50)};
  PatternParams p;
  p.relief_b = 3;
  p.passes = 3;
  p.feed = 0.2;
  PlanePath out;
  ASSERT_FALSE(expand_pattern_repeat({10, 60}, contour, p, out));
  ASSERT_EQ(out.size(), 3u * 4u + 1u);
  expect_move(out[0], MoveKind::rapid, 10, 63);
  expect_move(out[1], MoveKind::rapid, 2, 43);
  expect_move(out[2], MoveKind::feed, -30, 43);
  expect_move(out[5], MoveKind::rapid, 2, 41.5);
  expect_move(out[9], MoveKind::rapid, 2, 40);
  expect_move(out[11], MoveKind::feed, -30, 50);
  expect_move(out[12], MoveKind::rapid, 10, 60);
}

TEST(PatternRepeat, Alarms) {
  PatternParams p;
  PlanePath out;
  EXPECT_EQ(expand_pattern_repeat({0, 0}, {}, p, out)->alarm, alarm::kContourMissing);
  p.passes = 0;
  EXPECT_EQ(expand_pattern_repeat({0, 0}, {mv(MoveKind::rapid, 1, 1)}, p, out)->alarm,
            alarm::kCycleValue);
}

}  // namespace
}  // namespace mcnc::interp::cycles::test
