// A host's shared memory under faults (issue 21): in a run on Cyclone DDS, a channel, an axis
// node or RouDi itself killed with SIGKILL. The rest of the machine reaches the safe state of
// docs/operations.md (E-stop, alarm 3001 naming what was lost, drives quick-stopped, channel in
// reset, every process gone), RouDi gives back what a killed process held, and the next run on
// the same host runs as the first did. Each test is a host of its own (isolate_iceoryx_host), so
// that its RouDi can be watched and killed without touching the suite's.
#include "harness.hpp"

#include "common/clock/cycle_clock.hpp"
#include "launch/host_roudi.hpp"

#include <gtest/gtest.h>

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// What RouDi holds, from mcnc_roudi_probe: the processes registered with it (by name, probes
// left out) and the chunks in use in the payload segments (every segment but RouDi's own, id 0).
// RouDi's introspection is a snapshot of the last second or so: compare it with eventually().
struct RoudiHoldings {
  std::string processes;
  int chunks_in_use = -1;  // -1: the probe failed
  std::string text;
  bool operator==(const RoudiHoldings& o) const {
    return processes == o.processes && chunks_in_use == o.chunks_in_use;
  }
};

RoudiHoldings roudi_holdings() {
  const RunResult r = run({bin("mcnc_roudi_probe"), "--timeout", "10"}, -1, 30s);
  RoudiHoldings held;
  if (r.exit_code != 0) {
    held.text = "probe failed: " + r.err;
    return held;
  }
  const nlohmann::json probe = nlohmann::json::parse(r.out);
  for (const auto& p : probe["processes"]) {
    const std::string name = p["name"];
    if (name.rfind("mcnc_roudi_probe_", 0) != 0) {
      held.processes += " " + name;
    }
  }
  held.chunks_in_use = 0;
  for (const auto& segment : probe["segments"]) {
    for (const auto& pool : segment["pools"]) {
      held.chunks_in_use += segment["id"].get<int>() == 0 ? 0 : pool["used"].get<int>();
    }
  }
  held.text =
      "processes:" + held.processes + "; " + std::to_string(held.chunks_in_use) + " chunks in use";
  return held;
}

