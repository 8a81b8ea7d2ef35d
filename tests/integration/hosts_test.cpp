// A machine across hosts (issue 22). The cell of three hosts (launch/machines/cell_3ncu.yaml:
// the twin turret, its loader on a third host, Z3 a link axis) run on one host gives the twin
// turret's traces event for event, in the part transfer of launch/programs (G144 in CH3,
// G140/G141/G142 of A1, G04.1) and in CT-G1141-01 (G114.1 of S2 to S1): the file's hosts
// change where processes run, never what the machine does. And the same cell on three simulated
// hosts (tests/hosts/hostnet.py: network, mount and time namespaces, each host with its RouDi
// and a clock of its own), a launcher on each, gives that trace too.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::string& ch1, const std::string& ch2) {
  TestMachine machine(machine_file, domain);
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
                           "CH1=" + source(ch1), "--program", "CH2=" + source(ch2)},
                          -1, 300s);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return trace_until_end(read_trace(trace));
}

void expect_same_trace(const std::vector<nlohmann::json>& turret,
                       const std::vector<nlohmann::json>& cell) {
  ASSERT_GT(turret.size(), 1000U);
  ASSERT_EQ(turret.size(), cell.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < turret.size() && differ < 5; ++i) {
    if (turret[i] != cell[i]) {
      ++differ;
      ADD_FAILURE() << "event " << i << "\n" << turret[i].dump() << "\n" << cell[i].dump();
    }
  }
}

std::size_t count(const std::vector<nlohmann::json>& trace, const std::string& ev,
                  const std::string& key, const std::string& value) {
  std::size_t n = 0;
  for (const nlohmann::json& e : trace) {
    n += e["ev"] == ev && e.value(key, "") == value && e["cycle"] != 0 ? 1 : 0;
  }
  return n;
}

}  // namespace

TEST(Hosts, TheCellOfThreeHostsOnOneHostRunsAsTheTwinTurret) {
  const std::string ch1 = "launch/programs/part_transfer_ch1.nc";
  const std::string ch2 = "launch/programs/part_transfer_ch2.nc";
  const auto cell = run_programs("cell_3ncu.yaml", 161, ch1, ch2);
  expect_same_trace(run_programs("twin_turret.yaml", 160, ch1, ch2), cell);
  EXPECT_GE(count(cell, "owner", "axis", "A1"), 2U) << "A1 lent from ncu1 to ncu2 and back";
  EXPECT_EQ(count(cell, "sync_arrive", "ch", "CH2"), 2U);

  const std::string g1141 = "tests/integration/programs/g1141/";
  const auto coupled = run_programs("cell_3ncu.yaml", 163, g1141 + "ch1.nc", g1141 + "ch2.nc");
  expect_same_trace(run_programs("twin_turret.yaml", 162, g1141 + "ch1.nc", g1141 + "ch2.nc"),
                    coupled);
  EXPECT_EQ(count(coupled, "couple", "slave", "S2"), 1U) << "S2 on ncu2 follows S1 on ncu1";
}

// The cell on three simulated hosts with the part transfer: its machine file and trace in a
// directory of the build tree (the hosts share the machine's files, not /tmp), a launcher per
// host (ncu2's and ncu3's follow ncu1's, which coordinates).
class CellOnThreeHosts {
 public:
  explicit CellOnThreeHosts(int domain)
      : domain_(domain),
        machine_("cell_3ncu.yaml", domain),
        dir_(std::string(MCNC_BINARY_DIR) + "/hosts-test-" + std::to_string(domain)),
        hosts_("mhc" + std::to_string(domain), "ncu1,ncu2,ncu3", "ncu2=3,ncu3=-7",
               "10.77." + std::to_string(domain)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ + "/cell_3ncu.yaml") << slurp(machine_.path());
  }
  ~CellOnThreeHosts() { std::filesystem::remove_all(dir_); }
  CellOnThreeHosts(const CellOnThreeHosts&) = delete;
  CellOnThreeHosts& operator=(const CellOnThreeHosts&) = delete;

  [[nodiscard]] std::vector<std::string> launcher(const std::string& host) const {
    return hosts_.on(host, {bin("mcnc"), "run", dir_ + "/cell_3ncu.yaml", "--program",
                            "CH1=" + source(kCh1), "--program", "CH2=" + source(kCh2), "--trace",
                            trace(), "--timeout", "120", "--host", host});
  }
  [[nodiscard]] std::string trace() const { return dir_ + "/trace.jsonl"; }
  [[nodiscard]] std::string log(const std::string& host) const { return dir_ + "/" + host; }
  [[nodiscard]] int domain() const { return domain_; }
  // The coordinator (ncu1) started the run, and two seconds of it went by.
  [[nodiscard]] bool run_under_way() const {
    const bool started = eventually(
        [&] { return slurp(log("ncu1") + ".err").find("starting the run") != std::string::npos; },
        60s);
    std::this_thread::sleep_for(2s);
    return started;
  }
  [[nodiscard]] const SimulatedHosts& hosts() const { return hosts_; }

  static constexpr const char* kCh1 = "launch/programs/part_transfer_ch1.nc";
  static constexpr const char* kCh2 = "launch/programs/part_transfer_ch2.nc";

 private:
  int domain_;
  TestMachine machine_;
  std::string dir_;
  SimulatedHosts hosts_;
};

