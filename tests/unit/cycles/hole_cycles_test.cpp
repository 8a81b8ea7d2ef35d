// Hole cycles (G83/G87 drilling, G84/G88 tapping, G85/G89 boring): the spec examples step by
// step, the order and safety of the steps on generated holes, and the alarms.
#include "channel/interp/cycles/hole_cycles.hpp"
#include "channel/interp/program_alarms.hpp"

#include "tests/unit/cycles/cycle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::interp::cycles::test {
namespace {

using Kind = HoleStep::Kind;

struct Expected {
  Kind kind;
  double value = 0.0;  // `to`, `seconds` or `code`
};

void expect_steps(const std::vector<HoleStep>& got, std::initializer_list<Expected> want) {
  ASSERT_EQ(got.size(), want.size());
  std::size_t i = 0;
  for (const Expected& w : want) {
    SCOPED_TRACE(i);
    const HoleStep& g = got[i++];
    EXPECT_EQ(g.kind, w.kind);
    switch (w.kind) {
      case Kind::rapid:
      case Kind::feed:
      case Kind::tap:
      case Kind::shift:
        EXPECT_NEAR(g.to, w.value, 1e-9);
        break;
      case Kind::dwell:
        EXPECT_DOUBLE_EQ(g.seconds, w.value);
        break;
      case Kind::aux:
        EXPECT_EQ(g.code, static_cast<int>(w.value));
        break;
      case Kind::reverse:
      case Kind::restore:
      case Kind::spindle_stop:
      case Kind::orient:
        break;
    }
  }
}

// gsk D2-30 (L1524-1529): drill start Z0, G83 X0 C0 Z-10 Q3000 R1 P500 F0.1 (J0 / J1 / Q0).
// gsk's R is the back-off (J0) or the stop short of the last depth (J1); its start is the
// current Z, so R-level = initial = 0.
HoleCycle gsk_d2_30(PeckMode mode) {
  return HoleCycle{.kind = HoleKind::drill,
                   .peck_mode = mode,
                   .initial = 0.0,
                   .r_level = 0.0,
                   .bottom = -10.0,
                   .peck = 3.0,
                   .retract = 1.0,
                   .clearance = 1.0,
                   .dwell_s = 0.5,
                   .feed = 0.1};
}

TEST(HoleCycles, GskD2_30HighSpeedPeck) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(gsk_d2_30(PeckMode::high_speed), out));
  // Feeds 0 -> -3, -2 -> -6, -5 -> -9, -8 -> -10, a 1 mm rapid back-off between them.
  expect_steps(out, {{Kind::feed, -3},
                     {Kind::rapid, -2},
                     {Kind::feed, -6},
                     {Kind::rapid, -5},
                     {Kind::feed, -9},
                     {Kind::rapid, -8},
                     {Kind::feed, -10},
                     {Kind::dwell, 0.5},
                     {Kind::rapid, 0}});
}

TEST(HoleCycles, GskD2_30DeepHoleJ1) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(gsk_d2_30(PeckMode::deep), out));
  // The same feed segments; after each a rapid to Z0 and a rapid to 1 short of the depth.
  expect_steps(out, {{Kind::feed, -3},
                     {Kind::rapid, 0},
                     {Kind::rapid, -2},
                     {Kind::feed, -6},
                     {Kind::rapid, 0},
                     {Kind::rapid, -5},
                     {Kind::feed, -9},
                     {Kind::rapid, 0},
                     {Kind::rapid, -8},
                     {Kind::feed, -10},
                     {Kind::dwell, 0.5},
                     {Kind::rapid, 0}});
}

TEST(HoleCycles, GskD2_30WithoutQDrillsStraight) {
  for (PeckMode mode : {PeckMode::high_speed, PeckMode::deep, PeckMode::high_speed_deep}) {
    HoleCycle c = gsk_d2_30(mode);
    c.peck = 0.0;
    std::vector<HoleStep> out;
    ASSERT_FALSE(expand_hole(c, out));
    expect_steps(out, {{Kind::feed, -10}, {Kind::dwell, 0.5}, {Kind::rapid, 0}});
  }
}

TEST(HoleCycles, GskA6_34HighSpeedWithoutBackOffDrillsStraight) {
  HoleCycle c = gsk_d2_30(PeckMode::high_speed);
  c.retract = 0.0;  // rule 6 (L1070): R0 in the high-speed cycle
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::feed, -10}, {Kind::dwell, 0.5}, {Kind::rapid, 0}});
}

