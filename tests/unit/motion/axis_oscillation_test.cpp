// AxisOscillation (G81.1 / G80.1, spec dafeng L2454-2505) as a pure unit: its dead points, its
// speed, the axis's limits, the end of G80.1 and the stop of a reset.
#include "channel/motion/axis_oscillation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace mcnc::motion {
namespace {

constexpr double kDt = 0.001;
const AxisDynamics kFree{1e9, 1e9, 1e12};  // limits that never bind

struct Strokes {
  std::vector<double> turns;  // positions where the velocity changed sign or reached 0
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -std::numeric_limits<double>::infinity();
  double peak_speed = 0.0;
  double peak_acc = 0.0;
  int cycles = 0;
};

// How far the sample nearest a dead point may lie from it.
double turn_tolerance(const Strokes& r) {
  return r.peak_acc * kDt * kDt;
}

// Steps `o` for up to `cycles` cycles (until it is off), collecting its turning points.
Strokes run(AxisOscillation& o, int cycles) {
  Strokes r;
  double prev_v = o.sample().vel;
  double prev_pos = o.sample().pos;
  for (int i = 0; i < cycles && o.active(); ++i) {
    const OscillationSample s = o.step(kDt);
    ++r.cycles;
    r.lowest = std::min(r.lowest, s.pos);
    r.highest = std::max(r.highest, s.pos);
    r.peak_speed = std::max(r.peak_speed, std::fabs(s.vel));
    r.peak_acc = std::max(r.peak_acc, std::fabs(s.acc));
    if (prev_v != 0.0 && (s.vel == 0.0 || (s.vel > 0.0) != (prev_v > 0.0))) {
      // The dead point lies between the two samples: the slower one is within half the peak
      // acceleration times a cycle squared of it (turn_tolerance).
      r.turns.push_back(std::fabs(s.vel) < std::fabs(prev_v) ? s.pos : prev_pos);
    }
    prev_v = s.vel;
    prev_pos = s.pos;
  }
  return r;
}

TEST(AxisOscillation, TurnsAtTheDeadPointsOfTheSpecsExample) {
  // G81.1 Z0 Q100 F2000: between 0 and 100 at 2000 mm/min (L2491-2501).
  AxisOscillation o;
  ASSERT_TRUE(o.start(0.0, 0.0, 100.0, 2000.0 / 60.0, kFree));
  const Strokes r = run(o, 40000);
  ASSERT_GE(r.turns.size(), 4U);
  for (std::size_t k = 0; k < r.turns.size(); ++k) {
    EXPECT_NEAR(r.turns[k], k % 2 == 0 ? 100.0 : 0.0, turn_tolerance(r)) << "turn " << k;
  }
  EXPECT_GE(r.lowest, -1e-9);
  EXPECT_LE(r.highest, 100.0 + 1e-9);
  EXPECT_LE(r.peak_speed, 2000.0 / 60.0 + 1e-9);
  EXPECT_GT(r.peak_speed, 2000.0 / 60.0 * 0.999);  // the feed is the stroke's top speed
  EXPECT_TRUE(o.active());                         // until G80.1
}

TEST(AxisOscillation, AStrokeTakesHalfACosineAtTheFeed) {
  const double f = 2000.0 / 60.0;
  EXPECT_NEAR(AxisOscillation::stroke_time(100.0, f, kFree), std::numbers::pi * 100.0 / (2 * f),
              1e-12);
  AxisOscillation o;
  ASSERT_TRUE(o.start(0.0, 0.0, 100.0, f, kFree));
  // Half way through the first stroke the axis is half way, at its top speed.
  const int half = static_cast<int>(std::lround(std::numbers::pi * 100.0 / (4 * f) / kDt));
  OscillationSample s;
  for (int i = 0; i < half; ++i) {
    s = o.step(kDt);
  }
  EXPECT_NEAR(s.pos, 50.0, 0.05);
  EXPECT_NEAR(s.vel, f, 1e-3);
}

TEST(AxisOscillation, TheAxissLimitsLengthenAStroke) {
  // 1 mm strokes at 6000 mm/min would need 1974 mm/s^2: the axis's 500 slow them down.
  const AxisDynamics limits{200.0, 500.0, 1e9};
  const double t = AxisOscillation::stroke_time(1.0, 100.0, limits);
  EXPECT_NEAR(t, std::numbers::pi * std::sqrt(1.0 / 1000.0), 1e-12);
  AxisOscillation o;
  ASSERT_TRUE(o.start(5.0, 5.0, 4.0, 100.0, limits));
  const Strokes r = run(o, 2000);
  EXPECT_LE(r.peak_acc, 500.0 + 1e-9);
  EXPECT_LE(r.peak_speed, 200.0);
  ASSERT_GE(r.turns.size(), 2U);
  EXPECT_NEAR(r.turns[0], 4.0, turn_tolerance(r));
  EXPECT_NEAR(r.turns[1], 5.0, turn_tolerance(r));
  // Jerk binds too.
  EXPECT_NEAR(AxisOscillation::stroke_time(2.0, 1e9, AxisDynamics{1e9, 1e9, 100.0}),
              std::numbers::pi * std::cbrt(2.0 / 200.0), 1e-12);
}

TEST(AxisOscillation, FirstGoesToTheTopDeadPoint) {
  AxisOscillation o;
  ASSERT_TRUE(o.start(30.0, 10.0, 20.0, 50.0, kFree));
  const Strokes r = run(o, 5000);
  ASSERT_GE(r.turns.size(), 3U);
  EXPECT_NEAR(r.turns[0], 10.0, turn_tolerance(r));
  EXPECT_NEAR(r.turns[1], 20.0, turn_tolerance(r));
  EXPECT_NEAR(r.turns[2], 10.0, turn_tolerance(r));
}

TEST(AxisOscillation, FinishEndsTheStrokeUnderWayThenGoesToTheEnd) {
  // G80.1 Z0 while the axis goes up: it turns at 100, comes down to 0 and stops there.
  AxisOscillation o;
  ASSERT_TRUE(o.start(0.0, 0.0, 100.0, 100.0, kFree));
  for (int i = 0; i < 300; ++i) {
    o.step(kDt);
  }
  ASSERT_GT(o.sample().vel, 0.0);
  o.finish_at(0.0);
  EXPECT_EQ(o.phase(), AxisOscillation::Phase::finishing);
  const Strokes r = run(o, 10000);
  EXPECT_FALSE(o.active());
  ASSERT_EQ(r.turns.size(), 2U);
  EXPECT_NEAR(r.turns[0], 100.0, turn_tolerance(r));
  EXPECT_DOUBLE_EQ(o.sample().pos, 0.0);
  EXPECT_EQ(o.sample().vel, 0.0);
  EXPECT_LE(r.highest, 100.0 + 1e-9);
}

TEST(AxisOscillation, FinishToAnotherPointTakesOneMoreStroke) {
  AxisOscillation o;
  ASSERT_TRUE(o.start(0.0, 0.0, 10.0, 100.0, kFree));
  o.step(kDt);
  o.finish_at(-5.0);  // on its way to 10: then from 10 to -5
  const Strokes r = run(o, 10000);
  EXPECT_FALSE(o.active());
  EXPECT_NEAR(r.turns.front(), 10.0, turn_tolerance(r));
  EXPECT_DOUBLE_EQ(o.sample().pos, -5.0);
  EXPECT_NEAR(r.lowest, -5.0, 1e-9);
  // The last stroke is 15 long: it lasts a 15 mm stroke's time.
  EXPECT_NEAR(r.cycles * kDt,
              AxisOscillation::stroke_time(10.0, 100.0, kFree) +
                  AxisOscillation::stroke_time(15.0, 100.0, kFree),
              2 * kDt);
}

TEST(AxisOscillation, StopDeceleratesToRestWhereItIs) {
  AxisOscillation o;
  ASSERT_TRUE(o.start(0.0, 0.0, 100.0, 100.0, kFree));
  for (int i = 0; i < 500; ++i) {
    o.step(kDt);
  }
  const double v = o.sample().vel;
  const double at = o.sample().pos;
  ASSERT_GT(v, 50.0);
  o.stop(1000.0);
  const Strokes r = run(o, 1000);
  EXPECT_FALSE(o.active());
  EXPECT_EQ(o.sample().vel, 0.0);
  EXPECT_LE(r.peak_acc, 1000.0);
  // v^2 / 2a further on, within a cycle's travel.
  EXPECT_NEAR(o.sample().pos, at + v * v / 2000.0, v * kDt);
}

TEST(AxisOscillation, RefusesWhatCannotOscillate) {
  AxisOscillation o;
  EXPECT_FALSE(o.start(0.0, 5.0, 5.0, 10.0, kFree));  // no distance
  EXPECT_FALSE(o.start(0.0, 0.0, 5.0, 0.0, kFree));   // no feed
  EXPECT_FALSE(o.start(0.0, std::nan(""), 5.0, 10.0, kFree));
  EXPECT_FALSE(o.start(0.0, 0.0, std::numeric_limits<double>::infinity(), 10.0, kFree));
  EXPECT_FALSE(o.active());
  o.finish_at(3.0);  // nothing to finish
  EXPECT_FALSE(o.active());
  EXPECT_EQ(o.step(kDt).pos, 0.0);
}

}  // namespace
}  // namespace mcnc::motion
