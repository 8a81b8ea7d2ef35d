// The axis node brings its drive up by CANopen (boot-up, SDO configuration, NMT start) against
// the real simulator process over the bus; a drive that refuses an SDO is a clear alarm at
// start-up that names the object, and nothing moves.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// Adds `line` (indented as an axis key) after every axis's in_position line of the machine file
// (only the first axis's with `first_only`).
void add_to_each_axis(const TestMachine& machine, const std::string& line,
                      bool first_only = false) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::ofstream(machine.path()) << std::regex_replace(
      text.str(), std::regex("(\\n    in_position: [^\\n]*)"), "$1\n    " + line,
      first_only ? std::regex_constants::format_first_only : std::regex_constants::format_default);
}

// The last commanded-and-reached positions of X1 and Z1 in the trace (the axis nodes' samples
// and the channel's block ends) are those of xz_move.nc's last block: X60 (r30) Z10.
void expect_xz_move_end(const std::vector<nlohmann::json>& trace) {
  double x1 = 0.0;
  double z1 = 0.0;
  for (const auto& p : events(trace, "pos")) {
    (p["axis"] == "X1" ? x1 : z1) = p["act"].get<double>();
  }
  EXPECT_NEAR(x1, 30.0, 0.001);
  EXPECT_NEAR(z1, 10.0, 0.001);
}

TEST(DriveStartup, ARefusedSdoIsAnAlarmNamingTheObject) {
  TestMachine machine("small_lathe.yaml", 31);
  Background drives({bin("mcnc-drivesim"), "--machine", machine.path(), "--bus", "can0",
                     "--refuse-sdo", "1:0x6060"},
                    machine.domain(), machine.file("drivesim.log"));
  const RunResult r = run({bin("mcnc-axisnode"), "--machine", machine.path(), "--axis", "X1"},
                          machine.domain(), 60s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::string said = r.out + r.err;
  EXPECT_NE(said.find("node 1: writing 0x6060:00 (modes of operation) was refused: data cannot be "
                      "transferred or stored because of the present device state (SDO abort "
                      "0x08000022)"),
            std::string::npos)
      << said;
}

TEST(DriveStartup, TheOtherDriveOfTheBusComesUp) {
  // The same bus, the same refusal for node 1: node 2 (Z1) is configured and started.
  TestMachine machine("small_lathe.yaml", 32);
  Background drives({bin("mcnc-drivesim"), "--machine", machine.path(), "--bus", "can0",
                     "--refuse-sdo", "1:0x6060"},
                    machine.domain(), machine.file("drivesim.log"));
  Background axis({bin("mcnc-axisnode"), "--machine", machine.path(), "--axis", "Z1"},
                  machine.domain(), machine.file("z1.log"));
  // Started, it waits for its channel (which is not there): it must not have exited.
  std::this_thread::sleep_for(3s);
  EXPECT_EQ(axis.wait(0s), -1000) << "the axis node of a healthy drive exited";
}

}  // namespace

namespace {

// Runs the xz program with one injected drive fault; the trace.
std::vector<nlohmann::json> run_with_fault(int domain, const std::string& fault) {
  TestMachine machine("small_lathe.yaml", domain);
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program",
           "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace, "--drive-fault", fault},
          -1, 180s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the run ends in an alarm
  return read_trace(trace);
}

TEST(DriveFaults, OverCurrentEmcyIsAnAxisAlarmWithTheErrorInWords) {
  const auto trace = run_with_fault(33, "can0:1:overcurrent@2000");
  bool found = false;
  for (const auto& a : events(trace, "alarm", "X1")) {
    if (a["number"] == 2003) {
      found = true;
      EXPECT_EQ(a["text"], "drive fault: EMCY 0x2310 continuous over-current");
      EXPECT_GE(a["cycle"].get<std::uint64_t>(), 1990U);
    }
  }
  EXPECT_TRUE(found);
}

TEST(DriveFaults, SilentHeartbeatIsAnAlarmWithinTheConsumerTime) {
  // Heartbeats every 100 cycles (0x1017 = 100 ms at 1 ms), consumer time 150 cycles: the last
  // one before SYNC 1500 comes at 1400, the alarm at most 151 cycles later.
  const auto trace = run_with_fault(34, "can0:2:heartbeat_stop@1500");
  bool found = false;
  for (const auto& a : events(trace, "alarm", "Z1")) {
    if (a["number"] == 2006) {
      found = true;
      const auto cycle = a["cycle"].get<std::uint64_t>();
      EXPECT_GE(cycle, 1500U);
      EXPECT_LE(cycle, 1400U + 151U + 20U);  // a few cycles of start-up offset
    }
  }
  EXPECT_TRUE(found);
}

}  // namespace

