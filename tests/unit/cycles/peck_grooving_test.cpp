// G74/G75 peck grooving: the gsk golden cases, the order and safety of the moves on generated
// cycles, and the alarms.
#include "channel/interp/cycles/peck_grooving.hpp"
#include "channel/interp/program_alarms.hpp"

#include "tests/unit/cycles/cycle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::interp::cycles::test {
namespace {

using path::MoveKind;
using path::PlanePath;
using path::Point2;

// gsk D2-27 (L1508-1510): from X0 Z2, G74 R1; G74 Z-20 Q5000 F0.1; (Q in microns).
TEST(PeckGrooving, GskD2_27CentreDrilling) {
  const PeckGrooving c{
      .axis = PeckAxis::a, .end = {-20.0, 0.0}, .peck = 5.0, .retract = 1.0, .feed = 0.1};
  PlanePath out;
  ASSERT_FALSE(expand_peck_grooving({2.0, 0.0}, c, out));
  // Feeds 2 -> -3, -2 -> -8, -7 -> -13, -12 -> -18, -17 -> -20, a 1 mm retract between them,
  // then back to Z2 (which is A: X is already there).
  const double stops[] = {-3, -2, -8, -7, -13, -12, -18, -17, -20, 2};
  ASSERT_EQ(out.size(), 10u);
  for (std::size_t i = 0; i < out.size(); ++i) {
    expect_move(out[i], i % 2 == 0 && i < 9 ? MoveKind::feed : MoveKind::rapid, stops[i], 0.0);
  }
  EXPECT_DOUBLE_EQ(out[0].feed, 0.1);
}

// gsk D2-28 (L1511-1514): from X52 Z-10, G75 R0.5; G75 X40 Z-20 P3000 Q4000 F0.05; with P
// taken as a radius amount (3 mm), as the caller converts it.
TEST(PeckGrooving, GskD2_28FourGroovesOfTwoPecks) {
  const PeckGrooving c{.axis = PeckAxis::b,
                       .end = {-20.0, 20.0},
                       .peck = 3.0,
                       .step = 4.0,
                       .retract = 0.5,
                       .feed = 0.05};
  const Point2 start{-10.0, 26.0};
  PlanePath out;
  ASSERT_FALSE(expand_peck_grooving(start, c, out));
  ASSERT_EQ(out.size(), 4u + 3u * 5u + 1u);
  std::size_t i = 0;
  for (double z : {-10.0, -14.0, -18.0, -20.0}) {
    if (z != -10.0) {
      expect_move(out[i++], MoveKind::rapid, z, 26.0);  // step along Z at the start diameter
    }
    expect_move(out[i++], MoveKind::feed, z, 23.0);   // X46
    expect_move(out[i++], MoveKind::rapid, z, 23.5);  // back 0.5
    expect_move(out[i++], MoveKind::feed, z, 20.0);   // X40: the bottom
    expect_move(out[i++], MoveKind::rapid, z, 26.0);  // out to X52
  }
  expect_move(out[i], MoveKind::rapid, -10.0, 26.0);
}

TEST(PeckGrooving, GskD2_28WithDiameterPecksHasFourPecksPerGroove) {
  // The other reading of P3000 (a diameter amount: 1.5 mm of radius).
  const PeckGrooving c{
      .axis = PeckAxis::b, .end = {-20.0, 20.0}, .peck = 1.5, .step = 4.0, .retract = 0.5};
  PlanePath out;
  ASSERT_FALSE(expand_peck_grooving({-10.0, 26.0}, c, out));
  int feeds = 0;
  for (const path::PlaneMove& m : out) {
    feeds += m.kind == MoveKind::feed ? 1 : 0;
  }
  EXPECT_EQ(feeds, 4 * 4);
}

TEST(PeckGrooving, FaceGroovesReliefAwayFromTheNextGroove) {
  // G74 from X20 Z1 to X30 Z-5: grooves at X20, X26 (P6 diameter) and X30 (radius 10, 13, 15),
  // relief 0.5 towards smaller X.
  const PeckGrooving c{.axis = PeckAxis::a,
                       .end = {-5.0, 15.0},
                       .peck = 0.0,
                       .step = 3.0,
                       .relief = 0.5,
                       .retract = 1.0};
  PlanePath out;
  ASSERT_FALSE(expand_peck_grooving({1.0, 10.0}, c, out));
  ASSERT_EQ(out.size(), 3u * 3u + 2u + 1u);
  std::size_t i = 0;
  for (double x : {10.0, 13.0, 15.0}) {
    if (x != 10.0) {
      expect_move(out[i++], MoveKind::rapid, 1.0, x);
    }
    expect_move(out[i++], MoveKind::feed, -5.0, x);         // Q omitted: one feed to the bottom
    expect_move(out[i++], MoveKind::rapid, -5.0, x - 0.5);  // relief
    expect_move(out[i++], MoveKind::rapid, 1.0, x - 0.5);   // out to the start Z
  }
  expect_move(out[i], MoveKind::rapid, 1.0, 10.0);
}

TEST(PeckGrooving, RetractStopsAtTheStartLevel) {
  const PeckGrooving c{.axis = PeckAxis::a, .end = {-10.0, 5.0}, .peck = 2.0, .retract = 3.0};
  PlanePath out;
  ASSERT_FALSE(expand_peck_grooving({0.0, 5.0}, c, out));
  ASSERT_GE(out.size(), 3u);
  expect_move(out[0], MoveKind::feed, -2.0, 5.0);
  expect_move(out[1], MoveKind::rapid, 0.0, 5.0);  // 3 asked, 2 possible
  expect_move(out[2], MoveKind::feed, -4.0, 5.0);
  expect_move(out[3], MoveKind::rapid, -1.0, 5.0);
}

TEST(PeckGrooving, AppendsToThePath) {
  PlanePath out(2);
  const PeckGrooving c{.axis = PeckAxis::a, .end = {-4.0, 0.0}};
  ASSERT_FALSE(expand_peck_grooving({0.0, 0.0}, c, out));
  ASSERT_EQ(out.size(), 4u);
  expect_move(out[2], MoveKind::feed, -4.0, 0.0);
  expect_move(out[3], MoveKind::rapid, 0.0, 0.0);
}

// Generated cycles: groove positions, peck depths, retracts, and no rapid into uncut material.
TEST(PeckGrooving, PropertiesOfGeneratedCycles) {
  Uniform uniform(74075);
  for (int n = 0; n < 400; ++n) {
    SCOPED_TRACE(n);
    PeckGrooving c;
    c.axis = uniform.chance(0.5) ? PeckAxis::a : PeckAxis::b;
    const Point2 start{uniform(-20.0, 20.0), uniform(0.0, 30.0)};
    c.end = {start.a + uniform(-15.0, 15.0), start.b + uniform(-15.0, 15.0)};
    if (uniform.chance(0.2)) {  // a single groove
      (c.axis == PeckAxis::a ? c.end.b : c.end.a) = c.axis == PeckAxis::a ? start.b : start.a;
    }
    c.peck = uniform.chance(0.2) ? 0.0 : uniform(0.5, 6.0);
    c.step = uniform(0.5, 5.0);
    c.relief = uniform.chance(0.5) ? 0.0 : uniform(0.1, 0.4);
    c.retract = uniform.chance(0.2) ? 0.0 : uniform(0.1, 2.0);
    c.feed = uniform(0.01, 0.3);
    auto peck_of = [&c](Point2 p) { return c.axis == PeckAxis::a ? p.a : p.b; };
    auto step_of = [&c](Point2 p) { return c.axis == PeckAxis::a ? p.b : p.a; };
    const double depth = std::fabs(peck_of(c.end) - peck_of(start));
    const double span = std::fabs(step_of(c.end) - step_of(start));
    const double pdir = peck_of(c.end) < peck_of(start) ? -1.0 : 1.0;
    const double sdir = step_of(c.end) < step_of(start) ? -1.0 : 1.0;
    const int grooves = span > 0.0 ? static_cast<int>(std::ceil(span / c.step)) + 1 : 1;
    const int pecks = c.peck > 0.0 ? static_cast<int>(std::ceil(depth / c.peck)) : 1;

    PlanePath out;
    ASSERT_FALSE(expand_peck_grooving(start, c, out));
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.back().kind, MoveKind::rapid);
    EXPECT_NEAR(out.back().to.a, start.a, 1e-12);
    EXPECT_NEAR(out.back().to.b, start.b, 1e-12);

    Point2 at = start;
    int groove = -1;
    int peck_in_groove = 0;
    double reached = 0.0;  // depth cut in the current groove
    double groove_at = 0.0;
    for (const path::PlaneMove& m : out) {
      ASSERT_GT(std::hypot(m.to.a - at.a, m.to.b - at.b), 1e-9) << "zero-length move";
      const double from_depth = pdir * (peck_of(at) - peck_of(start));
      const double to_depth = pdir * (peck_of(m.to) - peck_of(start));
      if (m.kind == MoveKind::feed) {
        EXPECT_DOUBLE_EQ(m.feed, c.feed);
        EXPECT_NEAR(step_of(m.to), step_of(at), 1e-12) << "feeds go along the peck axis only";
        if (groove < 0 || reached >= depth - 1e-9) {  // a new groove, from the start level
          EXPECT_NEAR(from_depth, 0.0, 1e-9);
          ++groove;
          peck_in_groove = 0;
          reached = 0.0;
          groove_at = step_of(m.to);
          const double expected_at =
              groove + 1 == grooves ? step_of(c.end) : step_of(start) + sdir * groove * c.step;
          EXPECT_NEAR(groove_at, expected_at, 1e-9);
        }
        ++peck_in_groove;
        EXPECT_GT(to_depth, from_depth);
        const double expected = peck_in_groove == pecks ? depth : peck_in_groove * c.peck;
        EXPECT_NEAR(to_depth, expected, 1e-9);
        if (peck_in_groove > 1) {  // each feed starts where the retract left it
          EXPECT_NEAR(from_depth, reached - std::min(c.retract, reached), 1e-9);
        }
        reached = to_depth;
      } else {
        EXPECT_EQ(m.kind, MoveKind::rapid);
        // A rapid never goes deeper than what was cut, and moves sideways only at the start
        // level or, by the relief, at the bottom.
        EXPECT_LE(to_depth, reached + 1e-9);
        if (std::fabs(step_of(m.to) - step_of(at)) > 1e-12) {
          const bool at_start_level = std::fabs(from_depth) < 1e-9 && std::fabs(to_depth) < 1e-9;
          const bool relief = std::fabs(from_depth - depth) < 1e-9 &&
                              std::fabs(to_depth - depth) < 1e-9 &&
                              std::fabs(step_of(m.to) - (groove_at - sdir * c.relief)) < 1e-9;
          EXPECT_TRUE(at_start_level || relief);
        }
      }
      at = m.to;
    }
    EXPECT_EQ(groove + 1, depth > 1e-9 ? grooves : 0);
  }
}

