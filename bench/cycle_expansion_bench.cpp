// Time to expand the heaviest canned cycles (issue 4): G71 roughing over a 200-element contour
// and a G76 thread of 50 roughing passes. Not a test; figures in bench/README.md.
#include "channel/interp/cycles/multiple_thread.hpp"
#include "channel/interp/cycles/rough_turning.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

using mcnc::interp::path::MoveKind;
using mcnc::interp::path::PlaneMove;
using mcnc::interp::path::PlanePath;
using mcnc::interp::path::Point2;

// An OD contour (Z falling, X rising) of `elements` moves: a G00 to the first diameter, then
// feeds and convex arcs in turn, each element 0.5 mm long in Z.
PlanePath contour(int elements) {
  PlanePath path;
  PlaneMove first;
  first.kind = MoveKind::rapid;
  first.to = {2.0, 10.0};
  first.source = 0;
  path.push_back(first);
  Point2 at = first.to;
  for (int i = 1; i < elements; ++i) {
    PlaneMove m;
    m.source = i;
    const Point2 to{at.a - 0.5, at.b + 0.1};
    if (i % 2 == 0) {
      m.kind = MoveKind::arc;
      m.ccw = false;
      // The centre on the chord's right (a CW arc bulging outwards) at radius 2.
      const Point2 mid{(at.a + to.a) / 2.0, (at.b + to.b) / 2.0};
      const double dx = to.a - at.a;
      const double dy = to.b - at.b;
      const double chord = std::hypot(dx, dy);
      const double h = std::sqrt(4.0 - chord * chord / 4.0);
      m.center = {mid.a + h * dy / chord, mid.b - h * dx / chord};
    } else {
      m.kind = MoveKind::feed;
    }
    m.to = to;
    path.push_back(m);
    at = to;
  }
  return path;
}

void g71_200_elements(benchmark::State& state) {
  const PlanePath c = contour(200);
  mcnc::interp::cycles::RoughingParams p;
  p.depth = 0.5;
  p.retract = 0.5;
  p.allowance_a = 0.1;
  p.allowance_b = 0.2;
  p.feed = 0.25;
  p.max_elements = 1000;
  const Point2 start{3.0, 40.0};
  std::size_t moves = 0;
  for (auto _ : state) {
    PlanePath out;
    out.reserve(4096);
    if (mcnc::interp::cycles::expand_rough_turning(start, c, p, out)) {
      state.SkipWithError("G71 expansion failed");
      break;
    }
    moves = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["moves"] = static_cast<double>(moves);
}
BENCHMARK(g71_200_elements)->Unit(benchmark::kMicrosecond);

void g76_50_passes(benchmark::State& state) {
  mcnc::interp::cycles::MultipleThread t;
  t.end = {-40.0, 18.0};
  t.first_depth = 0.1;
  t.height = 0.1 * std::sqrt(50.0);  // depths 0.1 * sqrt(n): the 50th pass reaches the height
  t.min_depth = 0.0;
  t.finish_passes = 1;
  t.lead = 1.0;
  t.chamfer = 1.0;
  const Point2 start{5.0, 21.0};
  std::size_t moves = 0;
  for (auto _ : state) {
    PlanePath out;
    out.reserve(512);
    if (mcnc::interp::cycles::expand_multiple_thread(start, t, out)) {
      state.SkipWithError("G76 expansion failed");
      break;
    }
    moves = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["moves"] = static_cast<double>(moves);
}
BENCHMARK(g76_50_passes)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