namespace {

TEST(DriveFaults, AnOperatorResetBringsTheDriveBackAndTheProgramRunsAgain) {
  // Over-current at SYNC 2000, the operator's RESET at cycle 3000 and CYCLE START at 3100.
  TestMachine machine("small_lathe.yaml", 38);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run(
      {bin("mcnc"), "run", machine.path(), "--program",
       "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace_file, "--drive-fault",
       "can0:1:overcurrent@2000", "--operator", "reset@3000", "--operator", "cycle_start:CH1@3100"},
      -1, 180s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the alarm stays in the result
  const auto trace = read_trace(trace_file);
  // The fault: an alarm with the EMCY in words, then the drive in fault.
  const auto alarms = events(trace, "alarm");
  ASSERT_EQ(alarms.size(), 2U);  // X1's and the channel's, nothing after the reset
  EXPECT_EQ(alarms[0]["number"], 2003);
  EXPECT_EQ(alarms[0]["text"], "drive fault: EMCY 0x2310 continuous over-current");
  EXPECT_EQ(alarms[1]["number"], 1201);
  for (const auto& a : alarms) {
    EXPECT_LT(a["cycle"].get<std::uint64_t>(), 3000U);
  }
  // After the reset X1's drive walks back to operation enabled, in CiA 402 order.
  std::vector<std::string> after;
  for (const auto& d : events(trace, "drive", "X1")) {
    if (d["cycle"].get<std::uint64_t>() >= 3000) {
      after.push_back(d["state"]);
      EXPECT_LE(d["cycle"].get<std::uint64_t>(), 3010U);
    }
  }
  EXPECT_EQ(after, (std::vector<std::string>{"switch_on_disabled", "ready_to_switch_on",
                                             "switched_on", "operation_enabled"}));
  // The channel: reset, idle once the drive is back, running at the cycle start, program end.
  std::vector<std::pair<std::uint64_t, std::string>> states;
  for (const auto& s : events(trace, "state")) {
    if (s["cycle"].get<std::uint64_t>() >= 3000) {
      states.emplace_back(s["cycle"].get<std::uint64_t>(), s["state"]);
    }
  }
  ASSERT_EQ(states.size(), 4U);
  EXPECT_EQ(states[0], (std::pair<std::uint64_t, std::string>{3000, "reset"}));
  EXPECT_EQ(states[1].second, "idle");
  EXPECT_GT(states[1].first, 3003U);
  EXPECT_EQ(states[2], (std::pair<std::uint64_t, std::string>{3100, "running"}));
  EXPECT_EQ(states[3].second, "idle");
  const auto ends = events(trace, "end");
  ASSERT_EQ(ends.size(), 1U);
  EXPECT_EQ(ends[0]["code"], 30);
  EXPECT_GT(ends[0]["cycle"].get<std::uint64_t>(), 3100U);
  // And the axes got to the program's last point (X60 Z10: X1 at radius 30).
  double x1 = 0.0;
  double z1 = 0.0;
  for (const auto& p : events(trace, "pos")) {  // the last of the axis nodes' and the channel's
    (p["axis"] == "X1" ? x1 : z1) = p["cmd"].get<double>();
  }
  EXPECT_NEAR(x1, 30.0, 1e-6);
  EXPECT_NEAR(z1, 10.0, 1e-6);
}

TEST(DriveStartup, AxesHomeAtStartThenRunTheProgramFromTheirHome) {
  // Both axes home by method 37 (here is home) with a home offset of 50 mm: the drives stand
  // at 0, become 50 without moving, switch to CSP, and the program runs from there.
  TestMachine machine("small_lathe.yaml", 40);
  add_to_each_axis(machine, "homing: {method: 37, offset: 50}");
  const auto trace = run_to_clean_end(machine, "launch/programs/xz_move.nc");
  for (const std::string axis : {"X1", "Z1"}) {
    const auto modes = events(trace, "mode", axis);
    ASSERT_EQ(modes.size(), 1U) << axis;
    EXPECT_EQ(modes[0]["mode"], "csp");
    EXPECT_LE(modes[0]["cycle"].get<std::uint64_t>(), 10U);
  }
  // The channel starts once both are homed and in CSP, from the home positions.
  std::uint64_t running = 0;
  for (const auto& s : events(trace, "state", "CH1")) {
    if (s["state"] == "running") {
      running = s["cycle"].get<std::uint64_t>();
    }
  }
  EXPECT_GT(running, events(trace, "mode", "X1")[0]["cycle"].get<std::uint64_t>());
  for (const auto& p : events(trace, "pos")) {
    if (p["src"] != "CH1" && p["cycle"].get<std::uint64_t>() == 10) {
      EXPECT_NEAR(p["act"].get<double>(), 50.0, 0.5) << p.dump();  // just set off from home
    }
  }
  expect_xz_move_end(trace);
}

TEST(DriveStartup, CanopenSettingsFromTheMachineFileTakeEffect) {
  // X1's TPDO2 with the drive's velocity and following error (on both axes the bus would be
  // over 70 %), a 50 ms heartbeat and a quick stop deceleration written at start-up: the
  // lockstep run waits for both TPDOs of every SYNC and ends on its points.
  TestMachine machine("small_lathe.yaml", 41);
  add_to_each_axis(machine, "tpdo2: [velocity_actual, following_error_actual]", true);
  add_to_each_axis(machine, "heartbeat_ms: 50\n    quick_stop_deceleration: 3000");
  const auto trace = run_to_clean_end(machine, "launch/programs/xz_move.nc");
  EXPECT_TRUE(events(trace, "alarm").empty());
  expect_xz_move_end(trace);

  // With the 50 ms heartbeat, a drive falling silent is lost within 75 cycles of its last.
  TestMachine silent("small_lathe.yaml", 42);
  add_to_each_axis(silent, "heartbeat_ms: 50");
  const std::string trace_file = silent.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", silent.path(), "--program",
                           "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace_file,
                           "--drive-fault", "can0:2:heartbeat_stop@1500"},
                          -1, 180s);
  EXPECT_EQ(r.exit_code, 1);
  bool found = false;
  for (const auto& a : events(read_trace(trace_file), "alarm", "Z1")) {
    found = found || a["number"] == 2006;
    if (a["number"] == 2006) {
      EXPECT_GE(a["cycle"].get<std::uint64_t>(), 1500U);
      EXPECT_LE(a["cycle"].get<std::uint64_t>(), 1450U + 76U + 20U);
    }
  }
  EXPECT_TRUE(found);
}