// dafeng §7 item 21 (spec L2358; manual L1907-1940): G00 Z5; G83.5 Z-10 A0 R1 Q4 F300 M12,
// one hole. The back-off r is parameter 5110: 0.5 here.
TEST(HoleCycles, DafengItem21HighSpeedPeckWithClamp) {
  const HoleCycle c{.kind = HoleKind::drill,
                    .peck_mode = PeckMode::high_speed,
                    .initial = 5.0,
                    .r_level = 1.0,
                    .bottom = -10.0,
                    .peck = 4.0,
                    .retract = 0.5,
                    .feed = 300.0,
                    .clamp_code = 12};
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::aux, 12},
                     {Kind::rapid, 1},
                     {Kind::feed, -3},
                     {Kind::rapid, -2.5},
                     {Kind::feed, -7},
                     {Kind::rapid, -6.5},
                     {Kind::feed, -10},
                     {Kind::rapid, 1},  // back to R (system A: no G98 return level)
                     {Kind::aux, 13}});
}

TEST(HoleCycles, HighSpeedDeepFullRetractAfterTheSetDepth) {
  // .7: pecks of 2 with 0.5 back-offs; a full retract once 5 mm were drilled since the last.
  const HoleCycle c{.kind = HoleKind::drill,
                    .peck_mode = PeckMode::high_speed_deep,
                    .initial = 2.0,
                    .r_level = 1.0,
                    .bottom = -11.0,
                    .peck = 2.0,
                    .retract = 0.5,
                    .clearance = 0.3,
                    .full_retract_depth = 5.0};
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::rapid, 1},
                     {Kind::feed, -1},
                     {Kind::rapid, -0.5},
                     {Kind::feed, -3},
                     {Kind::rapid, -2.5},
                     {Kind::feed, -5},  // 6 mm since R: full retract
                     {Kind::rapid, 1},
                     {Kind::rapid, -4.7},
                     {Kind::feed, -7},
                     {Kind::rapid, -6.5},
                     {Kind::feed, -9},
                     {Kind::rapid, -8.5},
                     {Kind::feed, -11},
                     {Kind::rapid, 1}});
}

TEST(HoleCycles, HighSpeedDeepWithoutDepthRetractsFullyEveryPeck) {
  HoleCycle c = gsk_d2_30(PeckMode::high_speed_deep);
  std::vector<HoleStep> deep;
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  c.peck_mode = PeckMode::deep;
  ASSERT_FALSE(expand_hole(c, deep));
  ASSERT_EQ(out.size(), deep.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].kind, deep[i].kind);
    EXPECT_DOUBLE_EQ(out[i].to, deep[i].to);
  }
}

// dafeng §7 item 22 (manual L2084-2118): from Z5, G84 Z-10 R1 F1.25, with a 0.2 s dwell and
// the G98 return to the initial level.
TEST(HoleCycles, TappingInReverseOutRestore) {
  const HoleCycle c{.kind = HoleKind::tap,
                    .initial = 5.0,
                    .r_level = 1.0,
                    .bottom = -10.0,
                    .dwell_s = 0.2,
                    .lead = 1.25,
                    .clamp_code = 18,
                    .return_to_initial = true};
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::aux, 18},
                     {Kind::rapid, 1},
                     {Kind::tap, -10},
                     {Kind::dwell, 0.2},
                     {Kind::reverse},
                     {Kind::tap, 1},
                     {Kind::restore},
                     {Kind::rapid, 5},
                     {Kind::aux, 19}});
}

// dafeng §7 item 23 (manual L2131-2170): G84.5 ... R1 Q4 F1.25, one hole from Z5; the return r
// is parameter 5211: 1 here. Every move inside the hole is synchronised.
TEST(HoleCycles, PeckTappingHighSpeed) {
  const HoleCycle c{.kind = HoleKind::tap,
                    .peck_mode = PeckMode::high_speed,
                    .initial = 5.0,
                    .r_level = 1.0,
                    .bottom = -10.0,
                    .peck = 4.0,
                    .retract = 1.0,
                    .lead = -1.25};  // left hand
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::rapid, 1},
                     {Kind::tap, -3},
                     {Kind::reverse},
                     {Kind::tap, -2},
                     {Kind::restore},
                     {Kind::tap, -7},
                     {Kind::reverse},
                     {Kind::tap, -6},
                     {Kind::restore},
                     {Kind::tap, -10},
                     {Kind::reverse},
                     {Kind::tap, 1},
                     {Kind::restore}});
}

