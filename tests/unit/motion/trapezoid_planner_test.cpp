#include "channel/motion/trapezoid_planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace mcnc::motion {
namespace {

using interp::CanonicalCommand;
using interp::CommandKind;

constexpr double kRel = 1e-9;  // relative tolerance on limits

// X: slow and weak, Z: fast, C: a rotary axis with its own numbers (units/s, units/s^2).
std::vector<AxisLimits> lathe_limits() {
  return {{50.0, 20.0, 500.0}, {200.0, 40.0, 2000.0}, {360.0, 90.0, 1000.0}};
}

AxisVector vec(double x, double z, double c = 0.0) {
  AxisVector v{};
  v[0] = x;
  v[1] = z;
  v[2] = c;
  return v;
}

CanonicalCommand move(CommandKind kind, const AxisVector& target, double feed = 0.0) {
  CanonicalCommand c;
  c.kind = kind;
  c.target = target;
  c.feed = feed;
  return c;
}

bool bit_identical(const AxisVector& a, const AxisVector& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

struct Trace {
  std::vector<MotionSample> samples;
  bool done = false;
};

Trace run(TrapezoidPlanner& planner, double dt, std::size_t max_steps = 10'000'000) {
  Trace r;
  MotionSample s;
  for (std::size_t i = 0; i < max_steps; ++i) {
    const StepResult res = planner.step(dt, s);
    r.samples.push_back(s);
    if (res == StepResult::block_done) {
      r.done = true;
      break;
    }
  }
  return r;
}

// Path limits the planner is expected to use, computed here independently.
struct PathLimits {
  double v = 0.0;
  double a = 0.0;
  double length = 0.0;
};

PathLimits expected_path_limits(const std::vector<AxisLimits>& limits, const AxisVector& start,
                                const CanonicalCommand& c) {
  PathLimits p;
  double sq = 0.0;
  for (std::size_t i = 0; i < limits.size(); ++i) {
    sq += (c.target[i] - start[i]) * (c.target[i] - start[i]);
  }
  p.length = std::sqrt(sq);
  p.v = c.kind == CommandKind::linear ? c.feed / 60.0 : std::numeric_limits<double>::infinity();
  p.a = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const double u = std::fabs(c.target[i] - start[i]) / p.length;
    if (u > 0.0) {
      const double rate = c.kind == CommandKind::linear ? limits[i].max_feed : limits[i].rapid_rate;
      p.v = std::min(p.v, rate / u);
      p.a = std::min(p.a, limits[i].acceleration / u);
    }
  }
  return p;
}

double analytic_time(const PathLimits& p) {
  if (p.length * p.a >= p.v * p.v) {
    return p.length / p.v + p.v / p.a;
  }
  return 2.0 * std::sqrt(p.length / p.a);
}

// Every sample within every axis's velocity and acceleration limit, reported and differenced.
void check_limits(const std::vector<AxisLimits>& limits, CommandKind kind, const AxisVector& start,
                  const Trace& r, double dt) {
  MotionSample prev;
  prev.pos = start;
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    const MotionSample& s = r.samples[k];
    for (std::size_t i = 0; i < limits.size(); ++i) {
      const double v_lim = kind == CommandKind::linear ? limits[i].max_feed : limits[i].rapid_rate;
      const double a_lim = limits[i].acceleration;
      ASSERT_LE(std::fabs(s.vel[i]), v_lim * (1 + kRel)) << "sample " << k << " axis " << i;
      ASSERT_LE(std::fabs(s.acc[i]), a_lim * (1 + kRel)) << "sample " << k << " axis " << i;
      // The positions and velocities handed to a drive must respect the limits between samples
      // too (position rounding allowed for).
      const double pos_noise = 1e-12 * (1.0 + std::fabs(s.pos[i])) / dt;
      ASSERT_LE(std::fabs(s.pos[i] - prev.pos[i]) / dt, v_lim * (1 + kRel) + pos_noise)
          << "sample " << k << " axis " << i;
      ASSERT_LE(std::fabs(s.vel[i] - prev.vel[i]) / dt, a_lim * (1 + kRel) + 1e-9)
          << "sample " << k << " axis " << i;
    }
    prev = s;
  }
}