TEST(Hosts, TheCellRunsAcrossThreeHostsWithALauncherOnEachAsOnOneHost) {
  const auto one_host =
      run_programs("cell_3ncu.yaml", 164, CellOnThreeHosts::kCh1, CellOnThreeHosts::kCh2);
  const CellOnThreeHosts cell(165);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  const RunResult coordinator = run(cell.launcher("ncu1"), cell.domain(), 240s);
  EXPECT_EQ(coordinator.exit_code, 0) << coordinator.out << coordinator.err;
  EXPECT_EQ(ncu2.wait(60s), 0) << slurp(cell.log("ncu2") + ".err");
  EXPECT_EQ(ncu3.wait(60s), 0) << slurp(cell.log("ncu3") + ".err");
  expect_same_trace(one_host, trace_until_end(read_trace(cell.trace())));
}

// A process that dies on one host E-stops the machine on every host: its host's launcher
// reports it (alarm 3001), the coordinator E-stops and stops the run, and every launcher ends.
TEST(Hosts, AnAxisNodeKilledOnOneHostEStopsTheMachineOnEveryHost) {
  const CellOnThreeHosts cell(166);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  // Once the run is under way, X3 (the loader's axis, on ncu3) dies.
  ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
  const RunResult kill =
      // Only on ncu3 (its mount namespace): pkill sees every process of the machine.
      run(cell.hosts().on("ncu3", {"/bin/sh", "-c",
                                   "exec /usr/bin/pkill -KILL --nslist mnt --ns $$ -f "
                                   "'mcnc-axisnode .*--axis X3'"}),
          -1, 30s);
  ASSERT_EQ(kill.exit_code, 0) << "X3's node was running on ncu3";
  EXPECT_EQ(ncu1.wait(120s), 1) << "the coordinator E-stopped the run";
  const std::string out = slurp(cell.log("ncu1") + ".out") + slurp(cell.log("ncu1") + ".err");
  EXPECT_NE(out.find("host ncu3: emergency stop: X3"), std::string::npos) << out;
  EXPECT_EQ(ncu3.wait(120s), 1) << "ncu3 lost a process";
  EXPECT_GE(ncu2.wait(120s), 0) << "ncu2's launcher ends with the run";
  EXPECT_FALSE(events(read_trace(cell.trace()), "alarm", "launch").empty());
}

// A host that goes down during the run (its launcher killed, and its processes with it):
// the coordinator notices its launcher gone when its DDS lease runs out, and E-stops the rest.
TEST(Hosts, AHostThatGoesDownDuringTheRunEStopsTheRest) {
  const CellOnThreeHosts cell(167);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
  ncu3.kill(SIGKILL);
  EXPECT_EQ(ncu3.wait(30s), -SIGKILL);
  EXPECT_EQ(ncu1.wait(120s), 1) << "the coordinator E-stopped the run";
  const std::string out = slurp(cell.log("ncu1") + ".out") + slurp(cell.log("ncu1") + ".err");
  EXPECT_NE(out.find("host ncu3: its launcher is gone"), std::string::npos) << out;
  EXPECT_GE(ncu2.wait(120s), 0) << "ncu2's launcher ends with the run";
}

// A host whose launcher never answers: the coordinator names it when its start-up time runs
// out, and the run never starts.
TEST(Hosts, AHostThatDoesNotAnswerIsNamedAndNothingMoves) {
  const CellOnThreeHosts cell(168);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  const RunResult coordinator = run(cell.launcher("ncu1"), cell.domain(), 180s);
  EXPECT_EQ(coordinator.exit_code, 1) << coordinator.out << coordinator.err;
  const std::string out = coordinator.out + coordinator.err;
  EXPECT_NE(out.find("no launcher answers on host ncu3"), std::string::npos) << out;
  EXPECT_EQ(out.find("starting the run"), std::string::npos) << "the run never started";
  for (const nlohmann::json& e : read_trace(cell.trace())) {
    EXPECT_NE(e["ev"], "block_start") << e.dump();
  }
  EXPECT_GE(ncu2.wait(60s), 0) << "ncu2's launcher ends with the coordinator's stop";
}
