// The whole chain through `mcnc run`: channel -> DDS -> axis nodes -> CAN -> simulated drives.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

// The last `pos` event of each axis.
std::map<std::string, nlohmann::json> last_positions(const std::vector<nlohmann::json>& trace) {
  std::map<std::string, nlohmann::json> last;
  for (const auto& e : events(trace, "pos")) {
    last[e["axis"]] = e;
  }
  return last;
}

// `corner_tolerance`: how far from the blended corner the axes may be when the channel sees its
// block end (realtime: the feedback the channel has may be older by up to the deadline).
void expect_xz_move_result(const std::vector<nlohmann::json>& trace,
                           double corner_tolerance = 0.1) {
  ASSERT_FALSE(trace.empty());
  // Summary last, ok, program end M30.
  const auto& summary = trace.back();
  EXPECT_EQ(summary["ev"], "summary");
  EXPECT_EQ(summary["ok"], true);
  EXPECT_EQ(summary["channels"]["CH1"]["end"], 30);
  EXPECT_EQ(summary["channels"]["CH1"]["alarms"], 0);
  // Cycle time: from the first running cycle to the end event, in machine time.
  const auto running = events(trace, "state", "CH1").at(2);
  ASSERT_EQ(running["state"], "running");
  const std::uint64_t end_cycle = events(trace, "end", "CH1").at(0)["cycle"];
  EXPECT_NEAR(summary["channels"]["CH1"]["cycle_time_s"].get<double>(),
              static_cast<double>(end_cycle - running["cycle"].get<std::uint64_t>()) * 0.001, 1e-9);
  EXPECT_EQ(summary["cycles"], end_cycle);
  // Ordered by cycle.
  for (std::size_t i = 1; i < trace.size(); ++i) {
    ASSERT_LE(trace[i - 1]["cycle"].get<std::uint64_t>(), trace[i]["cycle"].get<std::uint64_t>())
        << i;
  }
  // Blocks in program order, with their text.
  const auto blocks = events(trace, "block", "CH1");
  std::vector<int> lines;
  for (const auto& b : blocks) {
    lines.push_back(b["line"]);
  }
  EXPECT_EQ(lines, (std::vector<int>{3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(blocks.at(0)["text"], "N10 G00 X40. Z5.");
  EXPECT_EQ(blocks.at(0)["prog"], "xz_move.nc");
  // States: reset -> idle -> running -> idle.
  std::vector<std::string> states;
  for (const auto& s : events(trace, "state", "CH1")) {
    states.push_back(s["state"]);
  }
  EXPECT_EQ(states, (std::vector<std::string>{"reset", "idle", "running", "idle"}));
  EXPECT_EQ(events(trace, "end", "CH1").at(0)["code"], 30);
  EXPECT_TRUE(events(trace, "alarm").empty());
  // Ownership announced once per axis at start.
  EXPECT_EQ(events(trace, "owner").size(), 2U);
  // The drives stand on the programmed end point: X60 (diameter) = 30 radius, Z10.
  auto last = last_positions(trace);
  EXPECT_NEAR(last.at("X1")["act"].get<double>(), 30.0, 0.001);
  EXPECT_NEAR(last.at("Z1")["act"].get<double>(), 10.0, 0.001);
  EXPECT_NEAR(last.at("X1")["cmd"].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(last.at("Z1")["cmd"].get<double>(), 10.0, 1e-9);
  // N20 (line 4) ends at X40 (r 20), Z-20 in a G64 corner: the path blends it within the
  // 0.01 mm tolerance, so when the block ends (where its line meets the blend, 0.05 mm before
  // the corner) the axes are near, not on, that point. N30 (line 5) ends at X50 (r 25), Z-25
  // before the dwell: an exact stop, on the point.
  const auto ends = events(trace, "pos", "CH1");
  bool corner = false;
  bool stop = false;
  for (const auto& e : ends) {
    if (e["axis"] == "Z1" && std::fabs(e["cmd"].get<double>() + 20.0) < 1e-9) {
      corner = true;
      EXPECT_NEAR(e["act"].get<double>(), -20.0, corner_tolerance);
    }
    if (e["axis"] == "Z1" && std::fabs(e["cmd"].get<double>() + 25.0) < 1e-9) {
      stop = true;
      EXPECT_NEAR(e["act"].get<double>(), -25.0, 0.001);
    }
    if (e["axis"] == "X1" && std::fabs(e["cmd"].get<double>() - 25.0) < 1e-9) {
      EXPECT_NEAR(e["act"].get<double>(), 25.0, 0.001);
    }
  }
  EXPECT_TRUE(corner) << "no block-end pos at Z-20";
  EXPECT_TRUE(stop) << "no block-end pos at Z-25";
}

}  // namespace

TEST(Run, LockstepMoveEndsOnTheProgrammedPoint) {
  TestMachine machine("small_lathe.yaml", 11);
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace},
                          -1, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("CH1: program end M30"), std::string::npos) << r.out;
  expect_xz_move_result(read_trace(trace));
}

TEST(Run, RealtimeMoveEndsOnTheProgrammedPoint) {
  TestMachine machine("small_lathe.yaml", 12, /*deadline_cycles=*/50);
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r = run_realtime({bin("mcnc"), "run", machine.path(), "--program",
                                    "CH1=" + source("launch/programs/xz_move.nc"), "--clock",
                                    "realtime", "--trace", trace, "--trace-pos-every", "5"},
                                   180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // At the corner the axes move at 10 mm/s: 50 cycles of 1 ms of late feedback are 0.5 mm more.
  expect_xz_move_result(read_trace(trace), 0.6);
}

TEST(Run, LockstepArcContourEndsOnItsPoints) {
  // The look-ahead channel on real processes: two arcs, G64 corners blended, a G09 exact stop.
  TestMachine machine("small_lathe.yaml", 30);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program",
           "CH1=" + source("launch/programs/arc_contour.nc"), "--trace", trace_file},
          -1, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto trace = read_trace(trace_file);
  EXPECT_TRUE(events(trace, "alarm").empty());
  EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
  std::vector<int> lines;
  for (const auto& b : events(trace, "block", "CH1")) {
    lines.push_back(b["line"].get<int>());
  }
  EXPECT_EQ(lines, (std::vector<int>{3, 4, 5, 6, 7, 8, 9, 10, 11}));
  // N70 (G09) stops on X50 (r 25) Z-30 with every axis in position; the program ends on
  // X60 (r 30) Z10.
  bool stop = false;
  for (const auto& e : events(trace, "pos", "CH1")) {
    if (e["axis"] == "Z1" && std::fabs(e["cmd"].get<double>() + 30.0) < 1e-9) {
      stop = true;
      EXPECT_NEAR(e["act"].get<double>(), -30.0, 0.001);
    }
  }
  EXPECT_TRUE(stop);
  auto last = last_positions(trace);
  EXPECT_NEAR(last.at("X1")["cmd"].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(last.at("Z1")["cmd"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(last.at("X1")["act"].get<double>(), 30.0, 0.001);
  EXPECT_NEAR(last.at("Z1")["act"].get<double>(), 10.0, 0.001);
}

TEST(Run, LockstepIsDeterministic) {
  std::vector<std::vector<nlohmann::json>> runs;
  for (int i = 0; i < 2; ++i) {
    TestMachine machine("small_lathe.yaml", 13 + i);
    const std::string trace = machine.file("trace.jsonl");
    const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                             "CH1=" + source("launch/programs/xz_move.nc"), "--trace", trace},
                            -1, 180s);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    runs.push_back(read_trace(trace));
  }
  // Same events at the same cycles with the same positions, and the same summary.
  const auto a = trace_until_end(runs[0]);
  const auto b = trace_until_end(runs[1]);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i], b[i]) << "event " << i;
  }
}

