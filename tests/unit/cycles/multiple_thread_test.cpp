// G76 multiple thread cutting: the pass depths of the spec examples, the geometry of each pass
// on generated cycles, and the alarms.
#include "channel/interp/cycles/multiple_thread.hpp"
#include "channel/interp/path/plane_geometry.hpp"
#include "channel/interp/program_alarms.hpp"

#include "tests/unit/cycles/cycle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::interp::cycles::test {
namespace {

using path::MoveKind;
using path::PlaneMove;
using path::PlanePath;
using path::Point2;

constexpr double kEps = 1e-9;

double flank_tan(double angle) {
  return std::tan(angle * path::kPi / 360.0);
}

// dafeng §7 item 15 (spec L2344; manual L1829-1835): G00 X68 Z50; G76 P010060 R0.2;
// G76 X60.4 Z25 P3.68 Q1.8 F6. Q(dmin) is a parameter there (5030): 0.1 here, never reached.
MultipleThread dafeng_example() {
  return MultipleThread{.end = {25.0, 30.2},
                        .height = 3.68,
                        .first_depth = 1.8,
                        .min_depth = 0.1,
                        .finish_allowance = 0.2,
                        .finish_passes = 1,
                        .chamfer = 0.0,
                        .tool_angle = 60.0,
                        .lead = 6.0};
}

TEST(MultipleThread, DafengExampleDepthsSqrtLaw) {
  const std::vector<double> d = thread_pass_depths(dafeng_example());
  ASSERT_EQ(d.size(), 4u);
  EXPECT_NEAR(d[0], 1.8, kEps);
  EXPECT_NEAR(d[1], 2.545584412, 1e-9);  // 1.8 * sqrt(2)
  EXPECT_NEAR(d[2], 3.117691454, 1e-9);  // 1.8 * sqrt(3)
  EXPECT_NEAR(d[3], 3.48, kEps);         // 1.8 * 2 = 3.6 capped at 3.68 - 0.2
}

TEST(MultipleThread, DafengExamplePathEndsAtTheMinorDiameter) {
  const Point2 start{50.0, 34.0};  // X68 Z50
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread(start, dafeng_example(), out));
  ASSERT_EQ(out.size(), 5u * 4u);  // 4 roughing + 1 finishing pass, no chamfer
  const double t = flank_tan(60.0);
  const double crest = 30.2 + 3.68;  // radius at the crest: X67.76
  const double depths[] = {1.8, 1.8 * std::sqrt(2.0), 1.8 * std::sqrt(3.0), 3.48, 3.68};
  for (int p = 0; p < 5; ++p) {
    const PlaneMove* m = &out[static_cast<std::size_t>(4 * p)];
    // Infeed along the flank: Z moves towards the chuck by depth * tan 30.
    expect_move(m[0], MoveKind::rapid, 50.0 - depths[p] * t, crest - depths[p]);
    expect_move(m[1], MoveKind::thread, 25.0, crest - depths[p]);
    EXPECT_DOUBLE_EQ(m[1].lead, 6.0);
    expect_move(m[2], MoveKind::rapid, 25.0, 34.0);
    expect_move(m[3], MoveKind::rapid, 50.0, 34.0);
  }
  // The finishing pass cuts the root: X60.4.
  EXPECT_NEAR(out[17].to.b * 2.0, 60.4, 1e-9);
}

// gsk D2-29 (L1515-1521): G76 P021060 Q100 R0.1; G76 X27.6 Z-30 P1200 Q400 F2; from X32 Z3.
MultipleThread gsk_example() {
  return MultipleThread{.end = {-30.0, 13.8},
                        .height = 1.2,
                        .first_depth = 0.4,
                        .min_depth = 0.1,
                        .finish_allowance = 0.1,
                        .finish_passes = 2,
                        .chamfer = 1.0 * 2.0,  // r = 10: 10 * 0.1 * lead
                        .tool_angle = 60.0,
                        .lead = 2.0};
}

