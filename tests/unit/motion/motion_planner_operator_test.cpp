// What the operator does to a running path: feed hold and resume, override steps, single
// block, reset. The path must continue on the same geometry, within the limits, to the same end.
#include "channel/motion/motion_planner.hpp"

#include "tests/unit/motion/motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::motion {
namespace {

using testing::check_limits;
using testing::line_to;
using testing::rapid_to;
using testing::run;
using testing::Sample;
using testing::test_machine;

// A long line, then a zigzag of G64 corners (blended), at F3000 = 50 mm/s.
std::vector<interp::Command> zigzag() {
  std::vector<interp::Command> prog{line_to({100.0, 0.0, 0.0}, 3000.0, 1)};
  for (int i = 1; i <= 12; ++i) {
    prog.push_back(line_to({100.0 + 10.0 * i, (i % 2) * 5.0, 0.0}, 3000.0, i + 1));
  }
  return prog;
}

// Distance from p to the polyline through the reference samples (a fine sampling of the
// planned path).
double distance_to_trace(const std::vector<Sample>& ref, const AxisVector& p) {
  double best = 1e300;
  for (std::size_t k = 1; k < ref.size(); ++k) {
    const AxisVector& a = ref[k - 1].s.pos;
    const AxisVector& b = ref[k].s.pos;
    double len2 = 0.0;
    double dot = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      len2 += (b[i] - a[i]) * (b[i] - a[i]);
      dot += (p[i] - a[i]) * (b[i] - a[i]);
    }
    const double f = len2 > 0.0 ? std::clamp(dot / len2, 0.0, 1.0) : 0.0;
    double d2 = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      const double q = a[i] + f * (b[i] - a[i]) - p[i];
      d2 += q * q;
    }
    best = std::min(best, d2);
  }
  return std::sqrt(best);
}

double worst_distance(const std::vector<Sample>& ref, const std::vector<Sample>& trace) {
  double worst = 0.0;
  for (std::size_t k = 0; k < trace.size(); k += 3) {
    worst = std::max(worst, distance_to_trace(ref, trace[k].s.pos));
  }
  return worst;
}

std::size_t first_cycle_of_block(const std::vector<Sample>& trace, std::uint64_t block) {
  for (std::size_t k = 0; k < trace.size(); ++k) {
    if (trace[k].block == block) {
      return k;
    }
  }
  return 0;
}

TEST(FeedHold, InTheMiddleOfABlendStopsAndResumesOnTheSamePath) {
  const MotionConfig c = test_machine();
  MotionPlanner ref_planner(c, AxisVector{});
  const auto ref = run(ref_planner, zigzag());
  // The blend into block 4 takes tens of cycles at its corner speed: hold 5 cycles into it.
  const std::size_t hold_at = first_cycle_of_block(ref, 4) + 5;
  ASSERT_GT(hold_at, 5U);
  const std::size_t release_at = hold_at + 400;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, zigzag(), [&](std::size_t cycle) {
    CycleInput in;
    in.feed_hold = cycle >= hold_at && cycle < release_at;
    return in;
  });
  // Jerk-limited: the speed may still rise while the acceleration is brought down (at most
  // a^2 / 2j = 1000^2 / 1e5 = 10 mm/s), then only falls until the axes stand.
  std::size_t peak = hold_at;
  for (std::size_t k = hold_at; k < release_at; ++k) {
    peak = trace[k].v > trace[peak].v ? k : peak;
  }
  EXPECT_LE(trace[peak].v, trace[hold_at].v + 10.0);
  bool held = false;
  for (std::size_t k = peak + 1; k < release_at; ++k) {
    EXPECT_LE(trace[k].v, trace[k - 1].v + 1e-9) << k;
    held = held || trace[k].state == MotionState::held;
  }
  EXPECT_TRUE(held);
  EXPECT_EQ(trace[release_at - 1].v, 0.0);
  EXPECT_LE(worst_distance(ref, trace), 1e-5);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  EXPECT_EQ(trace.back().s.pos, ref.back().s.pos);
  EXPECT_GT(trace.size(), ref.size() + 300);
}

TEST(FeedOverride, StepsChangeTheSpeedWithinTheLimitsOnTheSamePath) {
  const MotionConfig c = test_machine();
  MotionPlanner ref_planner(c, AxisVector{});
  const auto ref = run(ref_planner, zigzag());
  MotionPlanner p(c, AxisVector{});
  const auto override_at = [](std::size_t cycle) {
    if (cycle < 200) {
      return 1.0;
    }
    if (cycle < 600) {
      return 1.5;
    }
    if (cycle < 900) {
      return 0.5;
    }
    if (cycle < 1100) {
      return 0.0;  // 0 %: stands still on the path
    }
    return 2.0;
  };
  const auto trace = run(p, zigzag(), [&](std::size_t cycle) {
    CycleInput in;
    in.feed_override = override_at(cycle);
    return in;
  });
  EXPECT_NEAR(trace[550].v, 75.0, 1e-6);
  EXPECT_NEAR(trace[850].v, 25.0, 1e-6);
  EXPECT_EQ(trace[1090].v, 0.0);
  EXPECT_LE(worst_distance(ref, trace), 1e-5);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  EXPECT_EQ(trace.back().s.pos, ref.back().s.pos);
}