// Waits (30 s at most) until RouDi holds what it held `before`; false, and what it holds, if not.
::testing::AssertionResult roudi_holds_again(const RoudiHoldings& before) {
  RoudiHoldings now;
  if (eventually([&] { return (now = roudi_holdings()) == before; }, 30s)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "RouDi holds " << now.text << "; before, " << before.text;
}

// The host's RouDi, as a service of the host would run it (above the machine, as
// docs/operations.md asks).
TestMachine small_lathe_on_shared_memory(int domain) {
  TestMachine machine("small_lathe.yaml", domain);
  use_middleware(machine, "cyclonedds");
  return machine;
}

// xz_move to its end: the trace up to the end (what every run on this host must give alike).
std::vector<nlohmann::json> clean_run(const TestMachine& machine) {
  return trace_until_end(run_to_clean_end(machine, "launch/programs/xz_move.nc"));
}

// Last `state` of a drive or channel in a trace ("" when none).
std::string last_state(const std::vector<nlohmann::json>& trace, const std::string& ev,
                       const std::string& src) {
  const auto states = events(trace, ev, src);
  return states.empty() ? "" : states.back()["state"].get<std::string>();
}

// Last commanded position of Z1 in its trace part (nan before the first).
double z_cmd(const TestMachine& machine) {
  double cmd = std::nan("");
  for (const auto& e :
       events(read_trace(machine.file("trace.jsonl.parts/Z1.jsonl")), "pos", "Z1")) {
    cmd = e["cmd"];
  }
  return cmd;
}

// long_feed under mcnc run, up to where Z feeds; then `kill` (which kills something) and the
// run's end: launch's exit code, and the merged trace.
template <class Kill>
std::pair<int, std::vector<nlohmann::json>> kill_while_feeding(const TestMachine& machine,
                                                               Kill kill) {
  const std::string trace = machine.file("trace.jsonl");
  std::filesystem::remove(trace);  // an earlier run's, Z1's part among them
  std::filesystem::remove_all(trace + ".parts");
  Background launch({bin("mcnc"), "run", machine.path(), "--program",
                     "CH1=" + source("launch/programs/long_feed.nc"), "--trace", trace},
                    -1, machine.file("launch"));
  EXPECT_TRUE(eventually([&] { return z_cmd(machine) < -1.0; }, 60s))
      << slurp(machine.file("launch"));
  // The run's samples lie in RouDi's chunks: what a killed process holds is not nothing.
  EXPECT_GT(roudi_holdings().chunks_in_use, 0);
  kill();
  const int code = launch.wait(90s);
  EXPECT_NE(code, -1000) << "launch did not exit";
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "processes left running";
  return {code, read_trace(trace)};
}

// The one process of `machine` whose command line holds `arg` (0: none, or several).
pid_t pid_of(const TestMachine& machine, const std::string& arg) {
  const std::vector<pid_t> of_machine = pids_with_arg(machine.path());
  std::vector<pid_t> mine;
  for (pid_t p : pids_with_arg(arg)) {
    if (std::find(of_machine.begin(), of_machine.end(), p) != of_machine.end()) {
      mine.push_back(p);
    }
  }
  return mine.size() == 1 ? mine[0] : 0;
}

// Kills `victim` with SIGKILL while it waits: the rest of the machine is held (SIGSTOP) for
// 200 ms first, so that in lockstep the victim has finished its cycle and waits for inputs.
// iceoryx 2.0's RouDi hangs for good cleaning up after a process killed while it held a
// port's lock, in the middle of a publish (docs/decisions.md 38): what this test checks is the
// clean-up itself, not that hazard of the library.
void kill_while_it_waits(const TestMachine& machine, pid_t victim) {
  std::vector<pid_t> held;
  for (pid_t p : pids_with_arg(machine.path())) {
    if (p != victim && ::kill(p, SIGSTOP) == 0) {
      held.push_back(p);
    }
  }
  std::this_thread::sleep_for(200ms);
  ::kill(victim, SIGKILL);
  for (pid_t p : held) {
    ::kill(p, SIGCONT);
  }
}

void expect_launch_alarm(const std::vector<nlohmann::json>& trace, const std::string& text) {
  const auto alarms = events(trace, "alarm", "launch");
  ASSERT_EQ(alarms.size(), 1U);
  EXPECT_EQ(alarms[0]["number"], 3001);
  EXPECT_NE(alarms[0]["text"].get<std::string>().find(text), std::string::npos) << alarms[0];
}

}  // namespace

TEST(SharedMemory, AKilledChannelOrAxisNodeLeavesRoudiHoldingNothingAndTheNextRunRunsAsTheFirst) {
  isolate_iceoryx_host();
  const TestMachine machine = small_lathe_on_shared_memory(170);
  const auto roudi = start_host_roudi(machine.file("roudi"));
  const RoudiHoldings idle = roudi_holdings();
  ASSERT_EQ(idle.chunks_in_use, 0) << idle.text;
  const auto first = clean_run(machine);
  EXPECT_TRUE(roudi_holds_again(idle)) << "after a clean run";

  for (const std::string victim : {"--channel CH1", "--axis Z1"}) {
    SCOPED_TRACE(victim);
    const auto [code, trace] = kill_while_feeding(machine, [&] {
      const pid_t pid = pid_of(machine, victim);
      ASSERT_NE(pid, 0);
      kill_while_it_waits(machine, pid);
    });
    EXPECT_EQ(code, 1);
    const std::string name = victim.substr(victim.find(' ') + 1);
    expect_launch_alarm(trace, name + " killed by signal 9");
    // The axes that are left quick-stopped; a channel that is left is in reset.
    for (const std::string axis : {"X1", "Z1"}) {
      if (axis != name) {
        EXPECT_EQ(last_state(trace, "drive", axis), "quick_stop_active") << axis;
      }
    }
    if (name != "CH1") {
      EXPECT_EQ(last_state(trace, "state", "CH1"), "reset");
    }
    // RouDi finds the dead process by its missing keep-alive and gives its chunks back.
    EXPECT_TRUE(roudi_holds_again(idle));
  }

  EXPECT_EQ(clean_run(machine), first) << "the next run on the host";
  EXPECT_TRUE(roudi_holds_again(idle));
}