TEST(HoleCycles, PeckTappingDeepTapsBackToR) {
  const HoleCycle c{.kind = HoleKind::tap,
                    .peck_mode = PeckMode::deep,
                    .initial = 1.0,
                    .r_level = 1.0,
                    .bottom = -7.0,
                    .peck = 4.0,
                    .clearance = 1.0,
                    .lead = 1.0};
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(c, out));
  expect_steps(out, {{Kind::tap, -3},
                     {Kind::reverse},
                     {Kind::tap, 1},
                     {Kind::restore},
                     {Kind::tap, -7},
                     {Kind::reverse},
                     {Kind::tap, 1},
                     {Kind::restore}});
}

// dafeng G85/G89 (spec L722-726): rapid to R, feed to the bottom, dwell P, feed out to R.
TEST(HoleCycles, SideBoringFeedsOut) {
  const HoleCycle c{.kind = HoleKind::bore,
                    .peck_mode = PeckMode::high_speed,  // no pecks when boring
                    .initial = 30.0,
                    .r_level = 26.0,
                    .bottom = 40.0,  // G89: along X (radius), outwards here
                    .peck = 2.0,
                    .retract = 1.0,
                    .dwell_s = 1.0,
                    .feed = 0.05,
                    .return_to_initial = true};
  std::vector<HoleStep> out;
  // The initial level lies between R and the bottom: refused.
  const path::PathResult r = expand_hole(c, out);
  ASSERT_TRUE(r);
  HoleCycle ok = c;
  ok.initial = 20.0;
  ASSERT_FALSE(expand_hole(ok, out));
  expect_steps(out, {{Kind::rapid, 26},
                     {Kind::feed, 40},
                     {Kind::dwell, 1.0},
                     {Kind::feed, 26},
                     {Kind::rapid, 20}});
}

TEST(HoleCycles, AppendsToTheSteps) {
  std::vector<HoleStep> out(3);
  ASSERT_FALSE(expand_hole(HoleCycle{.initial = 1.0, .r_level = 1.0, .bottom = -1.0}, out));
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[3].kind, Kind::feed);
  EXPECT_EQ(out[4].kind, Kind::rapid);
}