TEST(MultipleThread, GskD2_29DepthsWithMinimumIncrement) {
  const std::vector<double> d = thread_pass_depths(gsk_example());
  // 0.4 sqrt(n) until the increment falls below 0.1, then steps of 0.1, ending at 1.2 - 0.1.
  const double expected[] = {0.4, 0.4 * std::sqrt(2.0), 0.4 * std::sqrt(3.0), 0.8, 0.9, 1.0, 1.1};
  ASSERT_EQ(d.size(), 7u);
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(d[i], expected[i], 1e-9) << "pass " << i + 1;
  }
}

TEST(MultipleThread, GskD2_29TwoFinishingPassesWithChamfer) {
  const Point2 start{3.0, 16.0};
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread(start, gsk_example(), out));
  ASSERT_EQ(out.size(), 9u * 5u);  // 7 roughing + 2 finishing, chamfer on
  const double t = flank_tan(60.0);
  // Roughing ends at depth 1.1 (X 13.9 radius at the chamfer start).
  const PlaneMove* last_rough = &out[6 * 5];
  expect_move(last_rough[1], MoveKind::thread, -28.0, 13.9);
  for (int f = 7; f < 9; ++f) {
    const PlaneMove* m = &out[static_cast<std::size_t>(5 * f)];
    expect_move(m[0], MoveKind::rapid, 3.0 - 1.2 * t, 13.8);
    expect_move(m[1], MoveKind::thread, -28.0, 13.8);  // at the root, up to the chamfer
    expect_move(m[2], MoveKind::thread, -30.0, 15.8);  // 45 degrees out over 2 mm
    EXPECT_DOUBLE_EQ(m[2].lead, 2.0);
    expect_move(m[3], MoveKind::rapid, -30.0, 16.0);
    expect_move(m[4], MoveKind::rapid, 3.0, 16.0);
  }
}

TEST(MultipleThread, FirstDepthBeyondTheRoughingDepthIsOnePass) {
  MultipleThread c = gsk_example();
  c.first_depth = 1.15;  // > 1.2 - 0.1, <= 1.2
  const std::vector<double> d = thread_pass_depths(c);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(d[0], 1.1, kEps);
}

TEST(MultipleThread, TaperedInsideThreadFollowsTheRootLine) {
  // Inside thread from Z2 to Z-20, root X30 at the end and X29 at the start, start at X26.
  MultipleThread c{.end = {-20.0, 15.0},
                   .taper = -0.5,
                   .height = 1.0,
                   .first_depth = 0.5,
                   .finish_allowance = 0.0,
                   .tool_angle = 0.0,
                   .lead = 1.5,
                   .infeed = ThreadInfeed::radial};
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({2.0, 13.0}, c, out));
  // Depths 0.5, 0.707, 0.866, 1.0, then the finishing pass at 1.0.
  ASSERT_EQ(out.size(), 5u * 4u);
  const PlaneMove* fin = &out[16];
  expect_move(fin[0], MoveKind::rapid, 2.0, 14.5);  // root at the start: 15 - 0.5
  expect_move(fin[1], MoveKind::thread, -20.0, 15.0);
  const PlaneMove* first = &out[0];
  expect_move(first[0], MoveKind::rapid, 2.0, 14.5 - 0.5);  // crest 13.5 + 0.5 towards the root
  expect_move(first[1], MoveKind::thread, -20.0, 15.0 - 0.5);
}

TEST(MultipleThread, MultipleStartsRepeatEachPass) {
  MultipleThread c = dafeng_example();
  c.starts = 3;
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({50.0, 34.0}, c, out));
  ASSERT_EQ(out.size(), 5u * 3u * 4u);
  for (std::size_t p = 0; p < 5; ++p) {
    for (std::size_t s = 0; s < 3; ++s) {
      const PlaneMove& th = out[(p * 3 + s) * 4 + 1];
      EXPECT_EQ(th.kind, MoveKind::thread);
      EXPECT_NEAR(th.start_angle, 120.0 * static_cast<double>(s), kEps);
      EXPECT_NEAR(th.to.b, out[p * 3 * 4 + 1].to.b, kEps) << "same depth for every start";
    }
  }
}

