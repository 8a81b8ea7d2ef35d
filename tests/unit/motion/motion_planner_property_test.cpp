// Property tests of the look-ahead planner over seeded random programs: lines, arcs and helices,
// runs of short CAM-like segments, reversals, exact stops and rapids. Every program must keep
// every axis within its limits on the cycle samples, stay within the blend tolerance of the
// programmed path, end exact-stop blocks exactly on their end points and end the program on its
// end point.
#include "channel/motion/motion_planner.hpp"

#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace mcnc::motion {
namespace {

using testing::check_limits;
using testing::run;
using testing::test_machine;

// The programmed geometry of one block, for the deviation check.
struct Programmed {
  bool arc = false;
  AxisVector from{};
  AxisVector to{};
  double ca = 0.0;
  double cb = 0.0;
  double radius = 0.0;
  bool exact_stop = false;
};

double distance_to(const Programmed& g, const AxisVector& p, std::size_t axes) {
  if (!g.arc) {
    double len2 = 0.0;
    double dot = 0.0;
    for (std::size_t i = 0; i < axes; ++i) {
      const double d = g.to[i] - g.from[i];
      len2 += d * d;
      dot += (p[i] - g.from[i]) * d;
    }
    const double f = len2 > 0.0 ? std::clamp(dot / len2, 0.0, 1.0) : 0.0;
    double dist2 = 0.0;
    for (std::size_t i = 0; i < axes; ++i) {
      const double q = g.from[i] + f * (g.to[i] - g.from[i]) - p[i];
      dist2 += q * q;
    }
    return std::sqrt(dist2);
  }
  // Arcs of these programs lie in the plane of axes 0 and 1 at a fixed axis 2 (no helix).
  const double r = std::hypot(p[0] - g.ca, p[1] - g.cb);
  return std::hypot(r - g.radius, p[2] - g.from[2]);
}

struct RandomProgram {
  std::vector<interp::Command> commands;
  std::vector<Programmed> geometry;  // per command
};

RandomProgram random_program(std::uint32_t seed, std::size_t blocks) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomProgram out;
  AxisVector pos{};
  AxisVector last_dir{1.0, 0.0, 0.0};
  std::uint64_t n = 0;
  const auto add = [&](interp::Command c, const Programmed& g) {
    c.n = ++n;
    c.line = static_cast<int>(n);
    out.commands.push_back(c);
    out.geometry.push_back(g);
  };
  while (out.commands.size() < blocks) {
    const double pick = unit(rng);
    const double feed = 100.0 + unit(rng) * 8000.0;  // mm/min
    const bool stop = unit(rng) < 0.08;
    if (pick < 0.35) {  // a line
      const double len = 0.05 + 20.0 * unit(rng) * unit(rng);
      const double az = 2.0 * std::numbers::pi * unit(rng);
      const double el = (unit(rng) - 0.5) * 0.6;
      AxisVector to = pos;
      to[0] += len * std::cos(az) * std::cos(el);
      to[1] += len * std::sin(az) * std::cos(el);
      to[2] += len * std::sin(el);
      interp::Command c = testing::line_to(to, feed);
      c.exact_stop = stop;
      Programmed g{false, pos, to, 0, 0, 0, stop};
      add(c, g);
      for (std::size_t i = 0; i < 3; ++i) {
        last_dir[i] = (to[i] - pos[i]) / len;
      }
      pos = to;
    } else if (pick < 0.55) {  // an arc in the plane of axes 0 and 1
      const double r = 0.5 + 15.0 * unit(rng);
      const double phi = 2.0 * std::numbers::pi * unit(rng);
      const double ca = pos[0] - r * std::cos(phi);
      const double cb = pos[1] - r * std::sin(phi);
      const bool ccw = unit(rng) < 0.5;
      const double sweep = (0.2 + 4.5 * unit(rng)) * (ccw ? 1.0 : -1.0);
      AxisVector to = pos;
      to[0] = ca + r * std::cos(phi + sweep);
      to[1] = cb + r * std::sin(phi + sweep);
      interp::Command c = testing::arc_to(to, ca, cb, ccw, feed);
      c.exact_stop = stop;
      Programmed g{true, pos, to, ca, cb, r, stop};
      add(c, g);
      last_dir = {-std::sin(phi + sweep) * (ccw ? 1.0 : -1.0),
                  std::cos(phi + sweep) * (ccw ? 1.0 : -1.0), 0.0};
      pos = to;
    } else if (pick < 0.8) {  // CAM-like: many short segments along a wavy curve
      const std::size_t count = 20 + static_cast<std::size_t>(unit(rng) * 80.0);
      const double step = 0.01 + 0.2 * unit(rng);
      double heading = std::atan2(last_dir[1], last_dir[0]);
      const double bend = (unit(rng) - 0.5) * 0.3;
      for (std::size_t k = 0; k < count && out.commands.size() < blocks; ++k) {
        heading += bend * std::sin(static_cast<double>(k) * 0.2);
        AxisVector to = pos;
        to[0] += step * std::cos(heading);
        to[1] += step * std::sin(heading);
        to[2] += step * 0.05 * std::sin(static_cast<double>(k) * 0.5);
        interp::Command c = testing::line_to(to, feed);
        add(c, Programmed{false, pos, to, 0, 0, 0, false});
        pos = to;
      }
      last_dir = {std::cos(heading), std::sin(heading), 0.0};
    } else if (pick < 0.9) {  // a reversal
      const double len = 0.1 + 5.0 * unit(rng);
      AxisVector to = pos;
      for (std::size_t i = 0; i < 3; ++i) {
        to[i] -= last_dir[i] * len;
        last_dir[i] = -last_dir[i];
      }
      add(testing::line_to(to, feed), Programmed{false, pos, to, 0, 0, 0, false});
      pos = to;
    } else {  // a rapid
      AxisVector to = pos;
      for (std::size_t i = 0; i < 3; ++i) {
        to[i] += (unit(rng) - 0.5) * 40.0;
      }
      add(testing::rapid_to(to), Programmed{false, pos, to, 0, 0, 0, true});
      pos = to;
    }
  }
  return out;
}