// Generated holes: the peck depths, no rapid into uncut material, tapping synchronised inside
// the hole with the spindle reversed on the way out, and the exit level.
TEST(HoleCycles, PropertiesOfGeneratedHoles) {
  Uniform uniform(83083);
  for (int n = 0; n < 500; ++n) {
    SCOPED_TRACE(n);
    HoleCycle c;
    c.kind = static_cast<HoleKind>(uniform.below(3));
    c.peck_mode = static_cast<PeckMode>(uniform.below(4));
    const double in = uniform.chance(0.5) ? -1.0 : 1.0;
    c.r_level = uniform(-20.0, 20.0);
    c.initial = c.r_level - in * (uniform.chance(0.3) ? 0.0 : uniform(0.1, 10.0));
    const double depth = uniform(0.5, 40.0);
    c.bottom = c.r_level + in * depth;
    c.peck = uniform.chance(0.2) ? 0.0 : uniform(0.3, 8.0);
    c.retract = uniform.chance(0.2) ? 0.0 : uniform(0.1, 2.0);
    c.clearance = uniform(0.0, 1.5);
    c.full_retract_depth = uniform.chance(0.3) ? 0.0 : uniform(1.0, 15.0);
    c.dwell_s = uniform.chance(0.5) ? 0.0 : uniform(0.1, 2.0);
    c.lead = uniform(0.5, 3.0);
    c.clamp_code = uniform.chance(0.5) ? 0 : 68;
    c.return_to_initial = uniform.chance(0.5);

    std::vector<HoleStep> out;
    ASSERT_FALSE(expand_hole(c, out));
    const bool tapping = c.kind == HoleKind::tap;
    const bool pecking = c.kind != HoleKind::bore && c.peck > 0.0 &&
                         c.peck_mode != PeckMode::none &&
                         !(c.peck_mode == PeckMode::high_speed && c.retract == 0.0);
    const int pecks = pecking ? static_cast<int>(std::ceil(depth / c.peck - 1e-9)) : 1;

    std::size_t first = 0;
    std::size_t last = out.size();
    if (c.clamp_code != 0) {
      ASSERT_GE(out.size(), 2u);
      EXPECT_EQ(out.front().kind, Kind::aux);
      EXPECT_EQ(out.front().code, 68);
      EXPECT_EQ(out.back().kind, Kind::aux);
      EXPECT_EQ(out.back().code, 69);
      first = 1;
      last = out.size() - 1;
    }
    auto below_r = [&](double pos) { return in * (pos - c.r_level); };
    double at = c.initial;
    double reached = 0.0;  // deepest point cut, below R
    int ins = 0;           // moves that cut deeper
    bool reversed = false;
    bool dwelled = false;
    double since_full = 0.0;      // depth cut since the last full retract (.7)
    double expected_back = -1.0;  // where the step after a peck goes back to; < 0: none
    for (std::size_t i = first; i < last; ++i) {
      const HoleStep& s = out[i];
      const bool motion = s.kind == Kind::rapid || s.kind == Kind::feed || s.kind == Kind::tap;
      if (motion && expected_back >= 0.0) {
        EXPECT_NEAR(below_r(s.to), expected_back, 1e-9) << "the back-off after a peck";
        expected_back = -1.0;
      }
      switch (s.kind) {
        case Kind::rapid:
          EXPECT_FALSE(reversed);
          EXPECT_LE(below_r(s.to), reached + 1e-9) << "a rapid into uncut material";
          if (tapping) {
            EXPECT_LE(below_r(s.to), 1e-9) << "a rapid inside a tapped hole";
          }
          break;
        case Kind::feed:
        case Kind::tap: {
          EXPECT_EQ(s.kind, tapping ? Kind::tap : Kind::feed);
          const bool deeper = below_r(s.to) > below_r(at);
          EXPECT_EQ(reversed, tapping && !deeper) << "the spindle turns back for the way out";
          if (deeper && below_r(s.to) > reached + 1e-9) {
            ++ins;
            const double expected = ins == pecks ? depth : ins * c.peck;
            EXPECT_NEAR(below_r(s.to), expected, 1e-9) << "peck " << ins;
            since_full += below_r(s.to) - reached;
            reached = below_r(s.to);
            if (pecking && ins < pecks) {
              const bool full =
                  c.peck_mode == PeckMode::deep || (c.peck_mode == PeckMode::high_speed_deep &&
                                                    since_full >= c.full_retract_depth - 1e-9);
              expected_back = full ? 0.0 : reached - std::min(c.retract, reached);
              since_full = full ? 0.0 : since_full;
              if (std::fabs(expected_back - reached) < 1e-9) {
                expected_back = -1.0;  // no back-off: the next peck follows
              }
            }
          }
          EXPECT_GE(below_r(s.to), -1e-9) << "cutting moves stay between R and the bottom";
          break;
        }
        case Kind::dwell:
          EXPECT_NEAR(reached, depth, 1e-9);
          EXPECT_NEAR(below_r(at), depth, 1e-9) << "dwell at the bottom";
          EXPECT_DOUBLE_EQ(s.seconds, c.dwell_s);
          dwelled = true;
          break;
        case Kind::reverse:
          EXPECT_TRUE(tapping);
          EXPECT_FALSE(reversed);
          reversed = true;
          break;
        case Kind::restore:
          EXPECT_TRUE(reversed);
          reversed = false;
          break;
        case Kind::aux:
          ADD_FAILURE() << "aux inside the hole";
          break;
        case Kind::spindle_stop:
        case Kind::orient:
        case Kind::shift:
          ADD_FAILURE() << "a step of the mill's G86/G76/G87 in a drill, tap or bore";
          break;
      }
      if (motion) {
        EXPECT_GT(std::fabs(s.to - at), 1e-9) << "a step that does not move";
        at = s.to;
      }
    }
    EXPECT_EQ(ins, pecks);
    EXPECT_EQ(dwelled, c.dwell_s > 0.0);
    EXPECT_FALSE(reversed);
    EXPECT_NEAR(at, c.return_to_initial ? c.initial : c.r_level, 1e-9);
  }
}

struct AlarmCase {
  const char* what;
  HoleCycle cycle;
};

class HoleCycleAlarm : public ::testing::TestWithParam<AlarmCase> {};

TEST_P(HoleCycleAlarm, RefusesWithoutSteps) {
  std::vector<HoleStep> out;
  const path::PathResult r = expand_hole(GetParam().cycle, out);
  ASSERT_TRUE(r) << GetParam().what;
  EXPECT_EQ(r->alarm, alarm::kCycleValue) << r->text;
  EXPECT_EQ(r->source, -1);
  EXPECT_TRUE(out.empty());
}