TEST(SingleBlock, FromTheStartStopsExactlyOnEveryBlockEnd) {
  const MotionConfig c = test_machine();
  MotionPlanner p(c, AxisVector{});
  p.set_single_block(true);
  const auto prog = zigzag();
  std::vector<AxisVector> stops;
  std::size_t pushed = 0;
  for (std::size_t cycle = 0; cycle < 200000 && !(pushed == prog.size() && p.idle()); ++cycle) {
    while (pushed < prog.size() && p.push(prog[pushed]) == PushResult::accepted) {
      ++pushed;
    }
    const MotionOutput& o = p.step(CycleInput{});
    if (o.state == MotionState::block_stop) {
      stops.push_back(o.sample.pos);
      p.resume();
    }
  }
  ASSERT_EQ(stops.size(), prog.size() - 1);  // the last block end is the program's end
  for (std::size_t i = 0; i < stops.size(); ++i) {
    EXPECT_EQ(stops[i], prog[i].to) << i;
  }
  EXPECT_EQ(p.output().sample.pos, prog.back().to);
}

TEST(SingleBlock, SwitchedOnUnderWayStopsAtABlockEndAndGoesOnAlongThePath) {
  const MotionConfig c = test_machine();
  MotionPlanner ref_planner(c, AxisVector{});
  const auto ref = run(ref_planner, zigzag());
  const std::size_t on_at = first_cycle_of_block(ref, 5) + 20;
  MotionPlanner p(c, AxisVector{});
  bool stopped = false;
  const auto trace =
      run(p, zigzag(), {}, 2'000'000, [&](std::size_t cycle, MotionPlanner& planner) {
        if (cycle == on_at) {
          planner.set_single_block(true);
        }
        if (planner.output().state == MotionState::block_stop && !stopped) {
          stopped = true;
          EXPECT_EQ(planner.output().path_velocity, 0.0);
          planner.set_single_block(false);
          planner.resume();
        }
      });
  EXPECT_TRUE(stopped);
  EXPECT_LE(worst_distance(ref, trace), 1e-5);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  EXPECT_EQ(trace.back().s.pos, ref.back().s.pos);
}

TEST(Reset, StopsWithTheResetDecelerationAndForgetsTheQueue) {
  MotionConfig c = test_machine();
  c.reset_deceleration_scale = 1.0;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, zigzag(), {}, 2'000'000, [](std::size_t cycle, MotionPlanner& planner) {
    if (cycle == 800) {
      planner.reset();
    }
  });
  // run() stops at idle: the queue is gone, the axes stand on the first line.
  ASSERT_TRUE(p.idle());
  EXPECT_EQ(p.queued_blocks(), 0U);
  const AxisVector stop = trace.back().s.pos;
  EXPECT_GT(stop[0], trace[800].s.pos[0]);
  EXPECT_LT(stop[0], 100.0);
  EXPECT_EQ(stop[1], 0.0);
  // 50 mm/s stops in 50/1000 + 1000/25000 = 0.09 s: the line's jerk is halved because it
  // ends in a blend (the curvature step there takes the other half).
  EXPECT_NEAR(static_cast<double>(trace.size() - 801), 90.0, 2.0);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
  // The next program starts from where the axes stand.
  EXPECT_EQ(p.queue_end(), stop);
  const auto next = run(p, {line_to({stop[0], 10.0, 0.0}, 3000.0, 20)});
  EXPECT_EQ(next.back().s.pos[1], 10.0);
}

TEST(Rapid, NotInterpolatedEachAxisAtItsOwnRate) {
  MotionConfig c = test_machine(2);
  c.rapid_interpolated = false;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, {rapid_to({300.0, 10.0}, 1)});
  // Y (10 mm) arrives long before X (300 mm): each at its own profile.
  std::size_t y_done = 0;
  for (std::size_t k = 0; k < trace.size(); ++k) {
    if (trace[k].s.pos[1] == 10.0) {
      y_done = k;
      break;
    }
  }
  EXPECT_LT(y_done, trace.size() / 2);
  EXPECT_EQ(trace.back().s.pos[0], 300.0);
  double vmax = 0.0;
  for (const auto& s : trace) {
    vmax = std::max(vmax, s.s.vel[0]);
  }
  EXPECT_NEAR(vmax, 400.0, 1e-6);  // X reaches its own rapid rate
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.velocity, 1.0 + 1e-9);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
}

