// The look-ahead planner's costs and the feed it achieves (bench/README.md has the figures and
// the command). Not a test: it measures.
#include "channel/motion/motion_planner.hpp"
#include "tests/unit/motion/motion_test_support.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

namespace {

using mcnc::interp::Command;
using mcnc::motion::AxisVector;
using mcnc::motion::CycleInput;
using mcnc::motion::MotionConfig;
using mcnc::motion::MotionPlanner;
using mcnc::motion::PushResult;

// The machine of the motion tests, with its own window.
MotionConfig machine(std::size_t axes, std::size_t window) {
  MotionConfig c = mcnc::motion::testing::test_machine(axes);
  c.lookahead_blocks = window;
  return c;
}

Command line(const AxisVector& to, double feed, std::uint64_t n) {
  return mcnc::motion::testing::line_to(to, feed, n);
}

// A CAM-like finishing path: 0.02-0.2 mm segments along a surface of waves in X, Y and Z, with
// the short segments where it bends (as a CAM system's chord tolerance makes them).
std::vector<Command> cam_program(std::size_t blocks, std::size_t axes) {
  std::vector<Command> out;
  out.reserve(blocks);
  AxisVector p{};
  double u = 0.0;
  for (std::size_t n = 1; n <= blocks; ++n) {
    const double bend = std::fabs(std::sin(u * 0.7));
    const double step = 0.02 + 0.18 * (1.0 - bend);
    u += step / 10.0;
    AxisVector to{};
    to[0] = 10.0 * u;
    to[1] = 8.0 * std::sin(u * 1.3);
    if (axes > 2) {
      to[2] = 2.0 * std::cos(u * 0.9);
    }
    if (axes > 3) {
      to[3] = 30.0 * std::sin(u * 0.5);  // a rotary axis, degrees
    }
    out.push_back(line(to, 6000.0, n));
    p = to;
  }
  return out;
}

// Look-ahead planning alone: every block of a 100 000-segment program pushed into a window
// that holds them all (blend, limits, runs), with the backward pass after every `batch` blocks
// (a channel pushes what the window takes once per cycle: a few blocks).
void BM_LookaheadPlanning(benchmark::State& state) {
  const auto program = cam_program(100000, 3);
  const auto batch = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    MotionPlanner p(machine(3, program.size() + 8), AxisVector{});
    std::size_t k = 0;
    for (const Command& c : program) {
      if (p.push(c) != PushResult::accepted) {
        state.SkipWithError("window full");
        return;
      }
      if (++k % batch == 0) {
        p.update_lookahead();
      }
    }
    p.update_lookahead();
    benchmark::DoNotOptimize(p.queued_blocks());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(program.size()));
}
BENCHMARK(BM_LookaheadPlanning)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMillisecond);

// The whole program through a 200-block window: push as the window takes blocks, one step per
// cycle. Reports blocks per second of computing and the machine time the program takes.
void BM_ProgramThroughWindow(benchmark::State& state) {
  const auto program = cam_program(100000, 3);
  std::size_t cycles = 0;
  for (auto _ : state) {
    MotionPlanner p(machine(3, 200), AxisVector{});
    std::size_t next = 0;
    cycles = 0;
    while (next < program.size() || !p.idle()) {
      while (next < program.size() && p.push(program[next]) == PushResult::accepted) {
        ++next;
      }
      benchmark::DoNotOptimize(p.step(CycleInput{}));
      ++cycles;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(program.size()));
  state.counters["machine_s"] = static_cast<double>(cycles) * 0.001;
}
BENCHMARK(BM_ProgramThroughWindow)->Unit(benchmark::kMillisecond);

// One interpolation cycle of a 4-axis channel (the window already full): median and p99 of the
// step() call, timed one by one.
void BM_InterpolationCycle4Axes(benchmark::State& state) {
  const auto program = cam_program(20000, 4);
  std::vector<double> ns;
  ns.reserve(1 << 20);
  for (auto _ : state) {
    MotionPlanner p(machine(4, program.size() + 8), AxisVector{});
    for (const Command& c : program) {
      p.push(c);
    }
    while (!p.idle() || ns.empty()) {
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(p.step(CycleInput{}));
      const auto t1 = std::chrono::steady_clock::now();
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    }
  }
  std::sort(ns.begin(), ns.end());
  state.counters["median_us"] = ns[ns.size() / 2] / 1000.0;
  state.counters["p99_us"] = ns[ns.size() * 99 / 100] / 1000.0;
  state.counters["cycles"] = static_cast<double>(ns.size());
}
BENCHMARK(BM_InterpolationCycle4Axes)->Unit(benchmark::kMillisecond)->Iterations(1);

// The feed on a full circle of 0.1 mm chords at F6000 (100 mm/s): achieved (mean over the
// middle half of the circle) as a share of the programmed feed and of what the limits allow:
// sqrt(a r), the centripetal limit of the axes' acceleration.
void BM_CircleOfShortSegments(benchmark::State& state) {
  const double r = static_cast<double>(state.range(0));
  const auto chords = static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi * r / 0.1));
  std::vector<Command> program;
  for (std::size_t i = 1; i <= chords; ++i) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(chords);
    program.push_back(line({r * std::cos(t), r * std::sin(t)}, 6000.0, i));
  }
  double mean = 0.0;
  for (auto _ : state) {
    MotionPlanner p(machine(2, 2000), AxisVector{r, 0.0});
    std::size_t next = 0;
    std::vector<double> v;
    while (next < program.size() || !p.idle()) {
      while (next < program.size() && p.push(program[next]) == PushResult::accepted) {
        ++next;
      }
      v.push_back(p.step(CycleInput{}).path_velocity);
    }
    double sum = 0.0;
    for (std::size_t k = v.size() / 4; k < 3 * v.size() / 4; ++k) {
      sum += v[k];
    }
    mean = sum / static_cast<double>(v.size() / 2);
  }
  const double allowed = std::min(100.0, std::sqrt(1000.0 * r));
  state.counters["feed_mm_s"] = mean;
  state.counters["pct_programmed"] = 100.0 * mean / 100.0;
  state.counters["pct_limits_allow"] = 100.0 * mean / allowed;
}
BENCHMARK(BM_CircleOfShortSegments)->Arg(5)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
