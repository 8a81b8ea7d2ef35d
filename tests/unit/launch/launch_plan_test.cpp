// What a launcher starts, in which order and with which command lines; on a machine of several
// hosts, only its host's processes, while it waits for all.
#include "launch/launch_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace mcnc::launch {
namespace {

std::vector<std::string> names(const LaunchPlan& plan) {
  std::vector<std::string> out;
  for (const ChildSpec& c : plan.children) {
    out.push_back(c.name);
  }
  return out;
}

bool has_args(const ChildSpec& c, const std::vector<std::string>& run) {
  return std::search(c.argv.begin(), c.argv.end(), run.begin(), run.end()) != c.argv.end();
}

config::MachineConfig two_hosts() {
  return config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: can0, uri: "udp:239.255.42.1:29000", sync_producer: X1}
  - {name: can1, uri: "udp:239.255.42.1:29001", sync_producer: X2}
channels:
  - {name: CH1, axes: [X1]}
  - {name: CH2, axes: [X2]}
axes:
  - {name: X1, address: X, bus: can0, node_id: 1}
  - {name: X2, address: X, bus: can1, node_id: 1}
plc: {signals: [{name: clamp, type: output}]}
hosts:
  - {name: a, runs: [CH1, X1, can0]}
  - {name: b, runs: [CH2, X2, can1, plc]}
)");
}

TEST(LaunchPlan, DriveSimulatorsThenAxisNodesThenChannelsThenThePlcAndTheHmiLast) {
  LaunchOptions options;
  options.machine_path = "m.yaml";
  options.bin_dir = "/opt/mcnc";
  options.programs = {{"CH2", "p2.nc"}};
  options.hmi_listen = "127.0.0.1:0";
  const LaunchPlan plan = launch_plan(two_hosts(), options, "/tmp/t.parts");
  EXPECT_EQ(names(plan), (std::vector<std::string>{"drivesim-can0", "drivesim-can1", "X1", "X2",
                                                   "CH1", "CH2", "PLC", kHmiName}));
  EXPECT_EQ(plan.dds_processes, (std::vector<std::string>{"X1", "X2", "CH1", "CH2", "PLC"}));
  EXPECT_EQ(plan.trace_parts,
            (std::vector<std::string>{"/tmp/t.parts/CH1.jsonl", "/tmp/t.parts/CH2.jsonl",
                                      "/tmp/t.parts/X1.jsonl", "/tmp/t.parts/X2.jsonl",
                                      "/tmp/t.parts/PLC.jsonl"}));
  const ChildSpec& ch2 = plan.children[5];
  EXPECT_EQ(ch2.argv[0], "/opt/mcnc/mcnc-channel");
  EXPECT_TRUE(has_args(ch2, {"--channel", "CH2", "--program", "p2.nc"}));
  EXPECT_TRUE(has_args(ch2, {"--clock", "lockstep"}));
  EXPECT_FALSE(has_args(plan.children[4], {"--program"})) << "CH1 has no program";
  EXPECT_TRUE(has_args(plan.children[7], {"--program", "CH2=p2.nc"})) << "the HMI shows it";
  EXPECT_TRUE(launch_plan(two_hosts(), options, "").trace_parts.empty()) << "no trace";
}

TEST(LaunchPlan, AHostsLauncherStartsWhatItsHostRunsAndWaitsForEveryProcess) {
  LaunchOptions options;
  options.machine_path = "m.yaml";
  options.hmi_listen = "127.0.0.1:0";
  const LaunchPlan a = launch_plan(two_hosts(), options, "/tmp/t.parts", "a");
  EXPECT_EQ(names(a), (std::vector<std::string>{"drivesim-can0", "X1", "CH1", kHmiName}));
  const LaunchPlan b = launch_plan(two_hosts(), options, "/tmp/t.parts", "b");
  EXPECT_EQ(names(b), (std::vector<std::string>{"drivesim-can1", "X2", "CH2", "PLC"}));
  EXPECT_EQ(b.dds_processes, (std::vector<std::string>{"X1", "X2", "CH1", "CH2", "PLC"}));
  EXPECT_EQ(b.trace_parts,
            (std::vector<std::string>{"/tmp/t.parts/CH2.jsonl", "/tmp/t.parts/X2.jsonl",
                                      "/tmp/t.parts/PLC.jsonl"}));
}

}  // namespace
}  // namespace mcnc::launch
