// Several channels machining together (issue 7): the spec's multi-channel examples run as real
// processes in lockstep, their "Expected" lists asserted from the trace.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <thread>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

using Trace = std::vector<nlohmann::json>;

// Runs `programs` (channel -> file) on `machine` with `mcnc run`; the exit code and the trace.
struct MultiRun {
  int exit_code = -1;
  std::string output;
  Trace trace;
};

MultiRun run_channels(const TestMachine& machine,
                      const std::map<std::string, std::string>& programs,
                      const std::vector<std::string>& extra = {}) {
  const std::string trace_file = machine.file("trace.jsonl");
  std::vector<std::string> argv{bin("mcnc"), "run", machine.path(), "--trace", trace_file};
  for (const auto& [channel, file] : programs) {
    argv.insert(argv.end(), {"--program", channel + "=" + file});
  }
  argv.insert(argv.end(), extra.begin(), extra.end());
  const RunResult r = run(argv, -1, std::chrono::seconds(300));
  return MultiRun{r.exit_code, r.out + r.err, read_trace(trace_file)};
}

// A program of the source tree with every `from` replaced by `to`, written beside the machine.
std::string variant(const TestMachine& machine, const std::string& program, const std::string& from,
                    const std::string& to) {
  std::ifstream in(source(program));
  std::stringstream text;
  text << in.rdbuf();
  const std::string out = machine.file(program.substr(program.find_last_of('/') + 1));
  std::ofstream(out) << std::regex_replace(text.str(), std::regex(from), to);
  return out;
}

// The cycle of the first event `ev` of channel `ch` whose fields match `match`.
std::uint64_t cycle_of(const Trace& trace, const std::string& ev, const std::string& ch,
                       const nlohmann::json& match = nlohmann::json::object()) {
  for (const auto& e : events(trace, ev, ch)) {
    bool ok = true;
    for (const auto& [key, value] : match.items()) {
      ok = ok && e.contains(key) && e[key] == value;
    }
    if (ok) {
      return e["cycle"].get<std::uint64_t>();
    }
  }
  ADD_FAILURE() << "no " << ev << " of " << ch << " matching " << match.dump();
  return 0;
}

std::uint64_t block_at(const Trace& trace, const std::string& ch, int line) {
  return cycle_of(trace, "block", ch, {{"line", line}});
}
std::uint64_t arrival(const Trace& trace, const std::string& ch, int p) {
  return cycle_of(trace, "sync_arrive", ch, {{"p", p}});
}
std::uint64_t release(const Trace& trace, const std::string& ch, int p) {
  return cycle_of(trace, "sync_release", ch, {{"p", p}});
}

const std::string kG041 = "tests/integration/programs/g041/";

// Each axis's commanded point at the last block end of channel `ch`.
std::map<std::string, double> end_points(const Trace& trace, const std::string& ch) {
  std::map<std::string, double> last;
  for (const auto& e : events(trace, "pos", ch)) {
    last[e["axis"]] = e["cmd"];
  }
  return last;
}

// CT-G041-01 (spec dafeng §3.1): the "Expected" list, for the plain form and its variants.
void expect_three_channel_order(const MultiRun& r) {
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  EXPECT_TRUE(events(t, "alarm").empty());
  // 1. Nothing after P1 until all three have reached P1.
  const std::uint64_t all_at_p1 =
      std::max({arrival(t, "CH1", 1), arrival(t, "CH2", 1), arrival(t, "CH3", 1)});
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {
    EXPECT_GE(release(t, ch, 1), all_at_p1) << ch;
    EXPECT_GT(block_at(t, ch, 5), all_at_p1) << ch;  // the block after P1
  }
  // 2. CH3 does not take part in P2; it waits at P3 for CH2 only.
  EXPECT_TRUE(events(t, "sync_arrive", "CH3").size() == 3U);  // P1, P3, P4
  EXPECT_EQ(events(t, "sync_arrive", "CH3").at(1)["channels"], nlohmann::json({2, 3}));
  EXPECT_LT(arrival(t, "CH3", 3), arrival(t, "CH1", 2));  // its own pace, not P2's
  // 3. Each M05 after P2 only once the other channel has reached P2.
  EXPECT_GT(block_at(t, "CH1", 8), arrival(t, "CH2", 2));
  EXPECT_GT(block_at(t, "CH2", 7), arrival(t, "CH1", 2));
  // The spindles turn while their channels wait (M03 before P1), and M05 stops CH1's only after
  // P2.
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {
    EXPECT_LE(cycle_of(t, "spindle", ch, {{"rpm", 1000.0}}), arrival(t, ch, 1)) << ch;
  }
  EXPECT_GT(cycle_of(t, "spindle", "CH1", {{"rpm", 0.0}}), arrival(t, "CH2", 2));
  // 4. CH3's G0 X0 Z0 after CH2 reached P3 (hence after CH1 reached P2).
  EXPECT_GT(block_at(t, "CH3", 10), arrival(t, "CH2", 3));
  EXPECT_GT(block_at(t, "CH3", 10), arrival(t, "CH1", 2));
  // 5. CH1 is not in P3: it reaches P4 and waits there while CH2 and CH3 go on.
  EXPECT_TRUE(events(t, "sync_arrive", "CH1").size() == 3U);  // P1, P2, P4
  EXPECT_LT(arrival(t, "CH1", 4), arrival(t, "CH2", 4));
  // 6. P4 joins all three: no M30 before every channel reached P4.
  const std::uint64_t all_at_p4 =
      std::max({arrival(t, "CH1", 4), arrival(t, "CH2", 4), arrival(t, "CH3", 4)});
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {
    EXPECT_GT(cycle_of(t, "end", ch), all_at_p4) << ch;
    EXPECT_EQ(events(t, "end", ch).at(0)["code"], 30) << ch;
    // Every mark in the first round.
    for (const auto& e : events(t, "sync_release", ch)) {
      EXPECT_EQ(e["gen"], 1) << ch;
    }
  }
  // While waiting a channel is in the waiting state.
  std::vector<std::string> ch1_states;
  for (const auto& s : events(t, "state", "CH1")) {
    ch1_states.push_back(s["state"]);
  }
  EXPECT_EQ(std::count(ch1_states.begin(), ch1_states.end(), "waiting"), 3) << r.output;
}

}  // namespace

TEST(MultiChannel, ThreeChannelWaitMarksAsTheSpecExample) {
  TestMachine machine("three_channel.yaml", 50);
  const MultiRun r = run_channels(machine, {{"CH1", source(kG041 + "O1001.nc")},
                                            {"CH2", source(kG041 + "O1002.nc")},
                                            {"CH3", source(kG041 + "O1003.nc")}});
  expect_three_channel_order(r);
  EXPECT_EQ(events(r.trace, "sync_arrive", "CH1").at(0)["channels"], nlohmann::json({1, 2, 3}));
  EXPECT_EQ(events(r.trace, "sync_arrive", "CH1").at(2)["all"], true);
}

TEST(MultiChannel, QMinusOneJoinsEveryChannelInAutomaticOperation) {
  TestMachine machine("three_channel.yaml", 51);
  const MultiRun r =
      run_channels(machine, {{"CH1", variant(machine, kG041 + "O1001.nc", "Q123", "Q-1")},
                             {"CH2", variant(machine, kG041 + "O1002.nc", "Q123", "Q-1")},
                             {"CH3", variant(machine, kG041 + "O1003.nc", "Q123", "Q-1")}});
  expect_three_channel_order(r);
  EXPECT_EQ(events(r.trace, "sync_arrive", "CH1").at(0)["all"], true);
}

namespace {

std::string write_program(const TestMachine& machine, const std::string& name,
                          const std::string& text) {
  const std::string path = machine.file(name);
  std::ofstream(path) << text;
  return path;
}

// Both channels raise `number` at their mark, and neither runs a block after it.
void expect_alarm_at_marks(const MultiRun& r, int number) {
  EXPECT_NE(r.exit_code, 0);
  for (const std::string ch : {"CH1", "CH2"}) {
    const auto alarms = events(r.trace, "alarm", ch);
    ASSERT_EQ(alarms.size(), 1U) << ch << r.output;
    EXPECT_EQ(alarms.at(0)["number"], number) << ch;
    EXPECT_EQ(alarms.at(0)["line"], 3) << ch;
    EXPECT_TRUE(events(r.trace, "sync_release", ch).empty()) << ch;
    EXPECT_EQ(events(r.trace, "block", ch).back()["line"], 3) << ch;
  }
}

}  // namespace

// CH1 waits at G04.1 P1 Q12 after a feed move; CH2 comes to `ch2_mark` sooner.
MultiRun run_against(int domain, const std::string& ch2_mark) {
  TestMachine machine("three_channel.yaml", domain);
  return run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc", "G00 X20 Z5\nG01 Z-5 F900\nG04.1 P1 Q12\nM30\n")},
       {"CH2", write_program(machine, "ch2.nc", "G00 X20 Z5\nG00 Z2\n" + ch2_mark + "\nM30\n")}});
}

// Spec dafeng §3.1 "decide" 2: the same P with participant sets that disagree.
TEST(MultiChannel, ParticipantSetsThatDisagreeAreAMismatchAlarmInBothChannels) {
  expect_alarm_at_marks(run_against(52, "G04.1 P1 Q123"), 1210);
}

// Spec dafeng §3.1 "decide" 1: different marks whose sets name each other.
TEST(MultiChannel, WaitsInACircleAreADeadlockAlarmInBothChannels) {
  expect_alarm_at_marks(run_against(53, "G04.1 P2 Q12"), 1211);
}