void expect_ends_exactly(const Trace& r, const AxisVector& target) {
  ASSERT_TRUE(r.done);
  ASSERT_FALSE(r.samples.empty());
  const MotionSample& last = r.samples.back();
  EXPECT_TRUE(bit_identical(last.pos, target));
  EXPECT_TRUE(bit_identical(last.vel, AxisVector{}));
  EXPECT_TRUE(bit_identical(last.acc, AxisVector{}));
}

double peak_speed(const Trace& r, std::size_t axis) {
  double peak = 0.0;
  for (const auto& s : r.samples) {
    peak = std::max(peak, std::fabs(s.vel[axis]));
  }
  return peak;
}

TEST(TrapezoidPlanner, LinearMoveAtProgrammedFeed) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(0.0, 0.0);
  const auto c = move(CommandKind::linear, vec(0.0, -30.0), 600.0);  // 10 units/s on Z
  ASSERT_TRUE(planner.begin(c, start));
  const double dt = 0.001;
  const Trace r = run(planner, dt);
  expect_ends_exactly(r, c.target);
  check_limits(limits, c.kind, start, r, dt);
  EXPECT_NEAR(peak_speed(r, 1), 10.0, 1e-12);
  EXPECT_EQ(peak_speed(r, 0), 0.0);  // X does not move at all
  for (const auto& s : r.samples) {
    EXPECT_EQ(s.pos[0], 0.0);
  }
  // 30 at 10/s with 2000/s^2: 3 s + 0.005 s.
  const double t = 30.0 / 10.0 + 10.0 / 2000.0;
  const double steps = static_cast<double>(r.samples.size());
  EXPECT_GE(steps * dt, t - 1e-9);
  EXPECT_LT((steps - 1) * dt, t);
}

TEST(TrapezoidPlanner, FeedIsClampedToTheAxisMaximum) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(10.0, 0.0);
  const auto c = move(CommandKind::linear, vec(-10.0, 0.0), 60000.0);  // 1000/s asked, X max 20
  ASSERT_TRUE(planner.begin(c, start));
  const Trace r = run(planner, 0.001);
  expect_ends_exactly(r, c.target);
  check_limits(limits, c.kind, start, r, 0.001);
  EXPECT_NEAR(peak_speed(r, 0), 20.0, 1e-12);
}

TEST(TrapezoidPlanner, TriangleProfileForShortMoves) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(0.0, 0.0);
  // Z: 0.2 at 2000/s^2 peaks at sqrt(400) = 20 < 40.
  const auto c = move(CommandKind::linear, vec(0.0, 0.2), 2400.0);
  ASSERT_TRUE(planner.begin(c, start));
  const double dt = 0.0001;
  const Trace r = run(planner, dt);
  expect_ends_exactly(r, c.target);
  check_limits(limits, c.kind, start, r, dt);
  const double peak = peak_speed(r, 1);
  EXPECT_LT(peak, 20.0 + 1e-9);
  EXPECT_GT(peak, 20.0 - 2000.0 * dt);  // sampled near the apex
  // No cruise: acceleration is never zero before the end.
  for (std::size_t k = 0; k + 1 < r.samples.size(); ++k) {
    EXPECT_NE(r.samples[k].acc[1], 0.0) << k;
  }
  const double t = 2.0 * std::sqrt(0.2 / 2000.0);
  EXPECT_NEAR(static_cast<double>(r.samples.size()) * dt, t, dt);
}