TEST(MultipleThread, AlternatingInfeedUsesBothFlanks) {
  MultipleThread c = dafeng_example();
  c.infeed = ThreadInfeed::alternating;
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({50.0, 34.0}, c, out));
  ASSERT_EQ(out.size(), 20u);
  const double t = flank_tan(60.0);
  const double apex = 50.0 - 3.68 * t;
  const double d[] = {1.8, 1.8 * std::sqrt(2.0), 1.8 * std::sqrt(3.0), 3.48, 3.68};
  for (int p = 0; p < 5; ++p) {
    // Even passes touch the trailing flank (behind the bottom), odd ones the leading flank.
    const double side = p % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR(out[static_cast<std::size_t>(4 * p)].to.a, apex + side * (3.68 - d[p]) * t, 1e-9);
  }
}

// GSK G78 (gsk A.6.33): the leading flank on every pass, constant-distance infeed, and a
// run-out with its own rise.
TEST(MultipleThread, LeadingFlankInfeedStaysOnTheFlankAhead) {
  MultipleThread c = dafeng_example();
  c.infeed = ThreadInfeed::leading_flank;
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({50.0, 34.0}, c, out));
  ASSERT_EQ(out.size(), 20u);
  const double t = flank_tan(60.0);
  const double apex = 50.0 - 3.68 * t;
  const double d[] = {1.8, 1.8 * std::sqrt(2.0), 1.8 * std::sqrt(3.0), 3.48, 3.68};
  for (int p = 0; p < 5; ++p) {
    EXPECT_NEAR(out[static_cast<std::size_t>(4 * p)].to.a, apex - (3.68 - d[p]) * t, 1e-9);
  }
}

TEST(MultipleThread, ConstantDepthInfeedCutsEqualSteps) {
  MultipleThread c = dafeng_example();
  c.constant_depth = true;
  c.infeed = ThreadInfeed::radial;
  const std::vector<double> d = thread_pass_depths(c);
  ASSERT_EQ(d.size(), 2u);  // 1.8, then 3.6 capped at 3.48
  EXPECT_NEAR(d[0], 1.8, kEps);
  EXPECT_NEAR(d[1], 3.48, kEps);
  c.first_depth = 0.5;
  const std::vector<double> e = thread_pass_depths(c);
  ASSERT_EQ(e.size(), 7u);
  for (std::size_t i = 0; i + 1 < e.size(); ++i) {
    EXPECT_NEAR(e[i], 0.5 * static_cast<double>(i + 1), kEps);
  }
  EXPECT_NEAR(e.back(), 3.48, kEps);
}

TEST(MultipleThread, RunOutWithItsOwnRise) {
  MultipleThread c = gsk_example();
  c.infeed = ThreadInfeed::radial;
  c.chamfer = 4.0;
  c.chamfer_rise = 1.0;
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({3.0, 16.0}, c, out));
  // The chamfer-out ends 1 mm (radius) above where its thread move ends, over 4 mm of Z.
  EXPECT_NEAR(out[2].to.b - out[1].to.b, 1.0, kEps);
  EXPECT_NEAR(std::fabs(out[2].to.a - out[1].to.a), 4.0, kEps);
}

TEST(MultipleThread, LeadChangeGivesTheChamferTheLeadReached) {
  MultipleThread c = gsk_example();
  c.lead_change = 0.01;
  c.infeed = ThreadInfeed::radial;
  PlanePath out;
  ASSERT_FALSE(expand_multiple_thread({3.0, 16.0}, c, out));
  // 31 mm of thread before the chamfer: lead^2 = 4 + 2 * 0.01 * 31.
  EXPECT_DOUBLE_EQ(out[1].lead, 2.0);
  EXPECT_DOUBLE_EQ(out[1].lead_change, 0.01);
  EXPECT_NEAR(out[2].lead, std::sqrt(4.0 + 0.62), 1e-12);
}