TEST(Run, BadMachineFileExits2WithTheKeyPath) {
  for (const std::string tool : {"mcnc", "mcnc-launch"}) {
    std::vector<std::string> argv{bin(tool)};
    if (tool == "mcnc") {
      argv.emplace_back("run");
    }
    argv.push_back(source("tests/fixtures/machines/bad_two_channels.yaml"));
    const RunResult r = run(argv, 15, 60s);
    EXPECT_EQ(r.exit_code, 2) << tool << r.out << r.err;
    EXPECT_NE(r.err.find("channels[1].axes[0]"), std::string::npos) << r.err;
    EXPECT_TRUE(pids_with_arg("bad_two_channels.yaml").empty()) << "nothing may be started";
  }
}

TEST(Run, BadProgramExits2WithLineAndColumnAndMovesNothing) {
  TestMachine machine("small_lathe.yaml", 16);
  const std::string program = machine.file("bad.nc");
  std::ofstream(program) << "%\nG01 X10 F100\nG01 X20 Q5\nM30\n%\n";
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program}, -1, 60s);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("bad.nc:3:"), std::string::npos) << r.err;
  EXPECT_TRUE(pids_with_arg(machine.path()).empty());
}

// An alarm in a called program (M98 from the program directory) names that program's file with
// its own line and column, not the main program's path (issue 25).
TEST(Run, AnAlarmInACalledProgramNamesThatProgramsFileLineAndColumn) {
  TestMachine machine("small_lathe.yaml", 145);
  const std::string dir = machine.file("programs");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/O3200.nc") << "O3200\nG01 X10 Z-5 F100\nG01 X12 Q#\nM99\n";
  const std::string main_program = machine.file("main.nc");
  std::ofstream(main_program) << "%\nO0001\nG00 X20 Z2\nM98 P3200\nM30\n%\n";
  const RunResult r = run(
      {bin("mcnc"), "run", machine.path(), "--progdir", dir, "--program", "CH1=" + main_program},
      -1, 60s);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("O3200.nc:3:10: alarm 3105"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("main.nc:"), std::string::npos) << r.err;
  EXPECT_TRUE(pids_with_arg(machine.path()).empty());
}