TEST(TrapezoidPlanner, RapidIsLimitedByTheSlowestAxis) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(0.0, 0.0);
  // Equal X and Z travel: X (50/s) limits the path to 50*sqrt(2); Z follows at 50/s too.
  const auto c = move(CommandKind::rapid, vec(100.0, 100.0));
  ASSERT_TRUE(planner.begin(c, start));
  const double dt = 0.001;
  const Trace r = run(planner, dt);
  expect_ends_exactly(r, c.target);
  check_limits(limits, c.kind, start, r, dt);
  EXPECT_NEAR(peak_speed(r, 0), 50.0, 1e-9);
  EXPECT_NEAR(peak_speed(r, 1), 50.0, 1e-9);
  // X's acceleration (500) also limits the path.
  double peak_acc = 0.0;
  for (const auto& s : r.samples) {
    peak_acc = std::max(peak_acc, std::fabs(s.acc[0]));
  }
  EXPECT_NEAR(peak_acc, 500.0, 1e-9);
  const double t = analytic_time(expected_path_limits(limits, start, c));
  EXPECT_NEAR(t, 100.0 / 50.0 + 50.0 / 500.0, 1e-12);
  EXPECT_NEAR(static_cast<double>(r.samples.size()) * dt, t, dt);
}

TEST(TrapezoidPlanner, RapidIgnoresFeed) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const auto c = move(CommandKind::rapid, vec(0.0, 50.0), 1.0);
  ASSERT_TRUE(planner.begin(c, vec(0.0, 0.0)));
  const Trace r = run(planner, 0.001);
  expect_ends_exactly(r, c.target);
  EXPECT_NEAR(peak_speed(r, 1), 200.0, 1e-9);
}

TEST(TrapezoidPlanner, PathPointsStayOnTheSegment) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(1.0, 2.0, 3.0);
  const auto c = move(CommandKind::linear, vec(4.0, -2.0, 15.0), 3000.0);
  ASSERT_TRUE(planner.begin(c, start));
  const Trace r = run(planner, 0.001);
  expect_ends_exactly(r, c.target);
  double last_fraction = 0.0;
  for (const auto& s : r.samples) {
    const double f = (s.pos[2] - 3.0) / 12.0;
    EXPECT_GE(f, last_fraction - 1e-15);
    EXPECT_LE(f, 1.0);
    EXPECT_NEAR(s.pos[0], 1.0 + 3.0 * f, 1e-12);
    EXPECT_NEAR(s.pos[1], 2.0 - 4.0 * f, 1e-12);
    last_fraction = f;
  }
}

TEST(TrapezoidPlanner, DwellLastsWholeCycles) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(1.5, -2.5, 7.0);
  struct Case {
    double dwell_s;
    double dt;
    std::size_t cycles;
  };
  for (const Case& k :
       {Case{0.5, 0.001, 500}, Case{0.0025, 0.001, 3}, Case{0.0005, 0.001, 1}, Case{0.0, 0.001, 1},
        Case{1.5, 0.002, 750}, Case{0.3, 0.001, 300}, Case{2.0, 0.001, 2000}}) {
    SCOPED_TRACE(k.dwell_s);
    CanonicalCommand c;
    c.kind = CommandKind::dwell;
    c.dwell_s = k.dwell_s;
    c.target = start;
    ASSERT_TRUE(planner.begin(c, start));
    const Trace r = run(planner, k.dt);
    ASSERT_TRUE(r.done);
    EXPECT_EQ(r.samples.size(), k.cycles);
    for (const auto& s : r.samples) {
      EXPECT_TRUE(bit_identical(s.pos, start));
      EXPECT_TRUE(bit_identical(s.vel, AxisVector{}));
    }
  }
}

TEST(TrapezoidPlanner, ProgramEndIsDoneAtOnce) {
  TrapezoidPlanner planner(3, lathe_limits());
  CanonicalCommand c;
  c.kind = CommandKind::program_end;
  c.end_code = 30;
  const AxisVector start = vec(3.0, 4.0, 5.0);
  ASSERT_TRUE(planner.begin(c, start));
  MotionSample s;
  EXPECT_EQ(planner.step(0.001, s), StepResult::block_done);
  EXPECT_TRUE(bit_identical(s.pos, start));
  EXPECT_TRUE(bit_identical(s.vel, AxisVector{}));
}