// Generated cycles: the depth law, and every pass on its line inside the finished thread.
TEST(MultipleThread, PropertiesOfGeneratedCycles) {
  Uniform uniform(76076);
  for (int n = 0; n < 400; ++n) {
    MultipleThread c;
    c.height = uniform(0.3, 4.0);
    c.finish_allowance = uniform(0.0, 0.3) * c.height;
    c.first_depth = uniform(0.1, 0.7) * c.height;
    c.min_depth = uniform(0.0, 0.15);
    c.finish_passes = uniform.below(4);
    c.tool_angle = std::floor(uniform(0.0, 99.99));
    c.lead = uniform(0.5, 6.0);
    c.starts = 1 + uniform.below(3);
    c.infeed = static_cast<ThreadInfeed>(uniform.below(3));
    c.taper = uniform(-2.0, 2.0);
    const double along = uniform.chance(0.5) ? -1.0 : 1.0;
    const double outward = uniform.chance(0.5) ? -1.0 : 1.0;
    const Point2 start{uniform(-50.0, 50.0), uniform(20.0, 40.0)};
    const double len = uniform(15.0, 60.0);
    c.chamfer = uniform.chance(0.5) ? 0.0 : uniform(0.1, 5.0);
    // Root at the end so that the start lies 0-2 mm beyond the crest at both ends.
    const double clearance = uniform(0.0, 2.0);
    c.end = {start.a + along * len,
             start.b - outward * (c.height + clearance + std::max(0.0, outward * c.taper))};
    SCOPED_TRACE(n);

    const std::vector<double> d = thread_pass_depths(c);
    const double last = c.height - c.finish_allowance;
    ASSERT_FALSE(d.empty());
    EXPECT_NEAR(d.back(), last, kEps);
    // The first pass is an increment too: raised to the minimum like the others.
    EXPECT_NEAR(d.front(), std::min(std::max(c.first_depth, c.min_depth), last), kEps);
    const double area = c.first_depth * c.first_depth;  // removed per pass, / tan(a/2)
    bool min_reached = false;
    for (std::size_t i = 1; i < d.size(); ++i) {
      const double step = d[i] - d[i - 1];
      EXPECT_GT(step, 0.0);
      const bool is_last = i + 1 == d.size();
      if (!is_last) {
        EXPECT_GE(step, c.min_depth - kEps);
        const double law = c.first_depth * std::sqrt(static_cast<double>(i + 1));
        EXPECT_NEAR(d[i], std::max(law, d[i - 1] + c.min_depth), 1e-9);
        min_reached = min_reached || d[i] > law + kEps || c.first_depth < c.min_depth;
        if (!min_reached) {
          // Constant cut area: the V of depth d has area d^2 tan(a/2).
          EXPECT_NEAR(d[i] * d[i] - d[i - 1] * d[i - 1], area, 1e-9);
        }
      } else {
        EXPECT_LE(d[i], std::max(c.first_depth * std::sqrt(static_cast<double>(i + 1)),
                                 d[i - 1] + c.min_depth) +
                            kEps);
      }
    }

    PlanePath out;
    const path::PathResult r = expand_multiple_thread(start, c, out);
    if (r) {
      // Only a flank shift or chamfer longer than the thread may refuse a generated cycle.
      EXPECT_EQ(r->alarm, alarm::kCycleValue) << r->text;
      EXPECT_TRUE(out.empty());
      continue;
    }
    const std::size_t finishing = c.finish_passes == 0 ? 1 : c.finish_passes;
    const std::size_t per_pass = c.chamfer > 0.0 ? 5 : 4;
    const std::size_t starts = static_cast<std::size_t>(c.starts);
    ASSERT_EQ(out.size(), (d.size() + finishing) * starts * per_pass);
    const double t = flank_tan(c.tool_angle);
    const double root_slope = c.taper / (start.a - c.end.a);
    auto root = [&](double a) { return c.end.b + root_slope * (a - c.end.a); };
    const double apex = out[(d.size() * starts) * per_pass].to.a;  // first finishing pass
    for (std::size_t p = 0; p < d.size() + finishing; ++p) {
      const double depth = p < d.size() ? d[p] : c.height;
      for (std::size_t s = 0; s < starts; ++s) {
        const PlaneMove* m = &out[(p * starts + s) * per_pass];
        // Infeed point on the pass line, `depth` below the crest.
        EXPECT_EQ(m[0].kind, MoveKind::rapid);
        EXPECT_NEAR(outward * (m[0].to.b - root(m[0].to.a)), c.height - depth, 1e-9);
        // The tool's V at this depth lies inside the finished thread's V.
        EXPECT_LE(std::fabs(m[0].to.a - apex), (c.height - depth) * t + 1e-9);
        const double shift = along * (m[0].to.a - start.a);
        if (c.infeed == ThreadInfeed::single_flank) {
          EXPECT_NEAR(shift, depth * t, 1e-9);
        } else if (c.infeed == ThreadInfeed::alternating) {
          // Trailing flank on even passes, leading flank on odd ones.
          EXPECT_NEAR(shift, p % 2 == 0 ? depth * t : (2.0 * c.height - depth) * t, 1e-9);
        } else if (c.infeed == ThreadInfeed::radial) {
          EXPECT_NEAR(shift, 0.0, 1e-12);
        }
        // The thread runs parallel to the root to the chamfer start, with the lead.
        EXPECT_EQ(m[1].kind, MoveKind::thread);
        EXPECT_NEAR(m[1].to.a, c.end.a - along * c.chamfer, 1e-9);
        EXPECT_NEAR(outward * (m[1].to.b - root(m[1].to.a)), c.height - depth, 1e-9);
        EXPECT_DOUBLE_EQ(m[1].lead, c.lead);
        EXPECT_NEAR(m[1].start_angle, 360.0 * static_cast<double>(s) / c.starts, 1e-9);
        const PlaneMove* back = &m[2];
        if (per_pass == 5) {
          EXPECT_EQ(m[2].kind, MoveKind::thread);
          EXPECT_DOUBLE_EQ(m[2].lead, c.lead);
          EXPECT_NEAR(m[2].to.a, c.end.a, 1e-9);
          EXPECT_NEAR(outward * (m[2].to.b - m[1].to.b), c.chamfer, 1e-9);  // 45 degrees
          back = &m[3];
        }
        expect_move(back[0], MoveKind::rapid, c.end.a, start.b);
        expect_move(back[1], MoveKind::rapid, start.a, start.b);
      }
    }
  }
}