// The mill's G86 (gsk B.1 L44): feed in, dwell, spindle stop, rapid out (G98: to the initial
// level), spindle restarted.
TEST(HoleCycles, MillBoreWithSpindleStop) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole({.kind = HoleKind::bore_stop,
                            .initial = 50,
                            .r_level = 2,
                            .bottom = -10,
                            .dwell_s = 0.2,
                            .return_to_initial = true},
                           out));
  expect_steps(out, {{Kind::rapid, 2},
                     {Kind::feed, -10},
                     {Kind::dwell, 0.2},
                     {Kind::spindle_stop},
                     {Kind::rapid, 50},
                     {Kind::restore}});
}

// G76 (L37): the tool leaves the wall oriented and shifted before the rapid out, and comes
// back to the centre before the spindle turns again. G99: out to R.
TEST(HoleCycles, MillFineBoring) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole(
      {.kind = HoleKind::fine_bore, .initial = 50, .r_level = 2, .bottom = -10, .shift = 0.3},
      out));
  expect_steps(out, {{Kind::rapid, 2},
                     {Kind::feed, -10},
                     {Kind::orient},
                     {Kind::shift, 0.3},
                     {Kind::rapid, 2},
                     {Kind::shift, 0},
                     {Kind::restore}});
}

// G87 (L45): in through the hole to R shifted, cut back to the bottom, out to the initial
// level, which a G99 hole before it may have left (initial_level).
TEST(HoleCycles, MillBackBoring) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole({.kind = HoleKind::back_bore,
                            .initial = 2,
                            .r_level = -25,
                            .bottom = -5,
                            .dwell_s = 0.1,
                            .shift = 0.5,
                            .has_initial_level = true,
                            .initial_level = 50},
                           out));
  expect_steps(out, {{Kind::orient},
                     {Kind::shift, 0.5},
                     {Kind::rapid, -25},
                     {Kind::shift, 0},
                     {Kind::restore},
                     {Kind::feed, -5},
                     {Kind::dwell, 0.1},
                     {Kind::orient},
                     {Kind::shift, 0.5},
                     {Kind::rapid, 50},
                     {Kind::shift, 0},
                     {Kind::restore}});
  // The initial level must lie beyond the bottom seen from R: else the way out crosses the cut.
  out.clear();
  const path::PathResult e =
      expand_hole({.kind = HoleKind::back_bore, .initial = -10, .r_level = -25, .bottom = -5}, out);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->alarm, alarm::kCycleValue);
  EXPECT_TRUE(out.empty());
}

// The mill's G98 after G99 holes: the tool stands at R, the way out goes to the level where the
// cycle began.
TEST(HoleCycles, MillReturnsToTheCyclesInitialLevel) {
  std::vector<HoleStep> out;
  ASSERT_FALSE(expand_hole({.kind = HoleKind::drill,
                            .initial = 2,
                            .r_level = 2,
                            .bottom = -10,
                            .return_to_initial = true,
                            .has_initial_level = true,
                            .initial_level = 50},
                           out));
  expect_steps(out, {{Kind::feed, -10}, {Kind::rapid, 50}});
}

INSTANTIATE_TEST_SUITE_P(
    Values, HoleCycleAlarm,
    ::testing::Values(
        AlarmCase{"negative peck", {.initial = 5, .r_level = 1, .bottom = -10, .peck = -1}},
        AlarmCase{"negative retract", {.initial = 5, .r_level = 1, .bottom = -10, .retract = -1}},
        AlarmCase{"negative clearance",
                  {.initial = 5, .r_level = 1, .bottom = -10, .clearance = -1}},
        AlarmCase{"negative dwell", {.initial = 5, .r_level = 1, .bottom = -10, .dwell_s = -1}},
        AlarmCase{"negative full-retract depth",
                  {.initial = 5, .r_level = 1, .bottom = -10, .full_retract_depth = -1}},
        AlarmCase{"negative shift", {.initial = 5, .r_level = 1, .bottom = -10, .shift = -1}},
        AlarmCase{"R at the bottom", {.initial = 5, .r_level = -10, .bottom = -10}},
        AlarmCase{"R beyond the bottom", {.initial = 5, .r_level = -12, .bottom = -10}},
        AlarmCase{"initial inside the hole", {.initial = -2, .r_level = 1, .bottom = -10}},
        AlarmCase{"tap with lead 0",
                  {.kind = HoleKind::tap, .initial = 5, .r_level = 1, .bottom = -10}},
        AlarmCase{"too many pecks",
                  {.peck_mode = PeckMode::deep,
                   .initial = 5,
                   .r_level = 1,
                   .bottom = -1000,
                   .peck = 0.001}}));

}  // namespace
}  // namespace mcnc::interp::cycles::test
