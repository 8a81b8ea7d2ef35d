// G10 L14 P7 through the runtime, in lockstep (decision 162): small_lathe.yaml at a 2 ms cycle
// with Z1's drive reporting its torque (torque_skip: 0x6077 in its TPDO2) and its load meeting
// a hard stop at Z-5 (the simulator's contact), the channel's drilling overload set as params
// 5100.2-5100.4 say. The G83's feed runs into the stop, the drive's torque rises above the
// 100 % of G10 L14 P7, the channel stops the feed and takes the drill back to R1 at rapid,
// then raises 1282 (example 1) or ends the block there and goes on (#100 counting it).
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::test {
namespace {

constexpr double kStop = -5.0;

// small_lathe.yaml with Z1's hard stop and its load reported, and CH1's drilling overload.
void drilling_lathe(const TestMachine& machine, const std::string& drilling) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto replace = [&](const std::string& what, const std::string& with) {
    const std::size_t at = yaml.find(what);
    ASSERT_NE(at, std::string::npos) << what;
    yaml.replace(at, what.size(), with);
  };
  replace("cycle_us: 1000", "cycle_us: 2000");  // Z1's second PDOs: the bus under 70 %
  replace("    axes: [X1, Z1]\n",
          "    axes: [X1, Z1]\n    overload:\n      drilling: " + drilling + "\n");
  replace("      max_velocity: 250     # mm/s\n",
          "      max_velocity: 250     # mm/s\n      contact: {at: -5, blocks: below}\n");
  replace("    node_id: 2\n", "    node_id: 2\n    torque_skip: true\n");
  std::ofstream(machine.path()) << yaml;
}

// Z1's command as its node reported it, in cycle order.
std::vector<std::pair<std::uint64_t, double>> z_commands(const std::vector<nlohmann::json>& trace) {
  std::vector<std::pair<std::uint64_t, double>> z;
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "Z1" && p["src"] == "Z1") {
      z.emplace_back(p["cycle"].get<std::uint64_t>(), p["cmd"].get<double>());
    }
  }
  return z;
}

// Example 1 (L4965-4993): back to R at once, then the alarm; nothing moves after it.
TEST(DrillOverload, RetractsToRThenAlarms) {
  TestMachine machine("small_lathe.yaml", 218);
  drilling_lathe(machine, "{retract: true, retry: false, alarm: true}");
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program",
           "CH1=" + source("tests/integration/programs/g10_l14/drill_overload_alarm.nc"), "--trace",
           trace_file, "--trace-pos-every", "1"},
          -1, std::chrono::seconds(180));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<nlohmann::json> trace = read_trace(trace_file);
  const std::vector<nlohmann::json> alarms = events(trace, "alarm");
  ASSERT_EQ(alarms.size(), 1U);
  const nlohmann::json& a = alarms.front();
  EXPECT_EQ(a["number"], 1282);
  EXPECT_EQ(a["line"], 4);  // the G83
  EXPECT_EQ(a["text"].get<std::string>().substr(0, 30), "G10 L14 P7: the load of axis Z") << a;
  const auto z = z_commands(trace);
  ASSERT_FALSE(z.empty());
  // Down to the stop (the command passes it by the travel of the cycles the torque takes to
  // rise: 5 mm/s, 0.01 mm per cycle), never to the bottom; then back up to R before the alarm.
  double lowest = 0.0;
  std::uint64_t lowest_at = 0;
  for (const auto& [cycle, cmd] : z) {
    if (cmd < lowest) {
      lowest = cmd;
      lowest_at = cycle;
    }
  }
  EXPECT_LT(lowest, kStop);
  EXPECT_GT(lowest, kStop - 0.3);
  const auto alarm_cycle = a["cycle"].get<std::uint64_t>();
  EXPECT_LT(lowest_at, alarm_cycle);
  for (const auto& [cycle, cmd] : z) {
    if (cycle >= alarm_cycle + 2) {
      EXPECT_NEAR(cmd, 1.0, 1e-6) << "cycle " << cycle;  // at R from the alarm on
    }
  }
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "X1") {
      EXPECT_NEAR(p["cmd"].get<double>(), 0.0, 1e-9) << p;  // X50 never ran
    }
  }
}

// 5100.2 = 1, .3 = 0, .4 = 0: back to R, the G83 block ends there, the program goes on.
TEST(DrillOverload, RetractsToRAndGoesOn) {
  TestMachine machine("small_lathe.yaml", 218);
  drilling_lathe(machine, "{retract: true}");
  const std::vector<nlohmann::json> trace =
      run_to_clean_end(machine, "tests/integration/programs/g10_l14/drill_overload_go_on.nc",
                       {"--trace-pos-every", "1"});
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto z = z_commands(trace);
  ASSERT_FALSE(z.empty());
  double lowest = 0.0;
  for (const auto& [cycle, cmd] : z) {
    lowest = std::min(lowest, cmd);
  }
  EXPECT_LT(lowest, kStop);
  EXPECT_GT(lowest, kStop - 0.3);
  EXPECT_NEAR(z.back().second, 1.0, 1e-6);  // the block ended at R
  double x = 0.0;
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "X1") {
      x = p["cmd"].get<double>();
    }
  }
  EXPECT_NEAR(x, 15.0, 1e-6);  // X30: #100 = 1
}

}  // namespace
}  // namespace mcnc::test