TEST(Rapid, NotInterpolatedStopsOnFeedHoldAndGoesOn) {
  MotionConfig c = test_machine(2);
  c.rapid_interpolated = false;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, {rapid_to({300.0, 10.0}, 1)}, [](std::size_t cycle) {
    CycleInput in;
    in.feed_hold = cycle >= 300 && cycle < 800;
    return in;
  });
  EXPECT_EQ(trace[790].state, MotionState::held);
  EXPECT_EQ(trace[790].s.vel[0], 0.0);
  EXPECT_EQ(trace[790].s.pos, trace[700].s.pos);  // standing still
  EXPECT_LT(trace[790].s.pos[0], 300.0);
  EXPECT_EQ(trace.back().s.pos[0], 300.0);
  EXPECT_EQ(trace.back().s.pos[1], 10.0);
  const auto r = check_limits(trace, c, AxisVector{});
  EXPECT_LE(r.acceleration, 1.0 + 1e-6);
  EXPECT_LE(r.jerk, 1.0 + 1e-6);
}

TEST(MotionPlanner, AMillionBlocksEndExactlyWithoutDrift) {
  // 1 000 000 short G64 moves along a gentle wave: positions come from each segment's own end
  // points, never from summed steps, so the end is exact.
  MotionConfig c = test_machine(2);
  MotionPlanner p(c, AxisVector{});
  AxisVector pos{};
  std::uint64_t n = 0;
  std::size_t cycles = 0;
  while (n < 1'000'000 || !p.idle()) {
    while (n < 1'000'000) {
      AxisVector to = pos;
      to[0] += 0.05;
      to[1] = 5.0 * std::sin(to[0] / 20.0);
      if (p.push(line_to(to, 12000.0, n + 1)) != PushResult::accepted) {
        break;
      }
      pos = to;
      ++n;
    }
    p.step(CycleInput{});
    ++cycles;
    ASSERT_LT(cycles, 5'000'000U);
  }
  EXPECT_EQ(p.output().sample.pos, pos);
  EXPECT_EQ(p.output().completed_block, 1'000'000U);
}

}  // namespace
}  // namespace mcnc::motion