// The cycle's moves from `start`; none when it is refused (which fails the test).
PlanePath expanded(const MultipleThread& c, Point2 start) {
  PlanePath out;
  const path::PathResult r = expand_multiple_thread(start, c, out);
  EXPECT_FALSE(r) << r->text;
  return out;
}

// GSK G78 E (decision 84): each pass starts E outside its depth and screws in at 45 degrees;
// with a lead change the thread after the screw-in has the lead reached there.
TEST(MultipleThread, ScrewInEntersEveryPassAtFortyFiveDegrees) {
  MultipleThread c = dafeng_example();
  c.infeed = ThreadInfeed::radial;
  c.screw_in = 0.5;
  c.lead_change = 0.01;
  const PlanePath out = expanded(c, {50.0, 34.0});
  ASSERT_EQ(out.size(), 5u * 5u);
  const double crest = 30.2 + 3.68;
  const double depths[] = {1.8, 1.8 * std::sqrt(2.0), 1.8 * std::sqrt(3.0), 3.48, 3.68};
  for (std::size_t p = 0; p < 5; ++p) {
    const PlaneMove* m = &out[5 * p];
    expect_move(m[0], MoveKind::rapid, 50.0, crest - depths[p] + 0.5);
    expect_move(m[1], MoveKind::thread, 49.5, crest - depths[p]);
    EXPECT_NEAR(m[1].lead, 6.0, kEps);
    expect_move(m[2], MoveKind::thread, 25.0, crest - depths[p]);
    EXPECT_NEAR(m[2].lead, std::sqrt(36.0 + 2.0 * 0.01 * 0.5), kEps);
  }
}

