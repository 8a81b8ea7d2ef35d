// Safety behaviour with real processes: a killed channel makes its axis nodes quick stop with
// an alarm; a crashed child makes mcnc-launch E-stop the machine and exit non-zero; a realtime
// machine the host cannot keep up with is E-stopped by a launcher that runs above it.
#include "harness.hpp"

#include "common/clock/cycle_clock.hpp"
#include "common/process/exit_deadline.hpp"
#include "common/process/process_node.hpp"
#include "launch/launcher.hpp"

#include <gtest/gtest.h>

#include <sched.h>

#include <csignal>
#include <iostream>
#include <memory>
#include <mutex>
#include <vector>

using namespace mcnc;
using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// Starts the processes of small_lathe one by one (no mcnc-launch), runs them with the given
// clock, kills the channel while Z moves, and checks what the Z axis node did.
void kill_channel_while_moving(int domain, ClockKind clock, std::uint32_t expected_alarm) {
  isolate_iceoryx_host();  // it kills a process on Cyclone DDS (start_host_roudi)
  TestMachine machine("small_lathe.yaml", domain, clock == REALTIME_CLOCK ? 50 : 0);
  const auto roudi = start_host_roudi(machine.file("roudi"));
  const std::string m = machine.path();
  const std::string clock_name = clock == LOCKSTEP_CLOCK ? "lockstep" : "realtime";
  Background sim({bin("mcnc-drivesim"), "--machine", m, "--bus", "can0", "--clock", clock_name},
                 domain, machine.file("sim"));
  Background x({bin("mcnc-axisnode"), "--machine", m, "--axis", "X1", "--clock", clock_name,
                "--trace", machine.file("X1.jsonl")},
               domain, machine.file("X1"));
  Background z({bin("mcnc-axisnode"), "--machine", m, "--axis", "Z1", "--clock", clock_name,
                "--trace", machine.file("Z1.jsonl")},
               domain, machine.file("Z1"));
  Background ch({bin("mcnc-channel"), "--machine", m, "--channel", "CH1", "--clock", clock_name,
                 "--program", source("launch/programs/long_feed.nc")},
                domain, machine.file("CH1"));

  // The test plays mcnc-launch's part: waits for everyone, starts the run, watches setpoints.
  process::ProcessNode control(domain, "test");
  std::mutex mutex;
  std::map<std::string, ProcessPhase> phases;
  std::uint64_t last_setpoint_cycle = 0;
  dds::Reader<ProcessState> states(control.participant(),
                                   [&](const ProcessState& s, const dds::WriterId&) {
                                     std::lock_guard<std::mutex> lock(mutex);
                                     phases[s.name()] = s.phase();
                                   });
  dds::Reader<AxisSetpoint> setpoints(control.participant(), dds::Keys::of({"X1", "Z1"}),
                                      [&](const AxisSetpoint& sp, const dds::WriterId&) {
                                        std::lock_guard<std::mutex> lock(mutex);
                                        if (sp.axis() == 2) {
                                          last_setpoint_cycle =
                                              std::max(last_setpoint_cycle, sp.cycle());
                                        }
                                      });
  dds::Writer<RunControl> run_control(control.participant());
  auto send = [&](RunCommand command, std::uint64_t generation) {
    RunControl rc;
    rc.generation(generation);
    rc.command(command);
    rc.clock(clock);
    rc.start_ns(clock::monotonic_ns() + 100'000'000);
    run_control.write(rc);
  };
  ASSERT_TRUE(eventually(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return phases["X1"] == PHASE_READY && phases["Z1"] == PHASE_READY &&
               phases["CH1"] == PHASE_READY;
      },
      60s));
  send(RUN_START, 1);

  // Z moves toward -200.
  ASSERT_TRUE(eventually([&] { return last_cmd(machine.file("Z1.jsonl"), "Z1") < -1.0; }, 60s));
  ch.kill(SIGKILL);
  ASSERT_EQ(ch.wait(10s), -SIGKILL);

  // The axis node alarms and commands a quick stop on its own. The drive applies it at the
  // next SYNC; in lockstep the bus's SYNC producer (X1) resumes once it has noticed the lost
  // owner too (its own DDS lease timer), so wait for the drive's state, not a fixed time.
  ASSERT_TRUE(eventually(
      [&] { return !events(read_trace(machine.file("Z1.jsonl")), "alarm").empty(); }, 30s));
  ASSERT_TRUE(eventually(
      [&] {
        const auto states = events(read_trace(machine.file("Z1.jsonl")), "drive", "Z1");
        return !states.empty() && states.back()["state"] == "quick_stop_active";
      },
      30s));
  std::this_thread::sleep_for(300ms);  // at rest: a few pos events with the same act
  send(RUN_STOP, 2);
  // Both nodes leave. iceoryx 2.0's RouDi may hang for good cleaning up after the killed
  // channel (docs/decisions.md 38); a node's DDS teardown then waits on it, and the node leaves
  // by its exit deadline instead, its work done and its alarms raised
  // (process::kExitTeardownHungAfterAlarms).
  for (Background* node : {&x, &z}) {
    const int code = node->wait(20s);
    EXPECT_TRUE(code == 0 || code == process::kExitTeardownHungAfterAlarms) << code;
  }
  sim.kill(SIGTERM);
  EXPECT_EQ(sim.wait(10s), 0);

  const auto trace = read_trace(machine.file("Z1.jsonl"));
  // The first alarm is the node's own detection (DDS liveliness may add "owner lost" later).
  const auto alarms = events(trace, "alarm", "Z1");
  ASSERT_GE(alarms.size(), 1U);
  for (const auto& a : alarms) {
    std::cout << "Z1 alarm: " << a << "\n";
  }
  EXPECT_EQ(alarms[0]["number"], expected_alarm);
  EXPECT_EQ(alarms[0]["axis"], "Z1");
  const std::uint64_t alarm_cycle = alarms[0]["cycle"];
  std::uint64_t last_setpoint = 0;
  {
    std::lock_guard<std::mutex> lock(mutex);
    last_setpoint = last_setpoint_cycle;
  }
  // A setpoint stamped S is used at S+1; the deadline counts the cycles after that.
  EXPECT_LE(alarm_cycle, last_setpoint + 1 + static_cast<std::uint64_t>(machine.deadline_cycles()));
  EXPECT_GT(alarm_cycle, last_setpoint);
  // Quick stop commanded, and the drive at rest in quick stop active.
  const auto drive_states = events(trace, "drive", "Z1");
  ASSERT_FALSE(drive_states.empty());
  EXPECT_EQ(drive_states.back()["state"], "quick_stop_active");
  EXPECT_GE(drive_states.back()["cycle"].get<std::uint64_t>(), alarm_cycle);
  const auto pos = events(trace, "pos", "Z1");
  ASSERT_GE(pos.size(), 3U);
  EXPECT_EQ(pos[pos.size() - 1]["act"], pos[pos.size() - 2]["act"]) << "drive still moving";
  EXPECT_LT(pos.back()["act"].get<double>(), -1.0);
}

}  // namespace

