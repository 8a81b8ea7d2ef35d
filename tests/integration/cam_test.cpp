// G51.8 / G50.8 electronic cam through the runtime, in lockstep (spec dafeng §2.6.7): on
// cam_lathe.yaml the channel sends the lift table to X1's axis node, which adds the lift at S1's
// angle to the channel's setpoint every cycle; the program moves X as usual, and G50.8 takes the
// lift off again. A G51.8 on a channel without a cam moves nothing.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

using namespace std::chrono_literals;

// cam_grind.nc's table: #(100 + i) = 0.5 (1 - cos i), i = 0..359 degrees, straight between.
double table_lift(double master_deg) {
  double a = std::fmod(master_deg, 360.0);
  a += a < 0.0 ? 360.0 : 0.0;
  const auto i = static_cast<int>(a);
  const auto point = [](int k) { return 0.5 * (1.0 - std::cos(k * std::numbers::pi / 180.0)); };
  return point(i) + (point((i + 1) % 360) - point(i)) * (a - i);
}

TEST(ElectronicCam, XIsItsProgrammedPathPlusTheTableLiftAtTheSpindlesAngleUntilG508) {
  TestMachine machine("cam_lathe.yaml", 154);
  const auto trace =
      run_to_clean_end(machine, "launch/programs/cam_grind.nc", {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "X1");
  ASSERT_EQ(couples.size(), 1U);
  EXPECT_EQ(couples[0]["kind"], "cam");
  EXPECT_EQ(couples[0]["master"], "S1");
  EXPECT_EQ(couples[0]["refused"], false);
  const auto decouples = events(trace, "decouple", "X1");
  ASSERT_EQ(decouples.size(), 1U);
  EXPECT_EQ(decouples[0]["kind"], "cam");

  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto x1 = axis_positions(trace, "X1", "cmd");
  const auto x1_act = axis_positions(trace, "X1", "act");
  // The dwell of line 7: the channel holds X at 27 (X55 U-1, in radius) while S1 turns at
  // 100 rpm. X1's node commands, for cycle c, the lift at S1's angle extrapolated from its
  // feedback of c - 1 (at constant speed: its angle at c).
  const std::uint64_t dwell = block.at(7);
  const std::uint64_t retract = block.at(8);
  ASSERT_GT(retract, dwell + 400);
  int compared = 0;
  double lowest = 1e9;
  double highest = -1e9;
  for (std::uint64_t c = dwell + 1; c < retract; ++c) {
    const double angle = 2.0 * s1.at(c - 1) - s1.at(c - 2);
    ASSERT_NEAR(x1.at(c), 27.0 + table_lift(angle), 1e-5) << "cycle " << c;
    lowest = std::min(lowest, x1_act.at(c));
    highest = std::max(highest, x1_act.at(c));
    ++compared;
  }
  EXPECT_GT(compared, 400);
  // The axis really moves by the 1 mm of the table over a turn (0.6 s at 100 rpm).
  EXPECT_NEAR(lowest, 27.0, 0.02);
  EXPECT_NEAR(highest, 28.0, 0.02);
  // S1 turns at 100 rpm.
  EXPECT_NEAR((s1.at(retract - 1) - s1.at(dwell + 1)) / ((retract - 2 - dwell) * 0.002), 600.0,
              1.0);

  // G50.8 (line 9) takes the lift off within X's limits, and the program goes on (M30) only
  // once it is off: from then on X stands at 32 (U10 on from 27), its programmed position.
  const std::uint64_t off = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_GT(off, block.at(9));
  EXPECT_GE(block.at(10), off);
  for (auto it = x1.lower_bound(off); it != x1.end(); ++it) {
    ASSERT_NEAR(it->second, 32.0, 1e-9) << "cycle " << it->first;
  }
  EXPECT_NEAR(x1_act.rbegin()->second, 32.0, 0.001);
  for (auto it = x1.lower_bound(block.at(9)); it != x1.end(); ++it) {
    const auto prev = x1.find(it->first - 1);
    ASSERT_LE(std::fabs(it->second - prev->second) / 0.002, 8000.0 / 60.0 + 1e-6)
        << "cycle " << it->first;  // X's rapid rate
  }
}

TEST(ElectronicCam, AG518OnAChannelWithoutACamMovesNothing) {
  TestMachine machine("polygon_lathe.yaml", 155);
  const std::string trace_path = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("launch/programs/cam_grind.nc"), "--trace", trace_path,
                           "--trace-pos-every", "1"},
                          -1, 180s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the run ends in the alarm
  const auto trace = read_trace(trace_path);
  bool refused = false;
  for (const auto& a : events(trace, "alarm", "CH1")) {
    if (a["number"] == 1253) {
      refused = true;
      EXPECT_EQ(a["line"], 4);
      EXPECT_NE(a["text"].get<std::string>().find("no electronic cam"), std::string::npos)
          << a["text"];
    }
  }
  EXPECT_TRUE(refused);
  EXPECT_TRUE(events(trace, "couple").empty());
  // X stayed at the G00's 55 (27.5 in radius): nothing after G51.8 ran.
  const auto x1 = axis_positions(trace, "X1", "cmd");
  ASSERT_FALSE(x1.empty());
  EXPECT_NEAR(x1.rbegin()->second, 27.5, 1e-6);
  for (const auto& [cycle, cmd] : x1) {
    ASSERT_LE(cmd, 27.5 + 1e-9) << "cycle " << cycle;
  }
}

}  // namespace
}  // namespace mcnc::test