// Dafeng G76 PQ (decision 85) on a steep inside taper: each lift reaches the depth of the pass
// before, the finishing pass does not break, and a lift that rises more along X than it
// advances carries its lead along X so that Z keeps 1.5 per revolution.
TEST(MultipleThread, ChipBreaksLiftToThePassBeforeOnRoughingPassesOnly) {
  MultipleThread c{.end = {-20.0, 15.0},
                   .taper = -4.0,  // root from 11 to 15 over 22 mm
                   .height = 1.0,
                   .first_depth = 0.5,
                   .tool_angle = 0.0,
                   .lead = 1.5,
                   .infeed = ThreadInfeed::radial,
                   .chip_break = 4.0};
  const PlanePath out = expanded(c, {2.0, 9.0});
  ASSERT_FALSE(out.empty());
  const double slope = 4.0 / 22.0;
  const auto root = [&](double a) { return 15.0 - slope * (a + 20.0); };
  // Pass 1 (depth 0.5, crest 1 inside the root): a break after 4 mm rises to the crest.
  expect_move(out[0], MoveKind::rapid, 2.0, root(2.0) - 0.5);
  expect_move(out[1], MoveKind::thread, -2.0, root(-2.0) - 0.5);
  expect_move(out[2], MoveKind::thread, -2.5, root(-2.5) - 1.0);
  expect_move(out[3], MoveKind::thread, -3.0, root(-3.0) - 0.5);
  // Down the lift X falls 0.5 + 0.5 * slope over 0.5 of Z: X is the longer axis.
  const double down_b = 0.5 + 0.5 * slope;
  EXPECT_NEAR(out[3].lead, 1.5 * down_b / 0.5, kEps);
  EXPECT_NEAR(out[2].lead, 1.5, kEps);  // up: X rises 0.5 - 0.5 * slope, less than Z
  // Count the breaks of each pass: every pass but the last (the finishing one) has some, each
  // lift ends at the depth of the pass before.
  std::vector<std::size_t> threads_per_pass;
  for (const PlaneMove& m : out) {
    if (m.kind == MoveKind::rapid && std::fabs(m.to.a - 2.0) < kEps && m.to.b > 9.5) {
      threads_per_pass.push_back(0);
    } else if (m.kind == MoveKind::thread) {
      ++threads_per_pass.back();
    }
  }
  ASSERT_EQ(threads_per_pass.size(), 5u);  // 0.5, 0.707, 0.866, 1.0, then finishing at 1.0
  for (std::size_t p = 0; p + 1 < threads_per_pass.size(); ++p) {
    EXPECT_GT(threads_per_pass[p], 1u) << p;
    EXPECT_EQ(threads_per_pass[p] % 3, 1u) << p;  // 3 moves a break, and the last cut
  }
  EXPECT_EQ(threads_per_pass.back(), 1u);
}

struct AlarmCase {
  const char* what;
  void (*change)(MultipleThread&, Point2&);
  int alarm;
};

class MultipleThreadAlarm : public ::testing::TestWithParam<AlarmCase> {};