TEST(TrapezoidPlanner, ZeroLengthMoveIsDoneAtOnce) {
  TrapezoidPlanner planner(3, lathe_limits());
  const AxisVector start = vec(3.0, 4.0, 5.0);
  for (auto kind : {CommandKind::rapid, CommandKind::linear}) {
    const auto c = move(kind, start, 100.0);
    ASSERT_TRUE(planner.begin(c, start));
    MotionSample s;
    EXPECT_EQ(planner.step(0.001, s), StepResult::block_done);
    EXPECT_TRUE(bit_identical(s.pos, c.target));
  }
}

TEST(TrapezoidPlanner, StepAfterTheEndHoldsTheEndPoint) {
  TrapezoidPlanner planner(3, lathe_limits());
  const auto c = move(CommandKind::rapid, vec(0.1, 0.2));
  ASSERT_TRUE(planner.begin(c, vec(0.0, 0.0)));
  const Trace r = run(planner, 0.001);
  ASSERT_TRUE(r.done);
  MotionSample s;
  EXPECT_EQ(planner.step(0.001, s), StepResult::block_done);
  EXPECT_TRUE(bit_identical(s.pos, c.target));
}

TEST(TrapezoidPlanner, StepBeforeAnyBlockIsDone) {
  TrapezoidPlanner planner(2, {{1, 1, 1}, {1, 1, 1}});
  MotionSample s;
  s.pos[0] = 42.0;
  EXPECT_EQ(planner.step(0.001, s), StepResult::block_done);
  EXPECT_EQ(s.pos[0], 0.0);
}

TEST(TrapezoidPlanner, RejectsWhatItCannotPlanAndKeepsTheCurrentBlock) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  const AxisVector start = vec(0.0, 0.0);
  const auto good = move(CommandKind::linear, vec(0.0, 5.0), 1200.0);
  ASSERT_TRUE(planner.begin(good, start));
  MotionSample s;
  ASSERT_EQ(planner.step(0.001, s), StepResult::moving);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, vec(0.0, 1.0), 0.0), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, vec(0.0, 1.0), -5.0), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, vec(0.0, 1.0), nan), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, vec(0.0, 1.0), inf), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, start, 0.0), start));  // zero length too
  EXPECT_FALSE(planner.begin(move(CommandKind::rapid, vec(nan, 1.0)), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::rapid, vec(0.0, inf)), start));
  EXPECT_FALSE(planner.begin(move(CommandKind::rapid, vec(1.0, 1.0)), vec(inf, 0.0)));
  EXPECT_FALSE(planner.begin(move(CommandKind::rapid, vec(1e308, 0.0)), vec(-1e308, 0.0)));
  CanonicalCommand dwell;
  dwell.kind = CommandKind::dwell;
  dwell.dwell_s = -1.0;
  EXPECT_FALSE(planner.begin(dwell, start));
  dwell.dwell_s = nan;
  EXPECT_FALSE(planner.begin(dwell, start));

  // The rejected commands changed nothing: the good block runs on to its own end.
  const Trace r = run(planner, 0.001);
  expect_ends_exactly(r, good.target);
}

TEST(TrapezoidPlanner, AxisWithoutRateCannotMove) {
  TrapezoidPlanner planner(2, {{0.0, 0.0, 100.0}, {10.0, 10.0, 100.0}});
  EXPECT_FALSE(planner.begin(move(CommandKind::rapid, vec(1.0, 1.0)), vec(0.0, 0.0)));
  EXPECT_FALSE(planner.begin(move(CommandKind::linear, vec(1.0, 0.0), 60.0), vec(0.0, 0.0)));
  // The other axis alone is fine.
  EXPECT_TRUE(planner.begin(move(CommandKind::linear, vec(0.0, 1.0), 60.0), vec(0.0, 0.0)));
}

