// Faults that once froze a lockstep machine for good end it in bounded time (issue 25): a drive
// taken out of NMT operational by a frame from elsewhere on the bus, a flood of SYNC frames from
// a second producer, and an axis node stopped by SIGSTOP. Each run is small_lathe in lockstep
// with Z moving at feed; each must end within 5 s of wall time of the fault, with exit 1 and the
// alarm that names the cause.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <iostream>
#include <string>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// The bound, from the fault to the launcher's exit.
constexpr auto kFaultToEnd = 5s;

// Z1's drive is node 2 of small_lathe's bus can0; X1 is its SYNC producer.
constexpr int kZDriveNode = 2;

// small_lathe running long_feed.nc (Z to -200 at F300) in lockstep under `mcnc run`.
class MovingLockstepLathe {
 public:
  explicit MovingLockstepLathe(int domain)
      : machine_(isolated(domain)),
        trace_(machine_.file("trace.jsonl")),
        run_({bin("mcnc"), "run", machine_.path(), "--clock", "lockstep", "--program",
              "CH1=" + source("launch/programs/long_feed.nc"), "--trace", trace_},
             -1, machine_.file("launch")) {}

  // Waits until Z moves at feed.
  [[nodiscard]] bool z_moves() const {
    return eventually([&] { return last_cmd(trace_ + ".parts/Z1.jsonl", "Z1") < -1.0; }, 90s);
  }
  [[nodiscard]] const TestMachine& machine() const { return machine_; }
  [[nodiscard]] std::string group() const {
    return "239.255." + std::to_string(machine_.domain()) + ".1";
  }
  [[nodiscard]] std::string port() const { return std::to_string(24000 + machine_.domain()); }
  // Waits for `mcnc run` to end; its exit code, and in `took` the wall time from `since`.
  int wait_end(std::chrono::steady_clock::time_point since, std::chrono::milliseconds& took) {
    const int code = run_.wait(60s);
    took = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() -
                                                                 since);
    std::cout << "the run ended " << took.count() << " ms after the fault, exit " << code << "\n";
    return code;
  }
  [[nodiscard]] std::vector<nlohmann::json> trace() const { return read_trace(trace_); }
  [[nodiscard]] std::string output() const {
    return slurp(machine_.file("launch.out")) + slurp(machine_.file("launch.err"));
  }

 private:
  // The run may kill a process that does not leave: on a host of its own as iceoryx sees it,
  // so that a RouDi hung by the kill is the test's alone.
  static TestMachine isolated(int domain) {
    isolate_iceoryx_host();
    return TestMachine("small_lathe.yaml", domain);
  }

  TestMachine machine_;
  std::string trace_;
  Background run_;
};

RunResult inject(const MovingLockstepLathe& lathe, const std::string& kind,
                 const std::string& value) {
  return run({source("tests/integration/bus_faults.py"), lathe.group(), lathe.port(), kind, value},
             -1, 30s);
}

// The first alarm an axis node raised, or null.
nlohmann::json first_alarm(const std::vector<nlohmann::json>& trace, const std::string& src) {
  const auto alarms = events(trace, "alarm", src);
  for (const auto& a : events(trace, "alarm")) {
    std::cout << "alarm: " << a << "\n";
  }
  return alarms.empty() ? nlohmann::json() : alarms.front();
}

}  // namespace

// An NMT stop to Z's drive: the drive answers no SYNC and its heartbeat says "stopped". Z1 no
// longer waits for the answer, its SYNC watchdog counts the cycles as in realtime: alarm 2004.
TEST(LockstepFaults, AnNmtStopToADriveEndsTheRunWithAlarm2004) {
  MovingLockstepLathe lathe(124);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  const auto fault_at = std::chrono::steady_clock::now();
  ASSERT_EQ(inject(lathe, "nmt-stop", std::to_string(kZDriveNode)).exit_code, 0);
  std::chrono::milliseconds took{};
  EXPECT_EQ(lathe.wait_end(fault_at, took), 1) << lathe.output();
  EXPECT_LE(took, kFaultToEnd) << lathe.output();
  const auto alarm = first_alarm(lathe.trace(), "Z1");
  ASSERT_FALSE(alarm.is_null()) << lathe.output();
  EXPECT_EQ(alarm["number"], 2004) << alarm;
}

// SYNC frames from another node, one a millisecond for 10 s: X1, the bus's SYNC producer, sees
// SYNCs it did not send and raises alarm 2011; the flood no longer holds its own SYNC back.
TEST(LockstepFaults, ASyncFloodEndsTheRunWithAlarm2011) {
  MovingLockstepLathe lathe(131);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  Background flood(
      {source("tests/integration/bus_faults.py"), lathe.group(), lathe.port(), "sync-flood", "10"},
      -1, lathe.machine().file("flood"));
  const auto fault_at = std::chrono::steady_clock::now();
  std::chrono::milliseconds took{};
  EXPECT_EQ(lathe.wait_end(fault_at, took), 1) << lathe.output();
  EXPECT_LE(took, kFaultToEnd) << lathe.output();
  const auto alarm = first_alarm(lathe.trace(), "X1");
  ASSERT_FALSE(alarm.is_null()) << lathe.output();
  EXPECT_EQ(alarm["number"], 2011) << alarm;
}

// Z1 stopped by SIGSTOP: the whole lockstep machine waits for it. Its launcher sees the child
// stopped, E-stops the machine (alarm 3001 naming it), resumes it so that it quick-stops its
// drive, and the run ends.
TEST(LockstepFaults, AStoppedAxisNodeEndsTheRunInAnEStop) {
  MovingLockstepLathe lathe(133);
  ASSERT_TRUE(lathe.z_moves()) << lathe.output();
  std::vector<pid_t> z1;
  for (const pid_t p : pids_with_arg("--axis Z1")) {
    for (const pid_t q : pids_with_arg(lathe.machine().path())) {
      if (p == q) {
        z1.push_back(p);
      }
    }
  }
  ASSERT_EQ(z1.size(), 1U);
  const auto fault_at = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(z1[0], SIGSTOP), 0);
  std::chrono::milliseconds took{};
  EXPECT_EQ(lathe.wait_end(fault_at, took), 1) << lathe.output();
  EXPECT_LE(took, kFaultToEnd) << lathe.output();
  EXPECT_TRUE(pids_with_arg(lathe.machine().path()).empty()) << "children left running";
  const auto trace = lathe.trace();
  const auto alarm = first_alarm(trace, "launch");
  ASSERT_FALSE(alarm.is_null()) << lathe.output();
  EXPECT_EQ(alarm["number"], 3001) << alarm;
  EXPECT_NE(alarm["text"].get<std::string>().find("Z1 stopped by signal 19"), std::string::npos)
      << alarm;
  // Resumed, Z1 brought its drive to rest with a quick stop.
  const auto z_states = events(trace, "drive", "Z1");
  ASSERT_FALSE(z_states.empty());
  EXPECT_EQ(z_states.back()["state"], "quick_stop_active");
}
