// G04 PS and G04 I through the runtime, in lockstep: the spindle lathe with a PLC whose input
// `part_seen` (port 2) follows the output M20 sets 300 ms later. G04 PS3000 ends when the
// simulated spindle drive's actual speed, in its axis node's feedback, reaches 3000 rpm; G04 I2
// when the PLC's status shows the input on; a G04 I whose input never comes is alarm 1271 and
// nothing after it moves.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace mcnc::test {
namespace {

void add_plc(const TestMachine& machine) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::string yaml = text.str();
  const std::string channel = "    feed_mode: per_min\n";
  const std::size_t at = yaml.find(channel);
  ASSERT_NE(at, std::string::npos);
  yaml.insert(at + channel.size(), "    speed_arrival: {tolerance: 10, timeout: 10}\n");
  yaml +=
      "\nplc:\n"
      "  signals:\n"
      "    - {name: part_feed, type: output}\n"
      "    - {name: part_seen, type: input, follows: part_feed, delay_ms: 300, port: 2}\n"
      "  m_codes:\n"
      "    - {code: 20, set: [part_feed]}\n";
  std::ofstream(machine.path()) << yaml;
}

TEST(DwellWait, PsEndsAtTheSpindlesActualSpeedAndIAtThePlcInput) {
  TestMachine machine("spindle_lathe.yaml", 148);
  add_plc(machine);
  const auto trace = run_to_clean_end(machine, "tests/integration/programs/g04/waits.nc");
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto start = block_starts(trace);
  ASSERT_TRUE(start.count(2) && start.count(3) && start.count(4) && start.count(5) &&
              start.count(7) && start.count(8));
  // The spindle's angle every 10 cycles (1 ms), its speed in rpm over a window.
  std::map<std::uint64_t, double> angle;
  for (const auto& p : events(trace, "pos", "S1")) {
    angle[p["cycle"].get<std::uint64_t>()] = p["act"].get<double>();
  }
  const auto rpm = [&](std::uint64_t from, std::uint64_t to) {
    from -= from % 10;
    to -= to % 10;
    return (angle.at(to) - angle.at(from)) / (static_cast<double>(to - from) * 0.001) / 6.0;
  };
  // G04 PS3000 (line 2) waited while the spindle ran up, and ended once it was there.
  EXPECT_LT(rpm(start.at(2), start.at(2) + 10), 2900.0);
  EXPECT_GT(start.at(3), start.at(2) + 10);
  // The speed over the 10 ms before the block ended was near 3000 rpm, over the 10 ms before
  // that still below it (the drive runs up at ~38000 rpm/s): it ended as the speed came.
  EXPECT_GT(rpm(start.at(3) - 10, start.at(3)), 2700.0);
  EXPECT_LT(rpm(start.at(3) - 20, start.at(3) - 10), 2990.0);
  EXPECT_NEAR(rpm(start.at(3) + 10, start.at(3) + 30), 3000.0, 15.0);
  // G04 I2 (line 4) ended 300 ms after M20 set the output (the simulated input's delay), a
  // few cycles later for the PLC's cycle and its status reaching the channel.
  EXPECT_GE(start.at(5), start.at(4) + 295);
  EXPECT_LE(start.at(5), start.at(4) + 310);
  // Z moved only after the wait: its position stood still up to the G01.
  const auto z = events(trace, "pos", "Z1");
  ASSERT_FALSE(z.empty());
  for (const auto& p : z) {
    if (p["cycle"].get<std::uint64_t>() <= start.at(5)) {
      EXPECT_NEAR(p["act"].get<double>(), z.front()["act"].get<double>(), 1e-6) << p.dump();
    }
  }
  // G04 PS0 (line 7) waited for the stop, which came at the end of M05's ramp down: still
  // turning over the 10 ms before the block ended, at rest over the 10 ms after (line 8 dwells,
  // so that the trace has them: a run that ends at once may end before them).
  EXPECT_GT(rpm(start.at(8) - 10, start.at(8)), 10.0);
  EXPECT_LT(std::abs(rpm(start.at(8), start.at(8) + 10)), 10.0);
  EXPECT_GT(start.at(8), start.at(7) + 30);
}

TEST(DwellWait, AnInputThatNeverComesIsAlarm1271BeforeAnythingMoves) {
  TestMachine machine("spindle_lathe.yaml", 149);
  add_plc(machine);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run(
      {bin("mcnc"), "run", machine.path(), "--program",
       "CH1=" + source("tests/integration/programs/g04/input_timeout.nc"), "--trace", trace_file},
      -1, std::chrono::seconds(180));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto trace = read_trace(trace_file);
  bool found = false;
  for (const auto& a : events(trace, "alarm", "CH1")) {
    if (a["number"] == 1271) {
      found = true;
      EXPECT_NE(a["text"].get<std::string>().find("input 2 not on within 0.200 s"),
                std::string::npos)
          << a.dump();
    }
  }
  EXPECT_TRUE(found);
  EXPECT_EQ(block_starts(trace).count(2), 0u);  // the G01 never started
  const auto z = events(trace, "pos", "Z1");
  ASSERT_FALSE(z.empty());
  for (const auto& p : z) {
    EXPECT_NEAR(p["act"].get<double>(), z.front()["act"].get<double>(), 1e-6) << p.dump();
  }
}

}  // namespace
}  // namespace mcnc::test