TEST(SharedMemory, AKilledRoudiEStopsTheMachineAndTheNextRunStartsItsOwn) {
  isolate_iceoryx_host();
  const TestMachine machine = small_lathe_on_shared_memory(171);
  auto roudi = start_host_roudi(machine.file("roudi"));
  const auto first = clean_run(machine);

  const auto [code, trace] = kill_while_feeding(machine, [&] { roudi->kill(SIGKILL); });
  EXPECT_EQ(code, 1);
  expect_launch_alarm(trace, "the host's iceoryx RouDi stopped answering");
  EXPECT_EQ(last_state(trace, "drive", "X1"), "quick_stop_active");
  EXPECT_EQ(last_state(trace, "drive", "Z1"), "quick_stop_active");
  EXPECT_EQ(last_state(trace, "state", "CH1"), "reset");
  EXPECT_EQ(roudi->wait(10s), -SIGKILL);

  // No RouDi answers now (its socket and shared memory are left behind): the launcher starts one
  // of its own, and the run is the first one's.
  EXPECT_EQ(clean_run(machine), first);
  EXPECT_EQ(roudi_holdings().chunks_in_use, -1) << "the launcher stops the RouDi it started";
}

// Whether process `pid` has `path` open.
bool holds_open(pid_t pid, const std::string& path) {
  std::error_code error;
  for (const auto& fd :
       std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd", error)) {
    if (std::filesystem::read_symlink(fd.path(), error) == path) {
      return true;
    }
  }
  return false;
}

// RouDi removes a process whose keep-alive it has not handled for 1.5 s. The threads of a
// realtime machine run at SCHED_FIFO, above every ordinary process: the RouDi the launcher
// starts runs above them, so that no load of the host starves it into removing processes that
// still run (docs/decisions.md 37). The machine's processes keep idle CPUs polling while they
// run (decision 138).
TEST(SharedMemory, ARealtimeMachinesRoudiRunsAboveItsProcessesWhichKeepIdleCpusPolling) {
  isolate_iceoryx_host();
  const TestMachine machine = small_lathe_on_shared_memory(172);
  Background launch({bin("mcnc"), "run", machine.path(), "--clock", "realtime", "--program",
                     "CH1=" + source("launch/programs/long_feed.nc")},
                    -1, machine.file("launch"));
  const std::string roudi_config = "mcnc-roudi-" + std::to_string(launch.pid()) + ".toml";
  pid_t roudi = 0;
  pid_t axis = 0;
  ASSERT_TRUE(eventually(
      [&] {
        const auto roudis = pids_with_arg(roudi_config);
        roudi = roudis.size() == 1 ? roudis[0] : 0;
        axis = pid_of(machine, "X1");
        return roudi != 0 && axis != 0;
      },
      60s))
      << slurp(machine.file("launch"));
  const auto fifo_priority = [](pid_t pid) {
    sched_param param{};
    return ::sched_getscheduler(pid) == SCHED_FIFO && ::sched_getparam(pid, &param) == 0
               ? param.sched_priority
               : 0;
  };
  // The axis node's main thread runs its cycles, at the axis cycle priority once the run has
  // started (its other threads run below it, decision 55; only its SYNC timer above, decision
  // 128); RouDi above all of them.
  EXPECT_TRUE(
      eventually([&] { return fifo_priority(axis) == mcnc::clock::kAxisCyclePriority; }, 10s));
  EXPECT_EQ(fifo_priority(roudi), mcnc::launch::kRoudiPriority);
  // Its CPU latency request is an open file: the kernel drops it when the process ends.
  EXPECT_TRUE(holds_open(axis, "/dev/cpu_dma_latency"));
  launch.kill(SIGTERM);
  EXPECT_NE(launch.wait(60s), -1000) << "launch did not exit";
  EXPECT_TRUE(pids_with_arg(roudi_config).empty()) << "the launcher stops the RouDi it started";
}