TEST(Safety, KilledChannelMakesAxisNodeQuickStopRealtime) {
  kill_channel_while_moving(21, REALTIME_CLOCK, 2001);  // setpoint deadline
}

TEST(Safety, KilledChannelMakesAxisNodeQuickStopLockstep) {
  kill_channel_while_moving(22, LOCKSTEP_CLOCK, 2002);  // owner lost (DDS liveliness)
}

TEST(Safety, CrashedChildMakesLaunchStopEverythingAndExitNonZero) {
  isolate_iceoryx_host();  // it kills a process on Cyclone DDS: the launcher starts a RouDi
  TestMachine machine("small_lathe.yaml", 23);
  const std::string trace = machine.file("trace.jsonl");
  Background launch({bin("mcnc-launch"), machine.path(), "--program",
                     "CH1=" + source("launch/programs/long_feed.nc"), "--trace", trace},
                    -1, machine.file("launch"));
  // Wait until Z moves, then crash the Z axis node (X1 is the bus's SYNC producer and survives).
  ASSERT_TRUE(eventually([&] { return last_cmd(trace + ".parts/Z1.jsonl", "Z1") < -1.0; }, 60s));
  std::vector<pid_t> pids = pids_with_arg("--axis Z1");
  std::vector<pid_t> mine;
  for (pid_t p : pids) {
    for (pid_t q : pids_with_arg(machine.path())) {
      if (p == q) {
        mine.push_back(p);
      }
    }
  }
  ASSERT_EQ(mine.size(), 1U);
  ::kill(mine[0], SIGKILL);
  const int code = launch.wait(60s);
  EXPECT_NE(code, 0);
  EXPECT_NE(code, -1000) << "launch did not exit";
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "children left running";

  const auto t = read_trace(trace);
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(t.back()["ev"], "summary");
  EXPECT_EQ(t.back()["ok"], false);
  const auto launch_alarms = events(t, "alarm", "launch");
  ASSERT_EQ(launch_alarms.size(), 1U);
  EXPECT_NE(launch_alarms[0]["text"].get<std::string>().find("Z1 killed by signal 9"),
            std::string::npos)
      << launch_alarms[0];
  // The surviving axis quick-stopped and the channel went to reset.
  const auto x_states = events(t, "drive", "X1");
  ASSERT_FALSE(x_states.empty());
  EXPECT_EQ(x_states.back()["state"], "quick_stop_active");
  const auto ch_states = events(t, "state", "CH1");
  EXPECT_EQ(ch_states.back()["state"], "reset");
}