namespace mcnc::motion {
namespace {

using testing::arc_to;

// Feed hold pressed at every cycle of a stretch: each held run must keep the limits, never go
// back, and stand on the path before the corner it had to stop at.
TEST(FeedHold, AcrossARunBoundaryTheStopGoesOnWhereItIs) {
  const MotionConfig c = test_machine();
  const std::vector<interp::Command> prog{line_to({50.0, 0.0, 0.0}, 12000.0, 1),
                                          line_to({100.0, 0.0, 0.0}, 6000.0, 2)};
  for (std::size_t hold_at = 330; hold_at < 420; hold_at += 3) {
    MotionPlanner p(c, AxisVector{});
    const auto trace = run(p, prog, [&](std::size_t cycle) {
      CycleInput in;
      in.feed_hold = cycle >= hold_at && cycle < hold_at + 300;
      return in;
    });
    const auto r = check_limits(trace, c, AxisVector{});
    EXPECT_LE(r.acceleration, 1.0 + 1e-6) << hold_at;
    EXPECT_LE(r.jerk, 1.0 + 1e-6) << hold_at;
    for (std::size_t k = 1; k < trace.size(); ++k) {
      ASSERT_GE(trace[k].s.pos[0], trace[k - 1].s.pos[0]) << hold_at << " cycle " << k;
    }
    EXPECT_EQ(trace.back().s.pos[0], 100.0);
  }
}

TEST(FeedHold, NeverRunsThroughACornerThePlanStopsAt) {
  // A line into an arc at a right angle: the plan stops at X20. A hold pressed before it stops
  // on the line, within the limits.
  const MotionConfig c = test_machine();
  const std::vector<interp::Command> prog{line_to({20.0, 0.0, 0.0}, 6000.0, 1),
                                          arc_to({30.0, 0.0, 0.0}, 25.0, 0.0, true, 6000.0, 2)};
  for (std::size_t hold_at = 150; hold_at < 330; hold_at += 4) {
    MotionPlanner p(c, AxisVector{});
    const auto trace = run(p, prog, [&](std::size_t cycle) {
      CycleInput in;
      in.feed_hold = cycle >= hold_at && cycle < hold_at + 400;
      return in;
    });
    ASSERT_GT(trace.size(), hold_at + 390);
    if (trace[hold_at].s.pos[0] < 20.0) {  // pressed before the axes reached the corner
      const AxisVector& held = trace[hold_at + 390].s.pos;
      EXPECT_LE(held[0], 20.0 + 1e-9) << hold_at;
      EXPECT_EQ(held[1], 0.0) << hold_at;
    }
    const auto r = check_limits(trace, c, AxisVector{});
    EXPECT_LE(r.acceleration, 1.0 + 1e-6) << hold_at;
    EXPECT_LE(r.jerk, 1.0 + 1e-6) << hold_at;
  }
}

TEST(FeedHold, DuringASingleBlockStopLeavesHoldWorking) {
  const MotionConfig c = test_machine();
  std::vector<interp::Command> prog;
  for (int i = 1; i <= 6; ++i) {
    prog.push_back(line_to({10.0 * i, 0.0, 0.0}, 6000.0, static_cast<std::uint64_t>(i)));
  }
  MotionPlanner p(c, AxisVector{});
  std::size_t next = 0;
  bool hold = false;
  int phase = 0;
  double held_x = -1.0;
  for (std::size_t cycle = 0; cycle < 100000 && !(next == prog.size() && p.idle()); ++cycle) {
    while (next < prog.size() && p.push(prog[next]) == PushResult::accepted) {
      ++next;
    }
    if (cycle == 50) {
      p.set_single_block(true);
    }
    CycleInput in;
    in.feed_hold = hold;
    const MotionOutput& o = p.step(in);
    if (phase == 0 && o.state == MotionState::block_stop) {
      hold = true;  // hold pressed while stopped at the block end...
      phase = 1;
    } else if (phase == 1 && o.state == MotionState::block_stop) {
      hold = false;  // ... released, then cycle start
      p.set_single_block(false);
      p.resume();
      phase = 2;
    } else if (phase == 2 && o.path_velocity > 50.0) {
      hold = true;  // a later hold must still stop the axes
      phase = 3;
    } else if (phase == 3 && o.state == MotionState::held) {
      held_x = o.sample.pos[0];
      phase = 4;
    } else if (phase == 4 && hold) {
      EXPECT_EQ(o.sample.pos[0], held_x) << "cycle " << cycle;
      hold = cycle < 2000;  // held for a while, then released to the end
    }
  }
  EXPECT_EQ(phase, 4);
  EXPECT_GT(held_x, 0.0);
  EXPECT_LT(held_x, 60.0);
  EXPECT_EQ(p.output().sample.pos[0], 60.0);
}

TEST(Restart, ForgetsTheBlocksOfTheLastRun) {
  const MotionConfig c = test_machine();
  MotionPlanner p(c, AxisVector{});
  run(p, {line_to({10.0, 0.0, 0.0}, 6000.0, 1), line_to({20.0, 0.0, 0.0}, 6000.0, 2)});
  EXPECT_EQ(p.output().completed_block, 2U);
  p.restart(p.output().sample.pos);
  EXPECT_EQ(p.output().completed_block, 0U);
  EXPECT_EQ(p.output().block, 0U);
}

TEST(Reset, StopsAThreadAndAnAxisWiseRapidWithinTheLimits) {
  MotionConfig c = test_machine(2);
  c.rapid_interpolated = false;
  interp::Command thread;
  thread.op = interp::Op::thread;
  thread.to = {0.0, -60.0};
  thread.lead = 2.0;
  thread.n = 1;
  for (const interp::Command& cmd : {thread, rapid_to({300.0, 10.0}, 1)}) {
    MotionPlanner p(c, AxisVector{});
    const auto trace = run(
        p, {cmd},
        [](std::size_t cycle) {
          CycleInput in = testing::steady_spindle(cycle);
          return in;
        },
        2'000'000,
        [](std::size_t cycle, MotionPlanner& planner) {
          if (cycle == 400) {
            planner.reset();
          }
        });
    ASSERT_TRUE(p.idle());
    const auto r = check_limits(trace, c, AxisVector{});
    EXPECT_LE(r.acceleration, 1.0 + 1e-6);
    EXPECT_LE(r.jerk, 1.0 + 1e-6);
    EXPECT_GT(trace.size(), 405U);  // it took a ramp to stop
  }
}

TEST(Dwell, InRevolutionsPausesUnderFeedHold) {
  const MotionConfig c = test_machine(2);
  interp::Command revs;
  revs.op = interp::Op::dwell;
  revs.seconds = 2.0;
  revs.in_revs = true;
  revs.n = 1;
  MotionPlanner p(c, AxisVector{});
  const auto trace = run(p, {revs}, [](std::size_t cycle) {
    CycleInput in = testing::steady_spindle(cycle);
    in.feed_hold = cycle >= 50 && cycle < 150;
    return in;
  });
  // Two revolutions at 600 rpm are 200 cycles; 100 held cycles do not count.
  EXPECT_NEAR(static_cast<double>(trace.size()), 300.0, 2.0);
}

}  // namespace
}  // namespace mcnc::motion