struct AlarmCase {
  const char* what;
  PeckGrooving cycle;
  int alarm;
};

class PeckGroovingAlarm : public ::testing::TestWithParam<AlarmCase> {};

TEST_P(PeckGroovingAlarm, RefusesWithoutMoves) {
  PlanePath out;
  const path::PathResult r = expand_peck_grooving({0.0, 10.0}, GetParam().cycle, out);
  ASSERT_TRUE(r) << GetParam().what;
  EXPECT_EQ(r->alarm, GetParam().alarm) << r->text;
  EXPECT_EQ(r->source, -1);
  EXPECT_TRUE(out.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Values, PeckGroovingAlarm,
    ::testing::Values(AlarmCase{"G74 X without P",
                                {.axis = PeckAxis::a, .end = {-5.0, 15.0}, .peck = 1.0},
                                alarm::kCycleWordMissing},
                      AlarmCase{"G75 Z without Q",
                                {.axis = PeckAxis::b, .end = {-5.0, 5.0}, .peck = 1.0},
                                alarm::kCycleWordMissing},
                      AlarmCase{"negative peck",
                                {.axis = PeckAxis::a, .end = {-5.0, 10.0}, .peck = -1.0},
                                alarm::kCycleValue},
                      AlarmCase{"negative step",
                                {.axis = PeckAxis::b, .end = {0.0, 5.0}, .step = -1.0},
                                alarm::kCycleValue},
                      AlarmCase{"negative relief",
                                {.axis = PeckAxis::a, .end = {-5.0, 10.0}, .relief = -0.1},
                                alarm::kCycleValue},
                      AlarmCase{"negative retract",
                                {.axis = PeckAxis::b, .end = {0.0, 5.0}, .retract = -0.1},
                                alarm::kCycleValue},
                      AlarmCase{"too many pecks",
                                {.axis = PeckAxis::a, .end = {-500.0, 10.0}, .peck = 0.001},
                                alarm::kCycleValue}));

}  // namespace
}  // namespace mcnc::interp::cycles::test