TEST_P(MultipleThreadAlarm, RefusesWithoutMoves) {
  MultipleThread c = gsk_example();
  Point2 start{3.0, 16.0};
  GetParam().change(c, start);
  PlanePath out;
  const path::PathResult r = expand_multiple_thread(start, c, out);
  ASSERT_TRUE(r) << GetParam().what;
  EXPECT_EQ(r->alarm, GetParam().alarm) << r->text;
  EXPECT_EQ(r->source, -1);
  EXPECT_FALSE(r->text.empty());
  EXPECT_TRUE(out.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Values, MultipleThreadAlarm,
    ::testing::Values(
        AlarmCase{"height 0", [](MultipleThread& c, Point2&) { c.height = 0.0; },
                  alarm::kCycleValue},
        AlarmCase{"first depth 0", [](MultipleThread& c, Point2&) { c.first_depth = 0.0; },
                  alarm::kCycleValue},
        AlarmCase{"first depth > height", [](MultipleThread& c, Point2&) { c.first_depth = 1.3; },
                  alarm::kCycleValue},
        AlarmCase{"allowance = height",
                  [](MultipleThread& c, Point2&) { c.finish_allowance = 1.2; }, alarm::kCycleValue},
        AlarmCase{"negative allowance",
                  [](MultipleThread& c, Point2&) { c.finish_allowance = -0.1; },
                  alarm::kCycleValue},
        AlarmCase{"negative min depth", [](MultipleThread& c, Point2&) { c.min_depth = -0.1; },
                  alarm::kCycleValue},
        AlarmCase{"negative chamfer", [](MultipleThread& c, Point2&) { c.chamfer = -1.0; },
                  alarm::kCycleValue},
        AlarmCase{"100 finishing passes", [](MultipleThread& c, Point2&) { c.finish_passes = 100; },
                  alarm::kCycleValue},
        AlarmCase{"tool angle 100", [](MultipleThread& c, Point2&) { c.tool_angle = 100.0; },
                  alarm::kCycleValue},
        AlarmCase{"0 starts", [](MultipleThread& c, Point2&) { c.starts = 0; }, alarm::kCycleValue},
        AlarmCase{"lead 0", [](MultipleThread& c, Point2&) { c.lead = 0.0; }, alarm::kCycleValue},
        AlarmCase{"no length", [](MultipleThread& c, Point2&) { c.end.a = 3.0; },
                  alarm::kCycleValue},
        AlarmCase{"start on the root", [](MultipleThread&, Point2& s) { s.b = 13.8; },
                  alarm::kCycleValue},
        AlarmCase{"start inside the crest", [](MultipleThread&, Point2& s) { s.b = 14.9; },
                  alarm::kCycleValue},
        AlarmCase{"taper puts the crest beyond the start at the end",
                  [](MultipleThread& c, Point2&) {
                    c.taper = -1.5;
                    c.end.b = 15.0;
                  },
                  alarm::kCycleValue},
        AlarmCase{"chamfer longer than the thread",
                  [](MultipleThread& c, Point2&) { c.chamfer = 33.0; }, alarm::kCycleValue},
        AlarmCase{"flank shift beyond the end",
                  [](MultipleThread& c, Point2& s) {
                    c.chamfer = 0.0;
                    s.a = -29.5;
                  },
                  alarm::kCycleValue},
        AlarmCase{"too many passes",
                  [](MultipleThread& c, Point2&) {
                    c.first_depth = 0.001;
                    c.min_depth = 0.0;
                  },
                  alarm::kCycleValue},
        AlarmCase{"negative screw-in", [](MultipleThread& c, Point2&) { c.screw_in = -0.1; },
                  alarm::kCycleValue},
        AlarmCase{"negative chip break", [](MultipleThread& c, Point2&) { c.chip_break = -1.0; },
                  alarm::kCycleValue},
        AlarmCase{"screw-in reaching the chamfer",
                  [](MultipleThread& c, Point2&) { c.screw_in = 31.0; }, alarm::kCycleValue},
        AlarmCase{"too many chip breaks",
                  [](MultipleThread& c, Point2& s) {
                    s.a = 6000.0;  // a 6 m thread broken every micron
                    c.chip_break = 0.001;
                  },
                  alarm::kCycleValue},
        AlarmCase{"lead reaching 0 (G34-like K)",
                  [](MultipleThread& c, Point2&) { c.lead_change = -0.1; }, alarm::kThreadLead}));

}  // namespace
}  // namespace mcnc::interp::cycles::test
