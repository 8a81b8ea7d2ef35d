// Fast DDS and Cyclone DDS as one machine's wire (issue 21): the machine file chooses each
// process's middleware, the twin-turret part transfer (CT-G1141-01) gives the same lockstep
// trace on either and with channels on one and axis nodes on the other, three times in a row on
// shared memory (once beside a CPU hog), and a machine on Cyclone DDS without a RouDi, or with
// one that registers no process, is refused before anything starts.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

const std::string kG1141 = "tests/integration/programs/g1141/";

// In a mount namespace of its own, the host's RouDi socket (if any) covered by /dev/null: there,
// as on a host without one, no RouDi answers.
constexpr const char* kWithoutRoudi =
    "{ [ ! -e /tmp/roudi ] || mount --bind /dev/null /tmp/roudi; } && ";

// The twin turret with `machine_wide` for every process, and `channels` for the channels when
// not empty.
TestMachine twin_turret_on(int domain, const std::string& machine_wide,
                           const std::string& channels = "") {
  TestMachine machine("twin_turret.yaml", domain);
  use_middleware(machine, machine_wide, channels);
  return machine;
}

std::vector<nlohmann::json> part_transfer(const TestMachine& machine) {
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
           "CH1=" + source(kG1141 + "ch1.nc"), "--program", "CH2=" + source(kG1141 + "ch2.nc")},
          -1, 300s);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return trace_until_end(read_trace(trace));
}

void expect_same_trace(const std::vector<nlohmann::json>& a, const std::vector<nlohmann::json>& b,
                       const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size() && differ < 5; ++i) {
    if (a[i] != b[i]) {
      ++differ;
      ADD_FAILURE() << what << ": event " << i << "\n" << a[i].dump() << "\n" << b[i].dump();
    }
  }
}

}  // namespace

TEST(Middleware, ThePartTransferGivesOneTraceOnEitherMiddlewareAndOnBothMixed) {
  const auto fast = part_transfer(twin_turret_on(150, "fastdds"));
  const auto cyclone = part_transfer(twin_turret_on(151, "cyclonedds"));
  // Channels on Cyclone DDS, axis nodes, the PLC and the launcher on Fast DDS.
  const auto mixed = part_transfer(twin_turret_on(152, "fastdds", "cyclonedds"));
  ASSERT_GT(fast.size(), 1000U);
  EXPECT_EQ(fast.back()["ev"], "summary");
  expect_same_trace(fast, cyclone, "Fast DDS against Cyclone DDS");
  expect_same_trace(fast, mixed, "Fast DDS against mixed");
}

// Lockstep determinism on the shared-memory path: three runs in a row give one trace, the
// last beside a CPU hog on every core (the lockstep clock waits for inputs, never for time).
TEST(Middleware, OnSharedMemoryThePartTransferGivesOneTraceThreeTimesOnceBesideACpuHog) {
  const auto first = part_transfer(twin_turret_on(155, "cyclonedds"));
  const auto second = part_transfer(twin_turret_on(156, "cyclonedds"));
  TestMachine hogged = twin_turret_on(157, "cyclonedds");
  std::vector<std::unique_ptr<Background>> hogs;
  for (unsigned i = 0; i < std::max(2U, std::thread::hardware_concurrency()); ++i) {
    hogs.push_back(std::make_unique<Background>(
        std::vector<std::string>{"/bin/sh", "-c", "while :; do :; done"}, -1,
        hogged.file("hog" + std::to_string(i) + ".log")));
  }
  const auto third = part_transfer(hogged);
  hogs.clear();
  ASSERT_GT(first.size(), 1000U);
  EXPECT_EQ(first.back()["ev"], "summary");
  expect_same_trace(first, second, "first against second");
  expect_same_trace(first, third, "first against the run beside the hog");
}

TEST(Middleware, AMachineOnCycloneDdsWithoutItsRoudiIsRefusedBeforeAnythingStarts) {
  TestMachine machine = twin_turret_on(153, "cyclonedds");
  // `roudi: running`: the host is to run one.
  const std::string yaml = std::regex_replace(slurp(machine.path()), std::regex("\nmachine:\n"),
                                              "\nmachine:\n  roudi: running\n");
  std::ofstream(machine.path()) << yaml;
  const auto start = std::chrono::steady_clock::now();
  const RunResult r =
      run({"/usr/bin/unshare", "--mount", "--", "/bin/sh", "-c",
           std::string(kWithoutRoudi) + "exec \"$0\" run \"$1\"", bin("mcnc"), machine.path()},
          -1, 60s);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no iceoryx RouDi answers"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing started"), std::string::npos) << r.err;
  EXPECT_LT(std::chrono::steady_clock::now() - start, 20s) << "at once, never a wait";
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "nothing may be started";
}

// A RouDi that is stuck (iceoryx 2.0 can hang for good cleaning up after a process killed with
// SIGKILL) still has its socket bound, so it answers a connect; here a stopped one stands for
// it. The launcher tries a registration (mcnc-roudi-check) before anything starts.
TEST(Middleware, AMachineWhoseRoudiRegistersNoProcessIsRefusedBeforeAnythingStarts) {
  isolate_iceoryx_host();
  TestMachine machine = twin_turret_on(158, "cyclonedds");
  const auto roudi = start_host_roudi(machine.file("roudi"));
  roudi->kill(SIGSTOP);
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = run({bin("mcnc"), "run", machine.path()}, -1, 60s);
  const auto took = std::chrono::steady_clock::now() - start;
  roudi->kill(SIGCONT);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("did not register a process within 5 s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("restart it"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing started"), std::string::npos) << r.err;
  EXPECT_LT(took, 20s);
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "nothing may be started";
}

TEST(Middleware, ACycloneDdsProcessWithoutARoudiExits2WithTheError) {
  TestMachine machine = twin_turret_on(154, "cyclonedds");
  const RunResult r =
      run({"/usr/bin/unshare", "--mount", "--", "/bin/sh", "-c",
           std::string(kWithoutRoudi) + "exec \"$0\" --machine \"$1\" --channel CH1",
           bin("mcnc-channel"), machine.path()},
          -1, 60s);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("no iceoryx RouDi answers"), std::string::npos) << r.out << r.err;
}