// CT-G041-01 variants for two-digit channels (spec dafeng §3.1): Q10 joins channels 1 and 10,
// Q1 Q1=2 channels 1 and 12; a G04.1 with neither P nor Q waits for nobody.
TEST(MultiChannel, TwoDigitChannelsOnATwelveChannelMachine) {
  TestMachine machine("twelve_channel.yaml", 54);
  const MultiRun r = run_channels(
      machine, {{"CH1", write_program(machine, "ch1.nc",
                                      "G01 X20 F600\nG04.1 P1 Q10\nG01 X30\nG04.1 P2 Q1 Q1=2\n"
                                      "G04.1\nG00 X0\nM30\n")},
                {"CH10", write_program(machine, "ch10.nc", "G04.1 P1 Q10\nG00 X10\nM30\n")},
                {"CH12", write_program(machine, "ch12.nc",
                                       "G01 X5 F300\nG04.1 P2 Q1 Q1=2\nG00 X12\nM30\n")}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  EXPECT_TRUE(events(t, "alarm").empty());
  EXPECT_EQ(events(t, "sync_arrive", "CH10").at(0)["channels"], nlohmann::json({1, 10}));
  EXPECT_EQ(events(t, "sync_arrive", "CH12").at(0)["channels"], nlohmann::json({1, 12}));
  // CH10 and CH12 are there first and wait for CH1.
  EXPECT_LT(arrival(t, "CH10", 1), arrival(t, "CH1", 1));
  EXPECT_GE(release(t, "CH10", 1), arrival(t, "CH1", 1));
  EXPECT_GT(block_at(t, "CH10", 2), arrival(t, "CH1", 1));
  EXPECT_LT(arrival(t, "CH12", 2), arrival(t, "CH1", 2));
  EXPECT_GT(block_at(t, "CH12", 3), arrival(t, "CH1", 2));
  // The bare G04.1 of CH1 arrives nowhere and waits for nobody.
  EXPECT_EQ(events(t, "sync_arrive", "CH1").size(), 2U);
  EXPECT_LE(block_at(t, "CH1", 6), block_at(t, "CH1", 5) + 1);
  // The other channels never ran.
  for (int c : {2, 3, 4, 5, 6, 7, 8, 9, 11}) {
    const std::string ch = "CH" + std::to_string(c);
    for (const auto& s : events(t, "state", ch)) {
      EXPECT_NE(s["state"], "running") << ch;
    }
  }
  for (const std::string ch : {"CH1", "CH10", "CH12"}) {
    EXPECT_EQ(events(t, "end", ch).at(0)["code"], 30) << ch;
  }
}

namespace {

// The spec's G144 examples: CH1 runs O1000 of `dir`, the program store is `dir`.
MultiRun run_store(int domain, const std::string& dir,
                   const std::map<std::string, std::string>& programs) {
  TestMachine machine("three_channel.yaml", domain);
  std::map<std::string, std::string> paths;
  for (const auto& [ch, file] : programs) {
    paths[ch] = source(dir + file);
  }
  return run_channels(machine, paths, {"--progdir", source(dir)});
}

// Kills this test's channel `ch` half a second after it started the block on `line`.
void kill_channel_during(const TestMachine& machine, const std::string& trace,
                         const std::string& ch, int line) {
  std::vector<pid_t> pids;
  ASSERT_TRUE(eventually(
      [&] {
        pids = pids_with_arg(machine.path() + " --channel " + ch);  // this test's only
        return !pids.empty();
      },
      60s));
  ASSERT_TRUE(eventually(
      [&] {
        std::ifstream parts(trace + ".parts/" + ch + ".jsonl");
        std::string all((std::istreambuf_iterator<char>(parts)), std::istreambuf_iterator<char>());
        return all.find("\"line\":" + std::to_string(line)) != std::string::npos;
      },
      60s));
  std::this_thread::sleep_for(500ms);
  ::kill(pids[0], SIGKILL);
}

// After a child was killed: the launcher's alarm names it, and `axes` ended in quick stop.
void expect_stopped_after_kill(const Trace& t, const std::string& killed,
                               const std::vector<std::string>& axes) {
  bool launch_saw_it = false;
  for (const auto& a : events(t, "alarm", "launch")) {
    launch_saw_it = launch_saw_it || a["text"].get<std::string>().find(killed) != std::string::npos;
  }
  EXPECT_TRUE(launch_saw_it) << killed;
  for (const std::string& axis : axes) {
    const auto drive = events(t, "drive", axis);
    ASSERT_FALSE(drive.empty()) << axis;
    EXPECT_EQ(drive.back()["state"], "quick_stop_active") << axis;
  }
}

std::vector<int> lines_of(const Trace& t, const std::string& ch) {
  std::vector<int> lines;
  for (const auto& b : events(t, "block", ch)) {
    lines.push_back(b["line"]);
  }
  return lines;
}

}  // namespace

// CT-G144-01 (spec dafeng §3.4 example 1): H1, released by G145.
TEST(MultiChannel, SubcallWithWaitReleasedByG145) {
  const MultiRun r = run_store(55, "tests/integration/programs/g144_wait/", {{"CH1", "O1000.nc"}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  const auto calls = events(t, "subcall", "CH1");
  ASSERT_EQ(calls.size(), 1U);
  EXPECT_EQ(calls[0]["target"], "CH2");
  EXPECT_EQ(calls[0]["program"], 2000);
  EXPECT_EQ(calls[0]["wait"], true);
  const auto releases = events(t, "subcall_release", "CH2");
  ASSERT_EQ(releases.size(), 1U);
  EXPECT_EQ(releases[0]["call_id"], calls[0]["call_id"]);
  EXPECT_EQ(releases[0]["outcome"], "released");
  // CH2 runs O2000 from the store: every block before G145 precedes CH1's G01 Z-10.
  EXPECT_EQ(lines_of(t, "CH2"), (std::vector<int>{3, 4, 5, 6, 7}));
  EXPECT_EQ(events(t, "block", "CH2").at(0)["prog"], "O2000.nc");
  const std::uint64_t g145 = block_at(t, "CH2", 5);
  EXPECT_GT(block_at(t, "CH2", 3), cycle_of(t, "subcall", "CH1"));
  EXPECT_GT(block_at(t, "CH1", 6), g145);
  EXPECT_EQ(releases[0]["cycle"], g145);
  // After G145 both run in parallel; O2000's M99 ends it (no loop) and CH2 goes idle.
  EXPECT_LT(block_at(t, "CH2", 6), cycle_of(t, "end", "CH1"));
  EXPECT_EQ(events(t, "end", "CH2").at(0)["code"], 99);
  EXPECT_EQ(events(t, "state", "CH2").back()["state"], "idle");
  EXPECT_EQ(r.trace.back()["channels"]["CH2"]["end"], 99);
}

// CT-G144-02 (example 2): H0 starts CH2 then CH3 without waiting; all meet at P1.
TEST(MultiChannel, SubcallsWithoutWaitRunInParallelAndMeetAtAMark) {
  const MultiRun r =
      run_store(56, "tests/integration/programs/g144_nowait/", {{"CH1", "O1000.nc"}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  const auto calls = events(t, "subcall", "CH1");
  ASSERT_EQ(calls.size(), 2U);
  EXPECT_EQ(calls[0]["target"], "CH2");
  EXPECT_EQ(calls[1]["target"], "CH3");
  EXPECT_EQ(calls[0]["wait"], false);
  // CH1 does not block: its move starts right after the two calls.
  EXPECT_LE(block_at(t, "CH1", 5), cycle_of(t, "subcall", "CH1", {{"target", "CH3"}}) + 1);
  EXPECT_LE(block_at(t, "CH2", 3), block_at(t, "CH3", 3));
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {
    EXPECT_GE(release(t, ch, 1),
              std::max({arrival(t, "CH1", 1), arrival(t, "CH2", 1), arrival(t, "CH3", 1)}))
        << ch;
  }
  EXPECT_EQ(events(t, "end", "CH1").at(0)["code"], 30);
  EXPECT_EQ(events(t, "end", "CH2").at(0)["code"], 99);
  EXPECT_EQ(events(t, "end", "CH3").at(0)["code"], 99);
  // The called programs released nobody waiting (H0): their ends still say so.
  EXPECT_EQ(events(t, "subcall_release", "CH2").size(), 1U);
}

// CT-G144-03 (example 3): three operations selected by Q, strictly in order, each call
// waiting until CH2 is idle again; a call without Q ends at M30 without G145.
TEST(MultiChannel, RepeatedSubcallsWaitForTheTargetAndPassTheirArguments) {
  const MultiRun r = run_store(57, "tests/integration/programs/g144_ops/", {{"CH1", "O1000.nc"}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  const auto calls = events(t, "subcall", "CH1");
  ASSERT_EQ(calls.size(), 4U);
  // The operations in the order of Q: N10 (line 7), N20 (line 11), N30 (line 15).
  std::vector<int> ops;
  for (const int l : lines_of(t, "CH2")) {
    if (l == 7 || l == 11 || l == 15 || l == 6) {
      ops.push_back(l);
    }
  }
  EXPECT_EQ(ops, (std::vector<int>{7, 11, 15, 6}));  // the fourth call reaches M30 (line 6)
  const auto ends = events(t, "end", "CH2");
  ASSERT_EQ(ends.size(), 4U);
  EXPECT_EQ(ends[3]["code"], 30);
  for (std::size_t k = 0; k + 1 < calls.size(); ++k) {
    // Each call only once CH2 ended the last one, and CH1 went on at its G145.
    EXPECT_GT(calls[k + 1]["cycle"].get<std::uint64_t>(), ends[k]["cycle"].get<std::uint64_t>())
        << k;
  }
  const auto releases = events(t, "subcall_release", "CH2");
  ASSERT_EQ(releases.size(), 4U);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(releases[k]["call_id"], calls[k]["call_id"]);
    EXPECT_EQ(releases[k]["outcome"], "released");
  }
  // CH1's move after each call overlaps CH2's G00 X0 after that G145.
  EXPECT_LT(block_at(t, "CH1", 6), ends[0]["cycle"].get<std::uint64_t>());
  EXPECT_EQ(events(t, "end", "CH1").at(0)["code"], 30);
}

// CT-CH-01 (spec dafeng §3.5): a program for CH1 started in CH2, directly or by G144.
TEST(MultiChannel, AProgramForAnotherChannelIsAnAlarmBeforeItMoves) {
  TestMachine machine("three_channel.yaml", 58);
  const std::string dir = source("tests/integration/programs/g144_wait/");
  const MultiRun direct = run_channels(machine, {{"CH2", dir + "O1000.nc"}});
  // `mcnc run` checks every program before it brings the machine up.
  EXPECT_NE(direct.exit_code, 0);
  EXPECT_NE(direct.output.find("O1000.nc:2:1: alarm 1119: this program may only run in channel 1"),
            std::string::npos)
      << direct.output;
  EXPECT_TRUE(direct.trace.empty());

  const std::string caller = write_program(machine, "call.nc", "G144 N3 P2000 H1\nM30\n");
  const MultiRun called = run_channels(machine, {{"CH1", caller}}, {"--progdir", dir});
  EXPECT_NE(called.exit_code, 0);
  const auto in_ch3 = events(called.trace, "alarm", "CH3");
  ASSERT_EQ(in_ch3.size(), 1U) << called.output;
  EXPECT_EQ(in_ch3[0]["number"], 1119);
  EXPECT_TRUE(events(called.trace, "pos", "CH3").empty());  // nothing moved
  const auto in_ch1 = events(called.trace, "alarm", "CH1");
  ASSERT_EQ(in_ch1.size(), 1U);
  EXPECT_EQ(in_ch1[0]["number"], 1221);
  EXPECT_EQ(events(called.trace, "subcall_release", "CH3").at(0)["outcome"], "failed");
}

// An alarm raised while a channel runs a called program (G144 into O2000 of the program
// directory, which the check before the run does not read) names that program's file, line and
// column: in `mcnc run`'s report, in the trace and on the wire (issue 25).
TEST(MultiChannel, AnAlarmInAProgramCalledByG144NamesItsFileLineAndColumn) {
  TestMachine machine("three_channel.yaml", 226);
  const std::string dir = machine.file("programs");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/O2000.nc") << "O2000\nG00 X10\nG01 X12 Q#\nM99\n";
  const std::string caller = write_program(machine, "call.nc", "G00 X20\nG144 N3 P2000 H1\nM30\n");
  const MultiRun r = run_channels(machine, {{"CH1", caller}}, {"--progdir", dir});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto in_ch3 = events(r.trace, "alarm", "CH3");
  ASSERT_EQ(in_ch3.size(), 1U) << r.output;
  EXPECT_EQ(in_ch3[0]["number"], 3105);
  EXPECT_EQ(in_ch3[0]["prog"], "O2000.nc");
  EXPECT_EQ(in_ch3[0]["line"], 3);
  EXPECT_EQ(in_ch3[0]["col"], 10);
  EXPECT_TRUE(events(r.trace, "pos", "CH3").empty());  // nothing of it moved
  EXPECT_NE(r.output.find("alarm: CH3 3105 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(" + dir + "/O2000.nc:3:10)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("call.nc:3"), std::string::npos) << r.output;
}

// CT-CHN-01 (spec dafeng §3.6): one subprogram, CHN picks each channel's own move.
TEST(MultiChannel, OneSubprogramMovesEachChannelByItsNumber) {
  const MultiRun r = run_store(59, "tests/integration/programs/chn/",
                               {{"CH1", "O1000.nc"}, {"CH2", "O2000.nc"}, {"CH3", "O3000.nc"}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, double> last;
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {
    last.merge(end_points(r.trace, ch));
  }
  EXPECT_DOUBLE_EQ(last.at("X1"), 0.0);  // G53 X0
  EXPECT_DOUBLE_EQ(last.at("Z1"), 20.0);
  EXPECT_DOUBLE_EQ(last.at("X2"), 10.0);  // X20 diameter, untouched
  EXPECT_DOUBLE_EQ(last.at("Z2"), 0.0);   // G53 Z0
  EXPECT_DOUBLE_EQ(last.at("X3"), 5.0);   // G53 X10 (diameter)
  EXPECT_DOUBLE_EQ(last.at("Z3"), 10.0);
}

// Shared macro variables (ARCHITECTURE.md §5): a value written before a wait mark is seen by
// the partner after it; #500-#999 are kept in the machine's retained file between runs.
TEST(MultiChannel, SharedVariablesWrittenBeforeAMarkAreSeenAfterItAndRetained) {
  TestMachine machine("three_channel.yaml", 60);
  const std::string retained = machine.file("retained.txt");
  const MultiRun first = run_channels(
      machine,
      {{"CH1",
        write_program(machine, "ch1.nc", "G01 Z-5 F600\n#500=7.5\n#20000=12\nG04.1 P1 Q12\nM30\n")},
       {"CH2", write_program(machine, "ch2.nc",
                             "G04.1 P1 Q12\nG01 Z[#500] X[#20000] F600\n#501=#500+1\nM30\n")}},
      {"--retained", retained});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::map<std::string, double> end = end_points(first.trace, "CH2");
  EXPECT_DOUBLE_EQ(end.at("Z2"), 7.5);
  EXPECT_DOUBLE_EQ(end.at("X2"), 6.0);  // X12 in diameter
  std::ifstream in(retained);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "#500=7.5\n#501=8.5\n");  // #20000 is not retained

  const MultiRun second = run_channels(
      machine, {{"CH3", write_program(machine, "ch3.nc", "G01 Z[#501] X[#20000+2] F900\nM30\n")}},
      {"--retained", retained});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const std::map<std::string, double> next = end_points(second.trace, "CH3");
  EXPECT_DOUBLE_EQ(next.at("Z3"), 8.5);
  EXPECT_DOUBLE_EQ(next.at("X3"), 1.0);  // #20000 starts null again: X2 in diameter
}

// Faults (issue 7): a channel killed while its partner waits for it at a mark. The partner
// does not wait for ever, nothing moves without its owner, and the machine stops safely.
TEST(MultiChannel, AChannelKilledWhileItsPartnerWaitsStopsTheMachineSafely) {
  isolate_iceoryx_host();  // it kills a channel (start_host_roudi)
  TestMachine machine("three_channel.yaml", 61);
  const std::string trace = machine.file("trace.jsonl");
  Background run(
      {bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
       "CH1=" + write_program(machine, "ch1.nc", "G04.1 P1 Q12\nG00 X10\nM30\n"), "--program",
       "CH2=" + write_program(machine, "ch2.nc", "G01 Z-200 F300\nG04.1 P1 Q12\nM30\n")},
      -1, machine.file("run"));
  // CH1 waits at P1 while CH2 feeds Z2: kill CH2 then.
  ASSERT_NO_FATAL_FAILURE(kill_channel_during(machine, trace, "CH2", 1));  // Z2 under way
  EXPECT_NE(run.wait(120s), 0);
  const Trace t = read_trace(trace);
  // CH1 never went past its mark; it ended in an alarm or the emergency stop, not waiting.
  EXPECT_TRUE(events(t, "sync_release", "CH1").empty());
  const auto ch1_states = events(t, "state", "CH1");
  ASSERT_FALSE(ch1_states.empty());
  EXPECT_NE(ch1_states.back()["state"], "waiting");
  EXPECT_EQ(lines_of(t, "CH1"), (std::vector<int>{1}));
  // The launcher saw the child die and stopped the machine; CH2's axes stopped on their own.
  expect_stopped_after_kill(t, "CH2", {"X2", "Z2"});
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "children left running";
}

namespace {

// Random programs (issue 7 stress): CH1 and CH2 meet at marks in one global order with moves
// of random length between them, and CH1 calls programs in CH3 (H1 or H0) between its marks.
// Deadlock-free by construction: every channel meets the marks in the same order, and only CH1
// calls CH3. `mismatch_at` >= 0: CH2 names CH3 too at that mark.
struct StressPrograms {
  std::string ch1;
  std::string ch2;
  std::map<int, std::string> called;  // O number -> text
  int marks = 0;
  int calls = 0;
};

StressPrograms stress_programs(std::uint32_t seed, int mismatch_at) {
  std::mt19937 rng(seed);
  StressPrograms s;
  auto moves = [&](std::string& prog) {
    for (int k = static_cast<int>(rng() % 3); k > 0; --k) {
      prog += "G01 X" + std::to_string(rng() % 40) + " Z" +
              std::to_string(-static_cast<int>(rng() % 20)) + " F" +
              std::to_string(900 + rng() % 2000) + "\n";
    }
  };
  s.marks = 4 + static_cast<int>(rng() % 4);
  for (int m = 0; m < s.marks; ++m) {
    moves(s.ch1);
    moves(s.ch2);
    if (rng() % 2 == 0) {
      const int number = 3001 + s.calls++;
      std::string called = "O" + std::to_string(number) + "\n";
      moves(called);
      called += "G145\n";
      moves(called);
      called += "M99\n";
      s.called[number] = called;
      s.ch1 += "G144 N3 P" + std::to_string(number) + (rng() % 2 == 0 ? " H1" : " H0") + "\n";
    }
    const int p = 1 + m % 3;  // marks reused: later rounds of the same barrier
    s.ch1 += "G04.1 P" + std::to_string(p) + " Q12\n";
    s.ch2 += "G04.1 P" + std::to_string(p) + (m == mismatch_at ? " Q123\n" : " Q12\n");
  }
  s.ch1 += "M30\n";
  s.ch2 += "M30\n";
  return s;
}

MultiRun run_stress(int domain, const StressPrograms& s) {
  TestMachine machine("three_channel.yaml", domain);
  for (const auto& [number, text] : s.called) {
    write_program(machine, "O" + std::to_string(number) + ".nc", text);
  }
  return run_channels(machine,
                      {{"CH1", write_program(machine, "ch1.nc", s.ch1)},
                       {"CH2", write_program(machine, "ch2.nc", s.ch2)}},
                      {"--progdir", machine.dir()});
}

}  // namespace

TEST(MultiChannel, RandomProgramsFreeOfDeadlockByConstructionFinish) {
  for (std::uint32_t seed : {7U, 1201U, 90210U}) {
    const StressPrograms s = stress_programs(seed, -1);
    const MultiRun r = run_stress(62, s);
    ASSERT_EQ(r.exit_code, 0) << "seed " << seed << "\n" << s.ch1 << "\n" << r.output;
    const Trace& t = r.trace;
    const auto a1 = events(t, "sync_arrive", "CH1");
    const auto a2 = events(t, "sync_arrive", "CH2");
    const auto r1 = events(t, "sync_release", "CH1");
    const auto r2 = events(t, "sync_release", "CH2");
    ASSERT_EQ(a1.size(), static_cast<std::size_t>(s.marks)) << "seed " << seed;
    ASSERT_EQ(a2.size(), a1.size());
    ASSERT_EQ(r1.size(), a1.size());
    ASSERT_EQ(r2.size(), a1.size());
    for (std::size_t m = 0; m < a1.size(); ++m) {
      // The same mark and round in both, released only once both arrived.
      EXPECT_EQ(a1[m]["p"], a2[m]["p"]);
      EXPECT_EQ(a1[m]["gen"], a2[m]["gen"]);
      const std::uint64_t both =
          std::max(a1[m]["cycle"].get<std::uint64_t>(), a2[m]["cycle"].get<std::uint64_t>());
      EXPECT_GE(r1[m]["cycle"].get<std::uint64_t>(), both) << "seed " << seed << " mark " << m;
      EXPECT_GE(r2[m]["cycle"].get<std::uint64_t>(), both) << "seed " << seed << " mark " << m;
    }
    // Every call ran and released its caller.
    EXPECT_EQ(events(t, "subcall", "CH1").size(), static_cast<std::size_t>(s.calls));
    EXPECT_EQ(events(t, "subcall_release", "CH3").size(), static_cast<std::size_t>(s.calls));
    EXPECT_EQ(events(t, "end", "CH3").size(), static_cast<std::size_t>(s.calls));
    EXPECT_TRUE(events(t, "alarm").empty()) << "seed " << seed;
  }
}

TEST(MultiChannel, RandomProgramsWithAnInjectedMismatchEndInTheMismatchAlarm) {
  for (std::uint32_t seed : {11U, 4242U}) {
    const StressPrograms s = stress_programs(seed, static_cast<int>(seed % 3));
    const MultiRun r = run_stress(63, s);
    EXPECT_NE(r.exit_code, 0);
    for (const std::string ch : {"CH1", "CH2"}) {
      const auto alarms = events(r.trace, "alarm", ch);
      ASSERT_FALSE(alarms.empty()) << "seed " << seed << " " << ch << "\n" << r.output;
      EXPECT_EQ(alarms.front()["number"], 1210) << "seed " << seed << " " << ch;
    }
  }
}

// The twin-turret machine: the loader (CH3, called by G144) brings the blank, the upper turret
// turns the left end, the lower turret waits for it.
TEST(MultiChannel, TwinTurretLoaderAndTurretsInTheirOrder) {
  TestMachine machine("twin_turret.yaml", 64);
  const MultiRun r = run_channels(machine,
                                  {{"CH1", source("launch/programs/twin_turret_ch1.nc")},
                                   {"CH2", source("launch/programs/twin_turret_ch2.nc")}},
                                  {"--report", machine.file("report")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The report (docs/report.md): a lane per channel with both marks where both channels met,
  // and a toolpath per channel with its marks on it.
  const std::string timeline = slurp(machine.file("report/timeline.svg"));
  for (const std::string ch : {"CH1", "CH2"}) {
    const std::string lane = svg_group(timeline, ch);
    EXPECT_EQ(occurrences(lane, "class=\"sync\" data-p=\"1\""), 1U) << ch;
    EXPECT_EQ(occurrences(lane, "class=\"sync\" data-p=\"2\""), 1U) << ch;
    EXPECT_GT(occurrences(lane, "class=\"block\""), 5U) << ch;
    const std::string path = slurp(machine.file("report/toolpath-" + ch + ".svg"));
    EXPECT_EQ(occurrences(path, "<path class=\"toolpath\""), 1U) << ch;
    EXPECT_EQ(occurrences(path, "class=\"sync\""), 2U) << ch;
  }
  EXPECT_GE(occurrences(svg_group(timeline, "CH2"), "class=\"wait\""), 2U);  // P1 and P2
  EXPECT_EQ(occurrences(slurp(machine.file("report/toolpath-CH3.svg")), "<path class=\"toolpath\""),
            1U);  // the loader's
  const std::string page = slurp(machine.file("report/report.html"));
  EXPECT_EQ(occurrences(page, "<svg"), 4U);  // the timeline and three toolpaths
  EXPECT_NE(page.find("<td>CH1</td><td>M30</td>"), std::string::npos);
  const Trace& t = r.trace;
  EXPECT_EQ(events(t, "block", "CH3").at(0)["prog"], "O3100.nc");
  const std::uint64_t loaded = block_at(t, "CH3", 5);  // G145: the blank is in
  // The PLC opened the main chuck before the call and clamped it after the blank was in.
  EXPECT_LT(cycle_of(t, "aux_done", "PLC", {{"ch", "CH1"}, {"code", "M11"}}),
            cycle_of(t, "subcall", "CH1"));
  const std::uint64_t clamped = cycle_of(t, "aux_done", "PLC", {{"ch", "CH1"}, {"code", "M10"}});
  EXPECT_GT(clamped, loaded);
  EXPECT_GT(block_at(t, "CH1", 7), clamped);  // M03 of the main spindle after it
  EXPECT_GT(block_at(t, "CH2", 5), arrival(t, "CH1", 1));
  EXPECT_EQ(events(t, "end", "CH3").at(0)["code"], 99);
  EXPECT_EQ(r.trace.back()["channels"]["CH1"]["end"], 30);
  EXPECT_EQ(r.trace.back()["channels"]["CH2"]["end"], 30);
}

namespace {

// G140/G141/G142 (spec dafeng §3.3): the owner of `axis` over the run, from its axis node's
// `owner` events: cycle -> channel name ("" while released).
std::map<std::uint64_t, std::string> owners(const Trace& t, const std::string& axis) {
  std::map<std::uint64_t, std::string> out;
  for (const auto& e : events(t, "owner", axis)) {
    out[e["cycle"].get<std::uint64_t>()] =
        e["owner"].is_null() ? "" : e["owner"].get<std::string>();
  }
  return out;
}

std::string owner_at(const std::map<std::uint64_t, std::string>& owners, std::uint64_t cycle) {
  auto it = owners.upper_bound(cycle);
  return it == owners.begin() ? "?" : std::prev(it)->second;
}

// Every setpoint the axis node followed came from the owner of that cycle.
void expect_follows_only_its_owner(const Trace& t, const std::string& axis) {
  const auto own = owners(t, axis);
  for (const auto& f : events(t, "follow", axis)) {
    if (!f["ch"].is_null()) {
      EXPECT_EQ(f["ch"], owner_at(own, f["cycle"])) << f.dump();
    }
  }
}

// The axis node's commanded positions of `axis` in [from, to).
std::vector<double> node_positions(const Trace& t, const std::string& axis, std::uint64_t from,
                                   std::uint64_t to) {
  std::vector<double> out;
  for (const auto& p : events(t, "pos", axis)) {
    if (p["cycle"] >= from && p["cycle"] < to) {
      out.push_back(p["cmd"]);
    }
  }
  return out;
}

// The channel's commanded point of `axis` at the end of the block on `line` (its pos events
// follow the block's start events: the last block end before the next block).
double end_point(const Trace& t, const std::string& ch, int line, const std::string& axis) {
  const std::uint64_t next = block_at(t, ch, line + 1);
  double at = std::nan("");
  for (const auto& p : events(t, "pos", ch)) {
    if (p["axis"] == axis && p["cycle"] <= next) {
      at = p["cmd"];
    }
  }
  return at;
}

const std::string kG140 = "tests/integration/programs/g140/";

}  // namespace

// CT-G140-01 (spec dafeng §3.3, L5653-5699) on the twin-turret lathe: channel 1 lends its
// rotary A (exchange number 14) to channel 2 between two wait marks and both restore it.
TEST(MultiChannel, AxisExchangeAsTheSpecExample) {
  TestMachine machine("twin_turret.yaml", 65);
  const MultiRun r =
      run_channels(machine, {{"CH1", source(kG140 + "ch1.nc")}, {"CH2", source(kG140 + "ch2.nc")}},
                   {"--report", machine.file("report")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  // The report's timeline shows the release on CH1's lane, the take-over on CH2's and the
  // restore on CH1's.
  const std::string timeline = slurp(machine.file("report/timeline.svg"));
  EXPECT_EQ(occurrences(svg_group(timeline, "CH1"), "class=\"owner\" data-axis=\"A1\""), 2U);
  EXPECT_EQ(occurrences(svg_group(timeline, "CH2"), "class=\"owner\" data-axis=\"A1\""), 1U);
  // A belongs to channel 1, is released, goes to channel 2, and after G142 to channel 1 again.
  std::vector<std::string> sequence;
  for (const auto& [cycle, owner] : owners(t, "A1")) {
    sequence.push_back(owner);
  }
  EXPECT_EQ(sequence, (std::vector<std::string>{"CH1", "", "CH2", "CH1"}));
  expect_follows_only_its_owner(t, "A1");
  const auto own = owners(t, "A1");
  const std::uint64_t released = std::next(own.begin())->first;
  const std::uint64_t to_ch2 = std::next(own.begin(), 2)->first;
  const std::uint64_t back = std::next(own.begin(), 3)->first;
  EXPECT_GE(released, block_at(t, "CH1", 9));  // G140 A14
  EXPECT_GT(to_ch2, block_at(t, "CH2", 7));    // G141 A14, after the release
  EXPECT_LE(to_ch2, block_at(t, "CH2", 8));
  // A turns under channel 1 up to its release (360), stands while released, turns under
  // channel 2 (120) and comes back to channel 1; channel 2's virtual A-90 moved nothing.
  const auto under_ch1 = node_positions(t, "A1", 0, released);
  EXPECT_NEAR(*std::max_element(under_ch1.begin(), under_ch1.end()), 360.0, 1e-6);
  for (double a : node_positions(t, "A1", released, to_ch2 + 2)) {
    EXPECT_NEAR(a, 20.0, 1e-6);
  }
  const auto under_ch2 = node_positions(t, "A1", to_ch2, back);
  EXPECT_NEAR(*std::max_element(under_ch2.begin(), under_ch2.end()), 120.0, 1e-6);
  const auto all = node_positions(t, "A1", 0, ~std::uint64_t{0});
  EXPECT_GE(*std::min_element(all.begin(), all.end()), -1e-6);
  // The machine coordinate travels with the axis: 20 + 10 in channel 2, 30 + 15 in channel 1.
  EXPECT_NEAR(end_point(t, "CH2", 8, "A1"), 30.0, 1e-6);
  EXPECT_NEAR(end_points(t, "CH1").at("A1"), 45.0, 1e-6);
  EXPECT_EQ(t.back()["channels"]["CH1"]["end"], 30);
  EXPECT_EQ(t.back()["channels"]["CH2"]["end"], 30);
  EXPECT_EQ(t.back()["channels"]["CH1"]["alarms"], 0);
  EXPECT_EQ(t.back()["channels"]["CH2"]["alarms"], 0);
}

// CT-G140-01, negative: G141 before the owner's G140 waits for it; G141 P1 takes the axis at
// once, but only once the owner's motion block has ended, and the owner commanding the axis
// again is an alarm there.
TEST(MultiChannel, AnAcquireBeforeTheReleaseWaitsForIt) {
  TestMachine machine("twin_turret.yaml", 66);
  const MultiRun r = run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc", "G01 A90 F3600\nG04 X1.\nG140 A14\nM30\n")},
       {"CH2", write_program(machine, "ch2.nc", "G141 A14\nG00 A[#5003+10]\nG142\nM30\n")}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  const std::uint64_t asked = cycle_of(t, "axis_request", "CH2", {{"request", "acquire"}});
  const std::uint64_t released = cycle_of(t, "axis_request", "CH1", {{"request", "release"}});
  EXPECT_LT(asked, released);
  const auto own = owners(t, "A1");
  std::vector<std::string> sequence;
  for (const auto& [cycle, owner] : own) {
    sequence.push_back(owner);
  }
  // Released and taken in the same decision, then restored by channel 2's G142.
  EXPECT_EQ(sequence, (std::vector<std::string>{"CH1", "CH2", "CH1"}));
  EXPECT_EQ(std::next(own.begin())->first, released + 1);
  EXPECT_GT(block_at(t, "CH2", 2), released);
  expect_follows_only_its_owner(t, "A1");
  EXPECT_NEAR(end_point(t, "CH2", 2, "A1"), 100.0, 1e-6);
}

TEST(MultiChannel, AForcedAcquireWaitsForTheOwnersMoveAndTheOwnerMayNotMoveItAgain) {
  TestMachine machine("twin_turret.yaml", 67);
  const MultiRun r = run_channels(
      machine, {{"CH1", write_program(machine, "ch1.nc", "G01 A90 F3600\nG04 X1.\nG00 A0\nM30\n")},
                {"CH2", write_program(machine, "ch2.nc", "G141 A14 P1\nG00 A[#5003+10]\nM30\n")}});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  const auto own = owners(t, "A1");
  ASSERT_EQ(own.size(), 2U) << r.output;
  const auto forced = events(t, "owner", "A1").at(1);
  EXPECT_EQ(forced["owner"], "CH2");
  EXPECT_EQ(forced["forced"], true);
  // Taken at rest: after channel 1's move to 90 ended (its next block, the dwell, started).
  EXPECT_GE(forced["cycle"].get<std::uint64_t>(), block_at(t, "CH1", 2));
  expect_follows_only_its_owner(t, "A1");
  EXPECT_NEAR(end_points(t, "CH2").at("A1"), 100.0, 1e-6);
  // Channel 1's G00 A0 is an alarm, and A never went back towards 0.
  const auto alarms = events(t, "alarm", "CH1");
  ASSERT_EQ(alarms.size(), 1U);
  EXPECT_EQ(alarms[0]["number"], 1231);
  EXPECT_EQ(alarms[0]["line"], 3);
  const auto after = node_positions(t, "A1", forced["cycle"], ~std::uint64_t{0});
  EXPECT_GE(*std::min_element(after.begin(), after.end()), 90.0 - 1e-6);
  EXPECT_EQ(t.back()["channels"]["CH2"]["end"], 30);
}

// An exchange survives a reset of the machine (spec L5635-5637): after the reset and a new
// cycle start, channel 2 still owns A and goes on from where A stands.
TEST(MultiChannel, AResetDoesNotUndoAnExchange) {
  TestMachine machine("twin_turret.yaml", 68);
  const MultiRun r = run_channels(
      machine,
      {{"CH2", write_program(machine, "ch2.nc", "G141 A14 P1\nG00 A[#5003+10]\nG04 X4.\nM30\n")}},
      {"--operator", "reset@1500", "--operator", "cycle_start:CH2@1600"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  std::vector<std::string> sequence;
  for (const auto& [cycle, owner] : owners(t, "A1")) {
    sequence.push_back(owner);
  }
  EXPECT_EQ(sequence, (std::vector<std::string>{"CH1", "CH2"}));
  EXPECT_EQ(events(t, "block", "CH2").at(0)["line"], 1);
  EXPECT_NEAR(end_points(t, "CH2").at("A1"), 20.0, 1e-6);  // 10 in each run
  expect_follows_only_its_owner(t, "A1");
}

// A program called into the channel that released A (G144) does not know of the release: the
// channel itself refuses to move an axis it does not own, before anything moves.
TEST(MultiChannel, MovingAnAxisGivenAwayIsAnAlarmBeforeItMoves) {
  TestMachine machine("twin_turret.yaml", 69);
  const std::string dir = machine.file("store");
  std::filesystem::create_directory(dir);
  std::ofstream(dir + "/O3200.nc") << "O3200\nG00 X0\nG00 A5\nM99\n";
  const MultiRun r = run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc", "G140 A14\nG04.1 P1 Q12\nM30\n")},
       {"CH2", write_program(machine, "ch2.nc", "G04.1 P1 Q12\nG144 N1 P3200 H1\nM30\n")}},
      {"--progdir", dir});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  const auto alarms = events(t, "alarm", "CH1");
  ASSERT_EQ(alarms.size(), 1U) << r.output;
  EXPECT_EQ(alarms[0]["number"], 1231);
  EXPECT_EQ(alarms[0]["line"], 3);
  EXPECT_EQ(events(t, "alarm", "CH2").at(0)["number"], 1221);  // the call failed
  for (double a : node_positions(t, "A1", 0, ~std::uint64_t{0})) {
    EXPECT_NEAR(a, 0.0, 1e-9);
  }
}

// Fault: the channel that owns an exchanged axis dies while it moves it. The axis node stops
// the axis (its owner is gone), nobody else's setpoints move it, the machine stops safely.
TEST(MultiChannel, AChannelKilledWhileItOwnsAnExchangedAxisStopsIt) {
  isolate_iceoryx_host();  // it kills a channel (start_host_roudi)
  TestMachine machine("twin_turret.yaml", 70);
  const std::string trace = machine.file("trace.jsonl");
  Background run(
      {bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
       "CH1=" + write_program(machine, "ch1.nc", "G04.1 P1 Q12\nG00 A0\nM30\n"), "--program",
       "CH2=" +
           write_program(machine, "ch2.nc", "G141 A14 P1\nG01 A3600 F3600\nG04.1 P1 Q12\nM30\n")},
      -1, machine.file("run"));
  ASSERT_NO_FATAL_FAILURE(kill_channel_during(machine, trace, "CH2", 2));  // A turning
  EXPECT_NE(run.wait(120s), 0);
  const Trace t = read_trace(trace);
  const auto own = owners(t, "A1");
  EXPECT_EQ(own.rbegin()->second, "CH2");  // nobody took it over
  expect_follows_only_its_owner(t, "A1");
  const auto drive = events(t, "drive", "A1");
  ASSERT_FALSE(drive.empty());
  EXPECT_EQ(drive.back()["state"], "quick_stop_active");
  EXPECT_TRUE(events(t, "sync_release", "CH1").empty());
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "children left running";
}

// Issue 7 stress: three channels race for A 1 000 times (each takes it, turns it half a degree
// from where it stands and gives it back). Never two owners: every setpoint the node followed
// was its owner's, the channels' own views of holding A never overlap, and the half degrees
// add up, so every hand-over carried A's machine position.
TEST(MultiChannel, AThousandRacesForOneAxisNeverHaveTwoOwners) {
  // A small machine for speed (eight processes): three one-axis channels, and A1 of channel 1
  // that the two others may take; on this test's private bus.
  TestMachine machine("twin_turret.yaml", 71);
  {
    std::ifstream in(machine.path());
    std::stringstream text;
    text << in.rdbuf();
    const std::string original = text.str();
    std::smatch bus;
    ASSERT_TRUE(std::regex_search(original, bus, std::regex(R"(udp:[0-9.]+:[0-9]+)")));
    std::ofstream(machine.path())
        << "machine: {name: race, cycle_us: 2000, domain: 71}\n"
           "buses: [{name: can0, uri: \""
        << bus.str()
        << "\", sync_producer: X1}]\n"
           "channels:\n"
           "  - {name: CH1, axes: [X1, A1]}\n"
           "  - {name: CH2, axes: [X2], exchange_axes: [A1]}\n"
           "  - {name: CH3, axes: [X3], exchange_axes: [A1]}\n"
           "axes:\n"
           "  - {name: X1, address: X, bus: can0, node_id: 1}\n"
           "  - {name: A1, address: A, type: rotary, exchange: 14, bus: can0, node_id: 2,\n"
           "     counts_per_unit: 1000, rapid_rate: 7200, max_feed: 7200, acceleration: 3600,\n"
           "     in_position: 0.001, following_error_limit: 5, drive: {units_per_rev: 360}}\n"
           "  - {name: X2, address: X, bus: can0, node_id: 3}\n"
           "  - {name: X3, address: X, bus: can0, node_id: 4}\n";
  }
  const std::map<std::string, int> rounds{{"CH1", 334}, {"CH2", 333}, {"CH3", 333}};
  std::map<std::string, std::string> programs;
  for (const auto& [ch, n] : rounds) {
    programs[ch] = write_program(machine, ch + ".nc",
                                 "#1=0\n"
                                 "WHILE [#1 LT " +
                                     std::to_string(n) +
                                     "] DO1\n"
                                     "G141 A14\n"
                                     "G01 A[#5002+0.5] F7200\n"
                                     "G140 A14\n"
                                     "#1=#1+1\n"
                                     "END1\n"
                                     "M30\n");
  }
  const MultiRun r = run_channels(machine, programs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  expect_follows_only_its_owner(t, "A1");
  // Each channel holds A from the start of its move (line 4) to its release (line 5).
  std::vector<std::tuple<std::uint64_t, std::uint64_t, std::string>> held;
  for (const auto& [ch, n] : rounds) {
    std::uint64_t since = 0;
    int count = 0;
    for (const auto& b : events(t, "block", ch)) {
      if (b["line"] == 4) {
        since = b["cycle"];
        ++count;
      } else if (b["line"] == 5) {
        held.emplace_back(since, b["cycle"], ch);
      }
    }
    EXPECT_EQ(count, n) << ch;
  }
  std::sort(held.begin(), held.end());
  for (std::size_t i = 1; i < held.size(); ++i) {
    EXPECT_LT(std::get<1>(held[i - 1]), std::get<0>(held[i]))
        << std::get<2>(held[i - 1]) << " and " << std::get<2>(held[i]);
  }
  int grants = 0;
  for (const auto& e : events(t, "owner", "A1")) {
    grants += e["owner"].is_null() ? 0 : 1;
  }
  EXPECT_GE(grants, 2 * 333);  // hand-overs between different channels (a channel may win twice)
  const auto end = node_positions(t, "A1", 0, ~std::uint64_t{0});
  EXPECT_NEAR(end.back(), 500.0, 1e-6);
}

namespace {

// The twin-turret lathe with an M50 that waits for a door sensor nobody closes.
TestMachine plc_machine(int domain) {
  TestMachine machine("twin_turret.yaml", domain);
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml =
      std::regex_replace(text.str(), std::regex(R"(\nplc:\n  signals:\n)"),
                         "\nplc:\n  signals:\n    - {name: door_closed, type: input}\n");
  yaml = std::regex_replace(
      yaml, std::regex(R"(\n  m_codes:\n)"),
      "\n  m_codes:\n    - {code: 50, channels: [CH1], wait: [door_closed], timeout_ms: 200}\n");
  std::ofstream(machine.path()) << yaml;
  return machine;
}

// The run stopped with exactly one alarm in `ch`: its number, line and a part of its text.
void expect_single_alarm(const MultiRun& r, const std::string& ch, int number, int line,
                         const std::string& text_part) {
  const auto alarms = events(r.trace, "alarm", ch);
  ASSERT_EQ(alarms.size(), 1U) << r.output;
  EXPECT_EQ(alarms[0]["number"], number);
  EXPECT_EQ(alarms[0]["line"], line);
  EXPECT_NE(alarms[0]["text"].get<std::string>().find(text_part), std::string::npos)
      << alarms[0].dump();
}

}  // namespace

// mcnc-plcnode (issue 7): M codes wait for their FIN, interlocks refuse before anything
// changes, a FIN that never comes is an alarm; each refusal stops the channel at its block.
TEST(MultiChannel, ThePlcRefusesAChuckOpenWhileTheSpindleTurns) {
  TestMachine machine = plc_machine(72);
  const MultiRun r = run_channels(
      machine, {{"CH1", write_program(machine, "ch1.nc", "M03 S500\nG04 X0.5\nM11\nM30\n")}});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  expect_single_alarm(r, "CH1", 1240, 3, "turns");
  EXPECT_EQ(events(t, "aux_done", "PLC").back()["outcome"], "refused");
}

TEST(MultiChannel, ThePlcKeepsTheSpindleStillWithTheChuckOpen) {
  TestMachine machine = plc_machine(73);
  const MultiRun r =
      run_channels(machine, {{"CH1", write_program(machine, "ch1.nc", "M11\nM03 S500\nM30\n")}});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  expect_single_alarm(r, "CH1", 1240, 2, "chuck1_closed=1");
  for (const auto& s : events(t, "spindle", "CH1")) {
    EXPECT_EQ(s["rpm"], 0.0);  // never commanded to turn
  }
}

// The spec's gear (M40-M44) and tailstock (M78/M79) codes on the twin-turret lathe: each waits
// for its sensor, and neither a gear change nor a tailstock retract happens under a turning
// spindle.
TEST(MultiChannel, GearsAndTailstockWaitForTheirSensorsAndNotUnderATurningSpindle) {
  TestMachine machine("twin_turret.yaml", 81);
  const MultiRun r = run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc", "M78\nM42\nM03 S300\nG04 X0.3\nM79\nM30\n")}});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  // FIN once the sensor follows its output: 400 ms for the tailstock, 200 ms for the gear
  // (2 ms cycles).
  for (const auto& [code, ms] : {std::pair{"M78", 400}, std::pair{"M42", 200}}) {
    const std::uint64_t asked = cycle_of(t, "aux", "PLC", {{"ch", "CH1"}, {"code", code}});
    const std::uint64_t done = cycle_of(t, "aux_done", "PLC", {{"ch", "CH1"}, {"code", code}});
    EXPECT_NEAR(static_cast<double>(done - asked), ms / 2.0, 3.0) << code;
  }
  EXPECT_GT(cycle_of(t, "aux", "PLC", {{"ch", "CH1"}, {"code", "M03"}}),
            cycle_of(t, "aux_done", "PLC", {{"ch", "CH1"}, {"code", "M42"}}));
  expect_single_alarm(r, "CH1", 1240, 5, "turns");
  EXPECT_EQ(events(t, "aux_done", "PLC").back()["outcome"], "refused");
}

TEST(MultiChannel, AnMCodeWithoutFinInTimeIsAnAlarm) {
  TestMachine machine = plc_machine(74);
  const MultiRun r = run_channels(
      machine, {{"CH1", write_program(machine, "ch1.nc", "M08\nM50\nG00 X10\nM30\n")}});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  expect_single_alarm(r, "CH1", 1241, 2, "door_closed=1");
  // Taken in the cycle after it was sent, then 200 ms (100 cycles of 2 ms) without FIN.
  const std::uint64_t started = cycle_of(t, "aux", "PLC", {{"code", "M50"}});
  const std::uint64_t ended = cycle_of(t, "aux_done", "PLC", {{"code", "M50"}});
  EXPECT_EQ(ended - started, 100U);
  EXPECT_EQ(lines_of(t, "CH1"), (std::vector<int>{1, 2}));  // X never moved
}

namespace {

const std::string kG1141 = "tests/integration/programs/g1141/";

double wrap_degrees(double a) {
  a = std::fmod(a, 360.0);
  return a > 180.0 ? a - 360.0 : (a <= -180.0 ? a + 360.0 : a);
}

// The axis nodes' `pos` samples of two spindles at the same cycles in [from, to).
std::vector<std::pair<nlohmann::json, nlohmann::json>> paired_positions(const Trace& t,
                                                                        const std::string& a,
                                                                        const std::string& b,
                                                                        std::uint64_t from,
                                                                        std::uint64_t to) {
  std::map<std::uint64_t, nlohmann::json> first;
  for (const auto& p : events(t, "pos", a)) {
    first[p["cycle"]] = p;
  }
  std::vector<std::pair<nlohmann::json, nlohmann::json>> out;
  for (const auto& p : events(t, "pos", b)) {
    const std::uint64_t c = p["cycle"];
    if (c >= from && c < to && first.contains(c)) {
      out.emplace_back(first[c], p);
    }
  }
  return out;
}

}  // namespace

// CT-G1141-01 (spec dafeng §3.7, L3476-3520): the twin-spindle part transfer. The strict
// reading of the flattened listing: channel 2 clamps before P2.
TEST(MultiChannel, TwinSpindlePartTransferAsTheSpecExample) {
  TestMachine machine("twin_turret.yaml", 75);
  const MultiRun r = run_channels(
      machine, {{"CH1", source(kG1141 + "ch1.nc")}, {"CH2", source(kG1141 + "ch2.nc")}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  const std::uint64_t coupled = cycle_of(t, "couple", "S2");
  const std::uint64_t in_phase = block_at(t, "CH1", 9);  // G114.1 ended: at speed, in phase
  const std::uint64_t decoupled = cycle_of(t, "decouple", "S2");
  // 1. Channel 2 does nothing after its P1 until channel 1 has synchronised and reached P1.
  EXPECT_GT(block_at(t, "CH2", 5), arrival(t, "CH1", 1));
  EXPECT_GT(arrival(t, "CH1", 1), in_phase);
  EXPECT_GT(in_phase, coupled);
  // 2. From then on spindle 2 follows spindle 1 in phase (Q/P = 1, R = 0): commanded exactly,
  // its drive within its following error, through the approach and the chuck changes.
  const auto pairs = paired_positions(t, "S1", "S2", in_phase, decoupled);
  ASSERT_GT(pairs.size(), 100U);
  for (const auto& [s1, s2] : pairs) {
    EXPECT_NEAR(wrap_degrees(s2["cmd"].get<double>() - s1["act"].get<double>()), 0.0, 1e-3)
        << s2.dump();
    EXPECT_LT(std::fabs(wrap_degrees(s2["act"].get<double>() - s1["act"].get<double>())), 30.0);
  }
  // 3. Channel 1's M11 only after channel 2's approach and clamp (P2).
  const std::uint64_t ch2_clamped =
      cycle_of(t, "aux_done", "PLC", {{"ch", "CH2"}, {"code", "M10"}});
  const std::uint64_t ch1_opens = cycle_of(t, "aux", "PLC", {{"ch", "CH1"}, {"code", "M11"}});
  EXPECT_GT(ch1_opens, arrival(t, "CH2", 2));
  EXPECT_GT(ch1_opens, ch2_clamped);  // the part is never released by both chucks
  EXPECT_EQ(cycle_of(t, "aux_done", "PLC", {{"ch", "CH1"}, {"code", "M11"}}) > 0, true);
  // 4. G113 only after both chucks switched (P3).
  EXPECT_GT(decoupled, release(t, "CH1", 3));
  // 5. Channel 2's own M03 only after P4, hence after G113.
  EXPECT_GT(cycle_of(t, "aux", "PLC", {{"ch", "CH2"}, {"code", "M03"}}), decoupled);
  EXPECT_EQ(t.back()["channels"]["CH1"]["end"], 30);
  EXPECT_EQ(t.back()["channels"]["CH2"]["end"], 30);
}

// A reset does not end G114.1 (spec L3463), and the slave's own channel may not turn it.
TEST(MultiChannel, ASpindleSyncSurvivesAResetAndItsSlaveIsNotTheChannelsToTurn) {
  TestMachine machine("twin_turret.yaml", 76);
  const MultiRun r = run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc", "M03 S300\nG114.1 R90\nG04 X4.\nM30\n")},
       {"CH2", write_program(machine, "ch2.nc", "G04 X5.\nM03 S100\nM30\n")}},
      {"--operator", "reset:CH1@3000", "--operator", "cycle_start:CH1@3100"});
  EXPECT_NE(r.exit_code, 0);  // channel 2's M03 is an alarm
  const Trace& t = r.trace;
  EXPECT_TRUE(events(t, "decouple", "S2").empty());
  const auto couples = events(t, "couple", "S2");
  ASSERT_EQ(couples.size(), 2U) << r.output;  // the first run's, and the second run's again
  EXPECT_GT(couples[1]["cycle"].get<std::uint64_t>(), 3100U);
  EXPECT_EQ(couples[0]["r"], 90.0);
  expect_single_alarm(r, "CH2", 1250, 2, "G113");
  // Still coupled after the reset: in phase (R90) whenever channel 1's G114.1 ended.
  const auto pairs = paired_positions(t, "S1", "S2", block_at(t, "CH1", 3), 3000);
  ASSERT_GT(pairs.size(), 10U);
  for (const auto& [s1, s2] : pairs) {
    EXPECT_NEAR(wrap_degrees(s2["cmd"].get<double>() - s1["act"].get<double>() - 90.0), 0.0, 1e-3);
  }
}

// Fault: the master's channel dies while the sub-spindle follows the main spindle (G114.1).
// The main spindle's node stops it (its owner is gone), the slave follows it down and is
// stopped with the machine, the partner waiting at a mark for the dead channel raises an alarm
// instead of waiting for ever, and the machine stops.
TEST(MultiChannel, AChannelKilledWhileItsSpindleLeadsASpindleSyncStopsBothSpindles) {
  isolate_iceoryx_host();  // it kills a channel (start_host_roudi)
  TestMachine machine("twin_turret.yaml", 80);
  const std::string trace = machine.file("trace.jsonl");
  Background run(
      {bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
       "CH1=" + write_program(machine, "ch1.nc", "M03 S300\nG114.1\nG04 X30.\nG04.1 P1 Q12\nM30\n"),
       "--program", "CH2=" + write_program(machine, "ch2.nc", "G04.1 P1 Q12\nM30\n")},
      -1, machine.file("run"));
  ASSERT_NO_FATAL_FAILURE(kill_channel_during(machine, trace, "CH1", 3));  // both turn, locked
  EXPECT_NE(run.wait(120s), 0);
  const Trace t = read_trace(trace);
  ASSERT_EQ(events(t, "couple", "S2").size(), 1U);
  const std::uint64_t locked = block_at(t, "CH1", 3);
  // CH2 never passed its mark and did not stay waiting for the dead channel.
  EXPECT_TRUE(events(t, "sync_release", "CH2").empty());
  const auto ch2_states = events(t, "state", "CH2");
  ASSERT_FALSE(ch2_states.empty());
  EXPECT_NE(ch2_states.back()["state"], "waiting");
  // Both spindles end in quick stop: neither turns on without its channel.
  expect_stopped_after_kill(t, "CH1", {"S1", "S2"});
  // Until its master stopped the slave followed it in phase (within half a degree: S1 is still
  // reaching S300, and the slave follows where S1 will be at its speed of the last cycle).
  const std::uint64_t stopped = cycle_of(t, "drive", "S1", {{"state", "quick_stop_active"}});
  ASSERT_GT(stopped, locked + 10);
  // How many samples fall before the kill depends on the machine's load (the kill comes half a
  // second of wall time after the block started): at least one.
  const auto pairs = paired_positions(t, "S1", "S2", locked, stopped - 10);
  ASSERT_FALSE(pairs.empty());
  for (const auto& [s1, s2] : pairs) {
    EXPECT_NEAR(wrap_degrees(s2["cmd"].get<double>() - s1["act"].get<double>()), 0.0, 0.5);
  }
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "children left running";
}

namespace {

const std::string kG514 = "tests/integration/programs/g514/";

// The last commanded position of `axis` at or before `cycle` (the node's pos samples).
double node_position_at(const Trace& t, const std::string& axis, std::uint64_t cycle) {
  double at = std::nan("");
  for (const auto& p : events(t, "pos", axis)) {
    if (p["cycle"] <= cycle) {
      at = p["cmd"];
    }
  }
  return at;
}

// While `slave` is coupled in [from, to): it moved by what `master` moved since `from`, at every
// sample. The master's position is extrapolated from its last two, so the two differ by at most
// a cycle squared times the acceleration (1500 mm/s^2 x (2 ms)^2 = 0.006 mm on gantry_cell).
void expect_moves_with(const Trace& t, const std::string& master, const std::string& slave,
                       std::uint64_t from, std::uint64_t to) {
  const auto all = paired_positions(t, master, slave, 0, to);
  // From where both stood when the coupling began (the sample at or before it).
  std::size_t first = 0;
  while (first + 1 < all.size() && all[first + 1].first["cycle"] <= from) {
    ++first;
  }
  ASSERT_GT(all.size(), first + 10) << slave << " with " << master;
  const double m0 = all[first].first["cmd"];
  const double s0 = all[first].second["cmd"];
  double master_moved = 0.0;
  for (std::size_t i = first; i < all.size(); ++i) {
    const auto& [m, s] = all[i];
    const double dm = m["cmd"].get<double>() - m0;
    EXPECT_NEAR(s["cmd"].get<double>() - s0, dm, 0.0065) << s.dump();
    master_moved = std::max(master_moved, std::fabs(dm));
  }
  EXPECT_GT(master_moved, 1.0);  // the window saw the master move
}

}  // namespace

// CT-G514-01 (spec dafeng §3.2, example 2): Y and Z copy X's increments while synchronised, and
// are released one by one. At F1000 instead of the listing's F100: the feed changes nothing the
// example expects, and the run is ten times shorter.
TEST(MultiChannel, AxisSyncAsTheSpecExample) {
  TestMachine machine("gantry_cell.yaml", 77);
  const MultiRun r = run_channels(
      machine, {{"CH1", variant(machine, kG514 + "ct_g514_01.nc", "F100\\b", "F1000")}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  EXPECT_TRUE(events(t, "alarm").empty()) << r.output;
  const std::uint64_t y_on = cycle_of(t, "couple", "Y", {{"kind", "axis"}, {"master", "X"}});
  const std::uint64_t z_on = cycle_of(t, "couple", "Z", {{"kind", "axis"}, {"master", "X"}});
  const std::uint64_t z_off = cycle_of(t, "decouple", "Z", {{"kind", "axis"}, {"master", "X"}});
  const std::uint64_t y_off = cycle_of(t, "decouple", "Y", {{"kind", "axis"}, {"master", "X"}});
  // Each G51.4 and G50.4 ends once its axis node answered: the program waits for it.
  EXPECT_LT(y_on, block_at(t, "CH1", 5));
  EXPECT_LT(z_on, block_at(t, "CH1", 6));
  EXPECT_LT(z_off, block_at(t, "CH1", 8));
  EXPECT_LT(y_off, block_at(t, "CH1", 10));
  // G01 U10: X, Y and Z all move by X's increment.
  expect_moves_with(t, "X", "Z", z_on, z_off);
  // G01 U10 again: X and Y; Y moved with X through both moves.
  expect_moves_with(t, "X", "Y", y_on, y_off);
  for (double z : node_positions(t, "Z", z_off + 2, ~std::uint64_t{0})) {
    EXPECT_NEAR(z, 10.0, 1e-9);  // released: Z stays
  }
  // Where each ended: exactly the increments of the blocks it followed.
  const std::uint64_t end = t.back()["cycle"];
  EXPECT_NEAR(node_position_at(t, "X", end), 30.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "Y", end), 20.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "Z", end), 10.0, 1e-9);
  // The gantry's second drive followed X from power-on throughout.
  EXPECT_EQ(cycle_of(t, "couple", "X1", {{"kind", "axis"}, {"master", "X"}}), 0U);
  EXPECT_NEAR(node_position_at(t, "X1", end), 30.0, 1e-9);
  expect_moves_with(t, "X", "X1", 0, end);
}

// Example 1: a gantry from power-on (parameter 5600.3), realigned with G50.4 Q4 and G51.4 Q4
// (master from parameter 5610). Programming the slave while it follows is an alarm before
// anything moves, and a reset does not end the synchronisation.
TEST(MultiChannel, AGantrySlaveFollowsFromPowerOnAndCannotBeProgrammedWhileItFollows) {
  TestMachine machine("gantry_cell.yaml", 78);
  const MultiRun r =
      run_channels(machine, {{"CH1", source(kG514 + "gantry.nc")}},
                   {"--operator", "reset:CH1@2000", "--operator", "cycle_start:CH1@2100"});
  EXPECT_NE(r.exit_code, 0);
  const Trace& t = r.trace;
  const auto alarms = events(t, "alarm", "CH1");
  ASSERT_EQ(alarms.size(), 2U) << r.output;  // B5 in each run
  for (const auto& a : alarms) {
    EXPECT_EQ(a["number"], 1261);
    EXPECT_EQ(a["line"], 7);
    EXPECT_NE(a["text"].get<std::string>().find("G50.4 Q4"), std::string::npos) << a.dump();
  }
  const std::uint64_t first_alarm = alarms[0]["cycle"];
  ASSERT_LT(first_alarm, 2000U) << "the first run must end before the reset";
  const auto couples = events(t, "couple", "X1");
  const auto decouples = events(t, "decouple", "X1");
  ASSERT_EQ(couples.size(), 3U);  // power-on, then G51.4 Q4 in each run
  ASSERT_EQ(decouples.size(), 2U);
  // First run: X1 moved with X to 50, stood while X went to 60, then followed to 80: 70.
  expect_moves_with(t, "X", "X1", 0, decouples[0]["cycle"]);
  EXPECT_NEAR(node_position_at(t, "X1", couples[1]["cycle"]), 50.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "X", couples[1]["cycle"]), 60.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "X1", first_alarm), 70.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "X", first_alarm), 80.0, 1e-9);
  // The reset kept the coupling: the second run's G00 X50 took X1 back by 30, to 40.
  expect_moves_with(t, "X", "X1", 2100, decouples[1]["cycle"]);
  EXPECT_NEAR(node_position_at(t, "X1", decouples[1]["cycle"]), 40.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "X1", t.back()["cycle"]), 60.0, 1e-9);
}

// Master and slave in different channels: CH2's Z2 travels with CH1's X between two wait
// marks, and after G50.4 its program goes on from where X took it.
TEST(MultiChannel, AnAxisOfAnotherChannelFollowsItsMaster) {
  TestMachine machine("gantry_cell.yaml", 79);
  const MultiRun r = run_channels(
      machine, {{"CH1", write_program(machine, "ch1.nc", "G04.1 P1\nG00 X-40\nG04.1 P2\nM30\n")},
                {"CH2", write_program(machine, "ch2.nc",
                                      "G51.4 Q5\nG04.1 P1\nG04.1 P2\nG50.4 Q5\nG00 Z7\nM30\n")}});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  EXPECT_TRUE(events(t, "alarm").empty());
  const std::uint64_t on = cycle_of(t, "couple", "Z2", {{"kind", "axis"}, {"master", "X"}});
  const std::uint64_t off = cycle_of(t, "decouple", "Z2", {{"kind", "axis"}, {"master", "X"}});
  EXPECT_LT(on, arrival(t, "CH2", 1));
  expect_moves_with(t, "X", "Z2", on, off);
  EXPECT_NEAR(node_position_at(t, "Z2", off), -40.0, 1e-9);
  EXPECT_NEAR(node_position_at(t, "Z2", t.back()["cycle"]), 7.0, 1e-9);
}

// C1 mode on the twin-turret lathe: M18 takes S1 over as CH1's C once it stands, C positions it
// in its own turn's degrees through the spindle's node in CSP, M17 gives it back to speed control.
TEST(MultiChannel, TheMainSpindleIsPositionedAsCBetweenM18AndM17) {
  TestMachine machine("twin_turret.yaml", 82);
  const MultiRun r = run_channels(
      machine,
      {{"CH1", write_program(machine, "ch1.nc",
                             "M03 S300\nG04 X0.3\nM05\nM18\nG00 C90\nG01 C270 F7200\nM17\n"
                             "M03 S200\nG04 X0.6\nM05\nM30\n")}},
      {"--trace-pos-every", "10"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trace& t = r.trace;
  std::vector<std::string> modes;
  for (const auto& e : events(t, "spindle_mode", "CH1")) {
    modes.push_back(e["mode"]);
  }
  ASSERT_EQ(modes, (std::vector<std::string>{"position", "speed"}));
  std::vector<std::string> drive_modes;
  for (const auto& e : events(t, "mode", "S1")) {
    drive_modes.push_back(e["mode"]);
  }
  EXPECT_EQ(drive_modes, (std::vector<std::string>{"csp", "csv"}));
  // The spindle's node samples every 10 cycles: the last one before a block starts.
  std::map<std::uint64_t, double> angle;
  for (const auto& p : events(t, "pos", "S1")) {
    angle[p["cycle"].get<std::uint64_t>()] = p["act"].get<double>();
  }
  const auto before = [&](int line) {
    const auto it = angle.upper_bound(block_at(t, "CH1", line));
    return it == angle.begin() ? 0.0 : std::prev(it)->second;
  };
  // Position control from where it stood after M05: C = its angle within the turn.
  EXPECT_GE(cycle_of(t, "spindle_mode", "CH1", {{"mode", "position"}}), block_at(t, "CH1", 4));
  EXPECT_NEAR(wrap_degrees(before(6) - 90.0), 0.0, 0.011);
  EXPECT_NEAR(before(8) - before(6), 180.0, 0.022);
  // The channel's view at the ends of the C blocks.
  std::vector<std::pair<double, double>> c_ends;
  for (const auto& p : events(t, "pos", "CH1")) {
    if (p["axis"] == "C1") {
      c_ends.emplace_back(p["cmd"].get<double>(), p["act"].get<double>());
    }
  }
  for (const double target : {90.0, 270.0}) {
    const auto it = std::find_if(c_ends.begin(), c_ends.end(),
                                 [&](const auto& e) { return std::fabs(e.first - target) < 1e-6; });
    ASSERT_NE(it, c_ends.end()) << target;
    EXPECT_NEAR(it->second, target, 0.011);
  }
  // Back under speed control it turns again: 200 rpm, 1200 degrees per second.
  const std::uint64_t dwell = block_at(t, "CH1", 9);
  const std::uint64_t from = dwell + 150 - (dwell + 150) % 10;  // 300 cycles of 2 ms
  EXPECT_NEAR((angle.at(from + 100) - angle.at(from)) / (100 * 0.002), 1200.0, 1.2);
  EXPECT_EQ(lines_of(t, "CH1"), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
}