TEST(Run, ABadScriptedOperatorCommandExits2AndStartsNothing) {
  TestMachine machine("small_lathe.yaml", 17);
  for (const std::string spec : {"reset", "reset@0", "reset@-5", "jog@100", "reset:CH9@100",
                                 "cycle_start:CH1@x", "reset@99999999999999999999999"}) {
    const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                             "CH1=" + source("launch/programs/xz_move.nc"), "--operator", spec},
                            -1, 60s);
    EXPECT_EQ(r.exit_code, 2) << spec << r.out << r.err;
    EXPECT_NE(r.err.find("--operator " + spec + ": expected ACTION[:CHANNEL]@CYCLE"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(pids_with_arg(machine.path()).empty());
  }
}

// A scripted command the machine cannot take (here stamped beyond the hour ahead that a process
// keeps commands for) is refused by the channel before the run starts: mcnc run names the
// command, who refused it and why, exits 1, and nothing moved (issue 25).
TEST(Run, AScriptedCommandTheMachineRefusesFailsTheRunBeforeAnythingMovesAndSaysWhy) {
  TestMachine machine("small_lathe.yaml", 184);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("launch/programs/xz_move.nc"), "--operator",
                           "feed_hold:CH1@4000000", "--trace", trace_file},
                          -1, 120s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err)
                .find("operator command feed_hold:CH1@4000000 refused by CH1 (too_far_ahead): "
                      "its cycle lies too far beyond the machine's"),
            std::string::npos)
      << r.out << r.err;
  const auto trace = read_trace(trace_file);
  EXPECT_TRUE(events(trace, "block", "CH1").empty());
  std::map<std::string, double> first_act;  // by axis: where it stood
  for (const auto& e : trace) {
    if (e.value("ev", "") == "pos") {
      const auto at = first_act.emplace(e["axis"], e["act"].get<double>()).first;
      EXPECT_EQ(e["act"].get<double>(), at->second) << e;
    }
  }
  EXPECT_TRUE(pids_with_arg(machine.path()).empty());
}

