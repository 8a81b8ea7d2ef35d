// A lathe with its main spindle on a second CAN bus: the channel turns it as the program says
// (M03/M04/M05 with S), its axis node drives it in CSV through the spindle's PDOs, and the
// simulated drive's position shows the speeds.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <map>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

TEST(Spindle, TurnsReversesAndStopsAsTheProgramSays) {
  TestMachine machine("spindle_lathe.yaml", 39);
  const auto trace = run_to_clean_end(machine, "launch/programs/spindle_turn.nc");
  ASSERT_FALSE(trace.empty());
  // The commanded speeds, signed, in program order, each when its block runs.
  std::vector<double> rpm;
  for (const auto& s : events(trace, "spindle", "CH1")) {
    rpm.push_back(s["rpm"].get<double>());
  }
  EXPECT_EQ(rpm, (std::vector<double>{600.0, -300.0, 0.0}));
  std::map<int, std::uint64_t> block_cycle;
  for (const auto& b : events(trace, "block", "CH1")) {
    block_cycle[b["line"].get<int>()] = b["cycle"].get<std::uint64_t>();
  }
  // The spindle drive stays in CSV (no positioning asked) and follows: degrees per second
  // from its actual positions, well inside each speed's stretch.
  EXPECT_TRUE(events(trace, "mode", "S1").empty());
  std::map<std::uint64_t, double> angle;
  for (const auto& p : events(trace, "pos", "S1")) {
    angle[p["cycle"].get<std::uint64_t>()] = p["act"].get<double>();
  }
  // The spindle's node ran every cycle of the run, in step with the channel (its samples every
  // 10 cycles reach the program's end).
  ASSERT_FALSE(angle.empty());
  EXPECT_GE(angle.rbegin()->first + 10, block_cycle.at(10));
  EXPECT_EQ(angle.size(), angle.rbegin()->first / 10 + 1);
  const auto speed = [&](std::uint64_t from, std::uint64_t to) {
    from -= from % 10;
    to -= to % 10;
    return (angle.at(to) - angle.at(from)) / (static_cast<double>(to - from) * 0.001);
  };
  const std::uint64_t dwell = block_cycle.at(5);    // N30 G04 P500: at 600 rpm
  const std::uint64_t reverse = block_cycle.at(7);  // N50 G01 at -300 rpm
  const std::uint64_t stopped = block_cycle.at(9);  // N70 G04 P300 after M05
  EXPECT_NEAR(speed(dwell + 100, dwell + 450), 3600.0, 3600.0 * 0.001);
  EXPECT_NEAR(speed(reverse + 200, reverse + 900), -1800.0, 1800.0 * 0.001);
  EXPECT_NEAR(speed(stopped + 100, stopped + 280), 0.0, 1e-9);
}

}  // namespace