void check_program(const MotionConfig& c, std::uint32_t seed) {
  const RandomProgram prog = random_program(seed, 400);
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, prog.commands);
  ASSERT_FALSE(trace.empty());
  ASSERT_NE(trace.back().state, MotionState::fault);
  ASSERT_TRUE(p.idle());

  // Limits, on the samples the drives see (tolerance: rounding only).
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.velocity, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  EXPECT_LE(r.acceleration, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  if (c.jerk_limited) {
    EXPECT_LE(r.jerk, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  }

  // Path deviation: every sample, and the middle of the chord to the next one (what a drive
  // interpolating linearly between setpoints follows), within the blend tolerance of its
  // block or a neighbour.
  const auto deviation = [&](std::uint64_t block, const AxisVector& p) {
    const std::size_t b = block - 1;
    double d = distance_to(prog.geometry[b], p, 3);
    if (b > 0) {
      d = std::min(d, distance_to(prog.geometry[b - 1], p, 3));
    }
    if (b + 1 < prog.geometry.size()) {
      d = std::min(d, distance_to(prog.geometry[b + 1], p, 3));
    }
    return d;
  };
  double worst = 0.0;
  double worst_chord = 0.0;
  for (std::size_t k = 0; k < trace.size(); ++k) {
    const auto& s = trace[k];
    if (s.block == 0) {
      continue;
    }
    worst = std::max(worst, deviation(s.block, s.s.pos));
    if (k + 1 < trace.size() && trace[k + 1].block == s.block) {
      AxisVector mid{};
      for (std::size_t i = 0; i < 3; ++i) {
        mid[i] = (s.s.pos[i] + trace[k + 1].s.pos[i]) / 2.0;
      }
      worst_chord = std::max(worst_chord, deviation(s.block, mid));
    }
  }
  EXPECT_LE(worst, c.path_tolerance + 1e-9);
  EXPECT_LE(worst_chord, c.path_tolerance + 1e-9);

  // Exact-stop blocks end exactly on their end points: some sample is that point.
  for (std::size_t b = 0; b < prog.geometry.size(); ++b) {
    if (!prog.geometry[b].exact_stop) {
      continue;
    }
    bool found = false;
    for (const auto& s : trace) {
      if (s.s.pos == prog.geometry[b].to) {
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << "block " << b + 1;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(trace.back().s.pos[i], prog.geometry.back().to[i], 1e-9);
  }
}

class RandomPrograms : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(RandomPrograms, StayWithinLimitsToleranceAndEndPoints) {
  check_program(test_machine(), GetParam());
}

// Axes with unlike limits, a short window, a faster cycle and a wider tolerance.
TEST_P(RandomPrograms, OnAnUnevenMachine) {
  MotionConfig c = test_machine();
  c.axes[0] = AxisDynamics{100.0, 500.0, 20000.0};
  c.axes[1] = AxisDynamics{300.0, 2000.0, 100000.0};
  c.axes[2] = AxisDynamics{50.0, 200.0, 5000.0};
  c.rapid_rate = {150.0, 500.0, 80.0};
  c.cycle_s = 0.0005;
  c.lookahead_blocks = 20;
  c.path_tolerance = 0.05;
  check_program(c, GetParam());
}

TEST_P(RandomPrograms, Trapezoidal) {
  MotionConfig c = test_machine();
  c.jerk_limited = false;
  check_program(c, GetParam());
}

// The same programs with the operator at the panel: feed holds and override changes (0-200 %)
// at random cycles. Limits, tolerance and the end point must hold all the same.
void check_with_operator(const MotionConfig& c, std::uint32_t seed) {
  const RandomProgram prog = random_program(seed, 150);
  std::mt19937 rng(seed * 7919U);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<std::size_t, CycleInput>> changes;  // from cycle on
  std::size_t at = 0;
  for (int i = 0; i < 200; ++i) {
    at += 20 + static_cast<std::size_t>(unit(rng) * 600.0);
    CycleInput in;
    const double pick = unit(rng);
    in.feed_hold = pick < 0.3;
    in.feed_override = pick < 0.4 ? 1.0 : (pick < 0.5 ? 0.0 : 2.0 * unit(rng));
    changes.emplace_back(at, in);
  }
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, prog.commands, [&](std::size_t cycle) {
    CycleInput in;
    for (const auto& [from, change] : changes) {
      if (from > cycle) {
        break;
      }
      in = change;
    }
    if (cycle > at) {
      in = CycleInput{};  // the operator lets it finish
    }
    return in;
  });
  ASSERT_TRUE(p.idle());
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.velocity, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  EXPECT_LE(r.acceleration, 1.0 + 1e-6) << "cycle " << r.worst_cycle;
  if (c.jerk_limited) {
    EXPECT_LE(r.jerk, 1.0 + 1e-6) << "cycle " << r.worst_jerk_cycle;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(trace.back().s.pos[i], prog.geometry.back().to[i], 1e-9);
  }
}

TEST_P(RandomPrograms, WithRandomHoldsAndOverrides) {
  check_with_operator(test_machine(), GetParam());
}

TEST_P(RandomPrograms, TrapezoidalWithRandomHoldsAndOverrides) {
  MotionConfig c = test_machine();
  c.jerk_limited = false;
  check_with_operator(c, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomPrograms, ::testing::Range(1u, 51u));

}  // namespace
}  // namespace mcnc::motion
