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

namespace mcnc::launch {
namespace {

// A plan of `buses` drive simulators and `dds` DDS processes, in start order.
LaunchPlan plan_of(std::size_t buses, std::size_t dds) {
  LaunchPlan plan;
  for (std::size_t b = 0; b < buses; ++b) {
    plan.children.push_back({"drivesim-can" + std::to_string(b), {}});
  }
  for (std::size_t p = 0; p < dds; ++p) {
    plan.children.push_back({"P" + std::to_string(p), {}});
    plan.dds_processes.push_back("P" + std::to_string(p));
  }
  return plan;
}

std::vector<std::size_t> all(std::size_t n) {
  std::vector<std::size_t> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = i;
  }
  return out;
}

TEST(StartWaves, AnUnsecuredOrSmallMachineStartsEveryChildAtOnce) {
  EXPECT_EQ(start_waves(plan_of(8, 48), false), (std::vector<std::vector<std::size_t>>{all(56)}));
  // The twin turret's size and one more: all at once, as before.
  EXPECT_EQ(start_waves(plan_of(2, 15), true), (std::vector<std::vector<std::size_t>>{all(17)}));
  EXPECT_EQ(start_waves(plan_of(2, kUnstaggeredDdsProcesses), true).size(), 1U);
}

TEST(StartWaves, ALargeSecuredMachineStartsItsDdsProcessesInWavesInStartOrder) {
  const LaunchPlan plan = plan_of(8, 48);  // the scale bench at N = 16
  const auto waves = start_waves(plan, true);
  ASSERT_EQ(waves.size(), 48 / kStartWave);
  std::vector<std::size_t> order;
  for (const auto& wave : waves) {
    std::size_t dds = 0;
    for (const std::size_t i : wave) {
      order.push_back(i);
      dds += plan.children[i].name.rfind("drivesim-", 0) == 0 ? 0 : 1;
    }
    EXPECT_EQ(dds, kStartWave);
  }
  EXPECT_EQ(order, all(56)) << "every child once, the drive simulators in the first wave";
}

TEST(StartWaves, TheLastWaveTakesWhatIsLeft) {
  const auto waves = start_waves(plan_of(1, kStartWave * 2 + 3), true);
  ASSERT_EQ(waves.size(), 3U);
  EXPECT_EQ(waves[0].size(), 1 + kStartWave);
  EXPECT_EQ(waves[1].size(), kStartWave);
  EXPECT_EQ(waves[2].size(), 3U);
}

}  // namespace
}  // namespace mcnc::launch