TEST(TrapezoidPlanner, ConstructorChecksLimits) {
  EXPECT_THROW(TrapezoidPlanner(3, {{1, 1, 1}}), std::invalid_argument);
  EXPECT_THROW(TrapezoidPlanner(interp::kMaxChannelAxes + 1,
                                std::vector<AxisLimits>(interp::kMaxChannelAxes + 1, {1, 1, 1})),
               std::invalid_argument);
  EXPECT_THROW(TrapezoidPlanner(1, {{-1, 1, 1}}), std::invalid_argument);
  EXPECT_THROW(TrapezoidPlanner(1, {{1, std::numeric_limits<double>::infinity(), 1}}),
               std::invalid_argument);
}

TEST(TrapezoidPlanner, AxesBeyondTheChannelAreUntouched) {
  TrapezoidPlanner planner(2, {{10, 10, 100}, {10, 10, 100}});
  AxisVector start{};
  start[5] = 9.0;
  AxisVector target{};
  target[0] = 1.0;
  target[5] = 123.0;  // not a channel axis: ignored
  ASSERT_TRUE(planner.begin(move(CommandKind::rapid, target), start));
  const Trace r = run(planner, 0.001);
  ASSERT_TRUE(r.done);
  for (const auto& s : r.samples) {
    EXPECT_EQ(s.pos[5], 9.0);
    EXPECT_EQ(s.vel[5], 0.0);
  }
  EXPECT_EQ(r.samples.back().pos[0], 1.0);
}

TEST(TrapezoidPlanner, ThousandRandomMovesEndOnTargetWithinLimits) {
  const auto limits = lathe_limits();
  TrapezoidPlanner planner(3, limits);
  std::mt19937 rng(20240611u);
  std::uniform_real_distribution<double> coord(-60.0, 60.0);
  std::uniform_real_distribution<double> tiny(-1e-3, 1e-3);
  std::uniform_real_distribution<double> feed(300.0, 12000.0);
  std::uniform_int_distribution<int> pick(0, 7);
  AxisVector pos = vec(0.0, 0.0, 0.0);
  std::size_t triangles = 0;
  std::size_t total_samples = 0;
  for (int m = 0; m < 1000; ++m) {
    SCOPED_TRACE(m);
    const int mask = pick(rng);
    AxisVector target = pos;
    const bool short_move = pick(rng) == 0;
    for (std::size_t i = 0; i < 3; ++i) {
      if ((mask >> i) & 1) {
        target[i] = short_move ? pos[i] + tiny(rng) : coord(rng);
      }
    }
    const auto kind = pick(rng) < 3 ? CommandKind::rapid : CommandKind::linear;
    const auto c = move(kind, target, feed(rng));
    const double dt = pick(rng) < 4 ? 0.001 : 0.002;
    ASSERT_TRUE(planner.begin(c, pos));
    const Trace r = run(planner, dt, 1'000'000);
    total_samples += r.samples.size();
    expect_ends_exactly(r, target);
    check_limits(limits, kind, pos, r, dt);
    const PathLimits p = expected_path_limits(limits, pos, c);
    if (p.length > 0.0) {
      const double t = analytic_time(p);
      if (p.length * p.a < p.v * p.v) {
        ++triangles;
      }
      const double steps = static_cast<double>(r.samples.size());
      ASSERT_GE(steps * dt, t - 1e-9 * dt);
      ASSERT_LE(steps * dt, t + dt + 1e-9);
    } else {
      ASSERT_EQ(r.samples.size(), 1u);
    }
    if (testing::Test::HasFatalFailure()) {
      return;
    }
    pos = target;
  }
  EXPECT_GT(triangles, 50u);  // the set covers both profile shapes
  EXPECT_GT(total_samples, 100'000u);
}

}  // namespace
}  // namespace mcnc::motion