TEST(DriveCsp, TenThousandCyclesWithinAFollowingErrorBound) {
  // The drives follow for over 10 000 cycles with a 1.2 mm following-error limit: no alarm,
  // and every recorded |cmd - act| below the bound.
  TestMachine machine("small_lathe.yaml", 35);
  add_to_each_axis(machine, "following_error_limit: 1.2");
  const auto trace = run_to_clean_end(machine, "tests/integration/programs/csp_back_and_forth.nc",
                                      {"--trace-pos-every", "5"});
  EXPECT_GE(trace.back()["cycles"].get<std::uint64_t>(), 10000U);
  EXPECT_TRUE(events(trace, "alarm").empty());
  double worst = 0.0;
  std::size_t samples = 0;
  for (const auto& p : events(trace, "pos")) {
    if (p["src"] == "X1" || p["src"] == "Z1") {
      worst = std::max(worst, std::fabs(p["cmd"].get<double>() - p["act"].get<double>()));
      ++samples;
    }
  }
  EXPECT_GT(samples, 3000U);
  EXPECT_LT(worst, 1.2);
  EXPECT_GT(worst, 0.1);  // the drives really moved at speed
}

}  // namespace

namespace {

TEST(BadFrames, AreCountedAndMoveNothing) {
  // Bad frames on the bus for the first four seconds of the run: the program still ends on its
  // points without an alarm, and the nodes say they dropped malformed frames.
  TestMachine machine("small_lathe.yaml", 37);
  Background noise(
      {source("tests/integration/bad_frames.py"), "239.255.37.1", std::to_string(24000 + 37), "4"},
      -1, machine.file("noise.log"));
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace_file},
                          -1, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto trace = read_trace(trace_file);
  EXPECT_TRUE(events(trace, "alarm").empty());
  std::map<std::string, nlohmann::json> last;
  for (const auto& e : events(trace, "pos")) {
    last[e["axis"]] = e;
  }
  EXPECT_NEAR(last.at("X1")["act"].get<double>(), 30.0, 0.001);
  EXPECT_NEAR(last.at("Z1")["act"].get<double>(), 10.0, 0.001);
  const std::string said = r.out + r.err;
  const std::regex counted(R"(\[X1\] \[info\] stopped: \d+ EMCY, ([1-9]\d*) malformed frames)");
  EXPECT_TRUE(std::regex_search(said, counted))
      << said.substr(said.size() > 3000 ? said.size() - 3000 : 0);
}

}  // namespace
