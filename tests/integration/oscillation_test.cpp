// G81.1 / G80.1 oscillation through the runtime (spec dafeng L2454-2505): the small lathe with
// Z1 enabled for oscillation (param 5700.1) runs the spec's example in lockstep with a 20 mm
// stroke. The axis node of Z1 is commanded the strokes: it turns at 20 and 0 while X1 feeds,
// G80.1 Z0 ends it at Z0, and the block after G80.1 starts only once Z1 stands there.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

void enable_oscillation(const TestMachine& machine) {
  ASSERT_TRUE(insert_in_machine_file(machine, "  - name: Z1\n", "    oscillation: true\n"));
}

struct Point {
  std::uint64_t cycle = 0;
  double cmd = 0.0;
};

TEST(Oscillation, TheAxisTurnsAtItsDeadPointsAndG801EndsItAtItsPosition) {
  TestMachine machine("small_lathe.yaml", 116);
  enable_oscillation(machine);
  const auto trace =
      run_to_clean_end(machine, "tests/integration/programs/oscillation/spec_example.nc",
                       {"--trace-pos-every", "1"});
  EXPECT_TRUE(events(trace, "alarm").empty());
  std::vector<Point> z;
  std::vector<Point> x;
  for (const auto& p : events(trace, "pos", "Z1")) {
    z.push_back({p["cycle"].get<std::uint64_t>(), p["cmd"].get<double>()});
  }
  for (const auto& p : events(trace, "pos", "X1")) {
    x.push_back({p["cycle"].get<std::uint64_t>(), p["cmd"].get<double>()});
  }
  ASSERT_GT(z.size(), 100U);
  // The turning points: where Z1's commanded position stops rising or falling.
  std::vector<Point> turns;
  int dir = 0;
  for (std::size_t i = 1; i < z.size(); ++i) {
    const double d = z[i].cmd - z[i - 1].cmd;
    const int now = d > 1e-9 ? 1 : d < -1e-9 ? -1 : 0;
    if (now != 0 && dir != 0 && now != dir) {
      turns.push_back(z[i - 1]);
    }
    dir = now != 0 ? now : dir;
  }
  // 20 mm strokes at 2000 mm/min take 0.94 s; X1 feeds 0.5 mm at 10 mm/min for 3 s: the axis
  // turned several times, at 20 and at 0 in turn, and never went beyond them.
  ASSERT_GE(turns.size(), 3U);
  for (std::size_t k = 0; k < turns.size(); ++k) {
    EXPECT_NEAR(turns[k].cmd, k % 2 == 0 ? 20.0 : 0.0, 1e-4)
        << "turn " << k << " at cycle " << turns[k].cycle;
  }
  for (const Point& p : z) {
    EXPECT_GE(p.cmd, -1e-4);
    EXPECT_LE(p.cmd, 20.0 + 1e-4);
  }
  // It oscillated while X1 fed from 25.5 (X51, after the rapid there) to 25 (X50), before
  // G00 X100 took it away.
  std::uint64_t feed_start = 0;
  std::uint64_t feed_end = 0;
  bool at_x51 = false;
  bool at_x50 = false;
  for (const Point& p : x) {
    at_x51 = at_x51 || std::fabs(p.cmd - 25.5) < 1e-9;
    if (at_x51 && feed_start == 0 && p.cmd < 25.5 - 1e-6) {
      feed_start = p.cycle;
    }
    at_x50 = at_x50 || (feed_start != 0 && std::fabs(p.cmd - 25.0) < 1e-9);
    if (at_x50 && feed_end == 0 && p.cmd > 25.0 + 1e-6) {
      feed_end = p.cycle;
    }
  }
  ASSERT_GT(feed_start, 0U);
  ASSERT_GT(feed_end, feed_start);
  std::size_t turns_while_feeding = 0;
  for (const Point& t : turns) {
    turns_while_feeding += t.cycle > feed_start && t.cycle < feed_end ? 1 : 0;
  }
  EXPECT_GE(turns_while_feeding, 2U);
  // G80.1 Z0: Z1 ends at 0 and stays there to the end.
  EXPECT_NEAR(z.back().cmd, 0.0, 1e-9);
  std::uint64_t z_rest = 0;
  for (std::size_t i = z.size(); i-- > 0;) {
    if (std::fabs(z[i].cmd) > 1e-9) {
      z_rest = z[i].cycle + 1;
      break;
    }
  }
  ASSERT_GT(z_rest, feed_end);
  // G00 X60 (line 7) starts after that: X1 leaves 50 only once Z1 stands at 0.
  std::uint64_t x_leaves_50 = 0;
  bool at_x100 = false;
  for (const Point& p : x) {
    at_x100 = at_x100 || (p.cycle > feed_end && std::fabs(p.cmd - 50.0) < 1e-9);
    if (at_x100 && x_leaves_50 == 0 && p.cmd < 50.0 - 1e-6) {
      x_leaves_50 = p.cycle;
    }
  }
  ASSERT_GT(x_leaves_50, 0U);
  EXPECT_GT(x_leaves_50, z_rest);
  bool after_g801 = false;
  for (const auto& b : events(trace, "block", "CH1")) {
    if (b["line"] == 7) {
      after_g801 = true;
      EXPECT_GE(b["cycle"].get<std::uint64_t>(), z_rest);
    }
  }
  EXPECT_TRUE(after_g801);
}

}  // namespace
}  // namespace mcnc::test