// A realtime machine that needs more CPU than the host has starves every ordinary process, the
// launcher's middleware threads among them. Here two busy loops at its axis nodes' cycle priority
// (SCHED_FIFO 40; only the SYNC timers' short sends run above), one a core, stand for such a
// machine for 8 s: the
// machine's processes cannot run beside them, and no channel is heard. The launcher's supervising
// thread runs above them and E-stops the machine after 5 s of silence; the stop goes through once
// the loops end.
TEST(Safety, ARealtimeMachineTheHostCannotKeepUpWithIsStoppedByItsLauncher) {
  isolate_iceoryx_host();  // the launcher's own RouDi: the loops keep the processes from it
  TestMachine machine("small_lathe.yaml", 24, 50);
  const std::string trace = machine.file("trace.jsonl");
  Background launch({bin("mcnc"), "run", machine.path(), "--clock", "realtime", "--program",
                     "CH1=" + source("launch/programs/long_feed.nc"), "--trace", trace},
                    -1, machine.file("launch"));
  ASSERT_TRUE(eventually([&] { return last_cmd(trace + ".parts/Z1.jsonl", "Z1") < -1.0; }, 60s))
      << slurp(machine.file("launch.err"));
  // Its supervising thread (the main one, whose id is the process's) runs above the machine.
  sched_param param{};
  EXPECT_EQ(::sched_getscheduler(launch.pid()), SCHED_FIFO);
  ASSERT_EQ(::sched_getparam(launch.pid(), &param), 0);
  EXPECT_EQ(param.sched_priority, mcnc::launch::kSupervisorPriority);
  std::vector<std::unique_ptr<Background>> loops;
  for (int core = 0; core < 2; ++core) {
    // Each ends by its own clock: nothing of lower priority could end it.
    loops.push_back(std::make_unique<Background>(
        std::vector<std::string>{"/usr/bin/chrt", "-f", "40", "/usr/bin/python3", "-c",
                                 "import time\nend = time.monotonic() + 8\n"
                                 "while time.monotonic() < end: pass\n"},
        -1, machine.file("loop" + std::to_string(core))));
  }
  const int code = launch.wait(120s);
  for (auto& loop : loops) {
    EXPECT_EQ(loop->wait(30s), 0);
  }
  EXPECT_EQ(code, 1) << slurp(machine.file("launch.out")) << slurp(machine.file("launch.err"));
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "children left running";
  const auto launch_alarms = events(read_trace(trace), "alarm", "launch");
  ASSERT_FALSE(launch_alarms.empty());
  EXPECT_NE(
      launch_alarms[0]["text"].get<std::string>().find(
          "no channel heard for 5 s: this host does not keep up with the machine in realtime"),
      std::string::npos)
      << launch_alarms[0];
}