TEST(Run, SubprogramsComeFromTheProgramDirectory) {
  // M98 P22001: O2001 twice, found by number in the directory --progdir names (the machine
  // file names none). Without it the program is rejected before anything starts.
  TestMachine machine("small_lathe.yaml", 43);
  const std::string trace_file = machine.file("trace.jsonl");
  const std::string program = source("tests/integration/programs/calls_from_store.nc");
  const RunResult missing =
      run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program}, -1, 60s);
  EXPECT_EQ(missing.exit_code, 2) << missing.out << missing.err;
  EXPECT_TRUE(pids_with_arg(machine.path()).empty());
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program, "--progdir",
           source("tests/integration/programs/store"), "--trace", trace_file},
          -1, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto trace = read_trace(trace_file);
  // The subprogram's blocks ran twice, from its own file.
  int steps = 0;
  for (const auto& b : events(trace, "block", "CH1")) {
    steps += b["prog"] == "O2001.nc" && b["text"] == "G01 U10. F600" ? 1 : 0;
  }
  EXPECT_EQ(steps, 2);
  EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
  const RunResult bad = run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program,
                             "--progdir", machine.file("no_such_dir")},
                            -1, 60s);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--progdir"), std::string::npos) << bad.err;
}

TEST(Run, ProgramForUnknownChannelExits2) {
  TestMachine machine("small_lathe.yaml", 129);
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH9=" + source("launch/programs/xz_move.nc")},
                          -1, 60s);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no channel CH9"), std::string::npos) << r.err;
}

namespace {

// The operator panel through `--operator` (the commands the HMI sends): at half the feed, a feed
// hold stops Z on its path until the cycle start; the move then ends on its point.
TEST(Run, FeedHoldStopsTheAxesUntilTheCycleStartAndTheFeedOverrideSlowsTheFeed) {
  TestMachine machine("small_lathe.yaml", 85);
  const std::string program = machine.file("feed.nc");
  std::ofstream(program) << "G01 Z-60 F3000\nM30\n";  // 50 mm/s, at 50 %: 25 mm/s, 2.4 s
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program, "--trace", trace_file,
           "--operator", "feed_override=50:CH1@1", "--operator", "feed_hold:CH1@1000", "--operator",
           "cycle_start:CH1@2000"},
          -1, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto trace = read_trace(trace_file);
  std::vector<std::pair<std::uint64_t, std::string>> states;
  for (const auto& s : events(trace, "state", "CH1")) {
    states.emplace_back(s["cycle"].get<std::uint64_t>(), s["state"].get<std::string>());
  }
  ASSERT_GE(states.size(), 5U);
  EXPECT_EQ(states[3], (std::pair<std::uint64_t, std::string>{1000, "hold"}));
  EXPECT_EQ(states[4], (std::pair<std::uint64_t, std::string>{2000, "running"}));
  // Z stands from shortly after the hold to the start.
  std::map<std::uint64_t, double> z;
  for (const auto& p : events(trace, "pos", "Z1")) {
    z[p["cycle"].get<std::uint64_t>()] = p["cmd"].get<double>();
  }
  const double held = z.at(1200);
  EXPECT_LT(held, -10.0);
  EXPECT_GT(held, -40.0);
  for (std::uint64_t c = 1200; c <= 2000; c += 10) {
    EXPECT_DOUBLE_EQ(z.at(c), held) << c;
  }
  // Before the hold Z went at 25 mm/s.
  EXPECT_NEAR((z.at(900) - z.at(500)) / 0.4, -25.0, 0.01);
  EXPECT_DOUBLE_EQ(last_positions(trace).at("Z1")["cmd"].get<double>(), -60.0);
  // 2.4 s of feed, the hold of a second and the ramps.
  const double cycle_time = trace.back()["channels"]["CH1"]["cycle_time_s"].get<double>();
  EXPECT_GT(cycle_time, 3.4);
  EXPECT_LT(cycle_time, 3.6);
}

}  // namespace
