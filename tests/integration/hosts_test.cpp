// A machine across hosts (issue 22). The cell of three hosts (launch/machines/cell_3ncu.yaml:
// the twin turret, its loader on a third host, Z3 a link axis) run on one host gives the twin
// turret's traces event for event, in the part transfer of launch/programs (G144 in CH3,
// G140/G141/G142 of A1, G04.1) and in CT-G1141-01 (G114.1 of S2 to S1): the file's hosts
// change where processes run, never what the machine does. And the same cell on three simulated
// hosts (tests/hosts/hostnet.py: network, mount and time namespaces, each host with its RouDi
// and a clock of its own), a launcher on each, gives that trace too.
#include "harness.hpp"

#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>
#include <iostream>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

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

  [[nodiscard]] std::vector<std::string> launcher(const std::string& host,
                                                  const std::vector<std::string>& more = {}) const {
    std::vector<std::string> argv{bin("mcnc"),
                                  "run",
                                  dir_ + "/cell_3ncu.yaml",
                                  "--program",
                                  "CH1=" + source(kCh1),
                                  "--program",
                                  "CH2=" + source(kCh2),
                                  "--trace",
                                  trace(),
                                  "--timeout",
                                  "120",
                                  "--host",
                                  host};
    argv.insert(argv.end(), more.begin(), more.end());
    return hosts_.on(host, argv);
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
  const std::string report = cell.log("report");
  const RunResult coordinator =
      run(cell.launcher("ncu1", {"--report", report}), cell.domain(), 240s);
  EXPECT_EQ(coordinator.exit_code, 0) << coordinator.out << coordinator.err;
  EXPECT_EQ(ncu2.wait(60s), 0) << slurp(cell.log("ncu2") + ".err");
  EXPECT_EQ(ncu3.wait(60s), 0) << slurp(cell.log("ncu3") + ".err");
  expect_same_trace(one_host, trace_until_end(read_trace(cell.trace())));

  // The coordinator's report is the whole machine's (docs/report.md): a lane per channel, CH3's
  // from ncu3; the turrets met at both marks; the loader's toolpath joins X3 (ncu3) and Z3
  // (ncu2); the page names each channel's end.
  const std::string timeline = slurp(report + "/timeline.svg");
  for (const std::string ch : {"CH1", "CH2"}) {
    const std::string lane = svg_group(timeline, ch);
    EXPECT_EQ(occurrences(lane, "class=\"sync\" data-p=\"1\""), 1U) << ch;
    EXPECT_EQ(occurrences(lane, "class=\"sync\" data-p=\"2\""), 1U) << ch;
  }
  EXPECT_GT(occurrences(svg_group(timeline, "CH3"), "class=\"block\""), 3U) << timeline;
  EXPECT_EQ(occurrences(slurp(report + "/toolpath-CH3.svg"), "<path class=\"toolpath\""), 1U);
  const std::string page = slurp(report + "/report.html");
  EXPECT_NE(page.find("<td>CH1</td><td>M30</td>"), std::string::npos);
  EXPECT_NE(page.find("<td>CH2</td><td>M30</td>"), std::string::npos);
  const std::string summary = slurp(report + "/summary.txt");
  EXPECT_EQ(summary.rfind("machine cell_3ncu: ok, ", 0), 0U) << summary;
  for (const std::string ch : {"CH1", "CH2", "CH3"}) {  // CH3 ends its called program, M99
    EXPECT_NE(summary.find("\n" + ch + ": ended M"), std::string::npos) << ch << "\n" << summary;
  }
}

// `--host` names a host the machine file does not have: exit 2 with the name and the file,
// before anything starts (no RouDi, no process of the machine).
TEST(Hosts, AnUnknownHostExits2AndStartsNothing) {
  const TestMachine machine("cell_3ncu.yaml", 119);
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source(CellOnThreeHosts::kCh1), "--host", "ncu9"},
                          machine.domain(), 60s);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--host ncu9: " + machine.path() + " names no such host"), std::string::npos)
      << r.err;
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "nothing may be started";
}

namespace {

// hostnet.py's verbs (cut, loss, heal) on the hosts of `prefix`, or of the cell.
RunResult hostnet(const std::string& prefix, const std::vector<std::string>& verb) {
  std::vector<std::string> argv{source("tests/hosts/hostnet.py"), verb.front(), "--prefix", prefix};
  argv.insert(argv.end(), verb.begin() + 1, verb.end());
  return run(argv, -1, 30s);
}
RunResult hostnet(const CellOnThreeHosts& cell, const std::vector<std::string>& verb) {
  return hostnet("mhc" + std::to_string(cell.domain()), verb);
}

// The processes running on a simulated host (in its mount namespace), but the keeper that holds
// its namespaces (hostnet.py's) and this probe: pid and command line. Empty, and a failure, when
// the probe is not inside the host: a host's list is what a test may kill.
std::map<pid_t, std::string> processes_on(const SimulatedHosts& hosts, const std::string& host) {
  const RunResult r =
      run(hosts.on(host, {"/bin/sh", "-c",
                          "[ \"$(readlink /proc/$$/ns/mnt)\" != "
                          "\"$(readlink /proc/1/ns/mnt)\" ] || exit 3; "
                          "echo $PPID; exec /usr/bin/pgrep -a --nslist mnt --ns $$"}),
          -1, 30s);
  std::map<pid_t, std::string> found;
  if (r.exit_code != 0 && r.exit_code != 1) {  // pgrep: 1 when nothing matched
    ADD_FAILURE() << "no process list of " << host << ": " << r.err;
    return found;
  }
  std::istringstream lines(r.out);
  std::string probe;  // nsenter, the probe's parent inside the host
  std::getline(lines, probe);
  for (std::string line; std::getline(lines, line);) {
    const std::size_t space = line.find(' ');
    if (space != std::string::npos && line.substr(0, space) != probe &&
        line.find("hostnet.py") == std::string::npos) {
      found[std::stoi(line.substr(0, space))] = line.substr(space + 1);
    }
  }
  return found;
}

// Every host of `hosts` runs no process of the machine any more (within `timeout`: a drive
// simulator outlives its launcher until its bus is quiet).
void expect_nothing_runs_on(const SimulatedHosts& hosts, const std::vector<std::string>& names,
                            std::chrono::seconds timeout) {
  for (const std::string& host : names) {
    std::map<pid_t, std::string> left;
    EXPECT_TRUE(eventually(
        [&] {
          left = processes_on(hosts, host);
          return left.empty();
        },
        timeout))
        << host << " still runs " << left.begin()->second;
  }
}

// What a partition leaves: both sides E-stopped, every launcher ended, every drive at rest at
// the end. `cut` is the host cut off from the two others.
void expect_partition_stops_both_sides(const CellOnThreeHosts& cell, const std::string& cut,
                                       Background& ncu1, Background& ncu2, Background& ncu3) {
  std::map<std::string, Background*> launchers{{"ncu1", &ncu1}, {"ncu2", &ncu2}, {"ncu3", &ncu3}};
  for (const auto& [host, launcher] : launchers) {
    EXPECT_EQ(launcher->wait(120s), 1) << host << " E-stopped its side\n"
                                       << slurp(cell.log(host) + ".err");
  }
  const std::string coordinator = slurp(cell.log("ncu1") + ".err");
  if (cut == "ncu1") {
    for (const std::string host : {"ncu2", "ncu3"}) {
      EXPECT_NE(slurp(cell.log(host) + ".err").find("the coordinator on host ncu1 is gone"),
                std::string::npos)
          << host;
    }
    EXPECT_NE(coordinator.find("its launcher is gone"), std::string::npos) << coordinator;
  } else {
    EXPECT_NE(coordinator.find("host " + cut + ": its launcher is gone"), std::string::npos)
        << coordinator;
    EXPECT_NE(slurp(cell.log(cut) + ".err").find("the coordinator on host ncu1 is gone"),
              std::string::npos)
        << slurp(cell.log(cut) + ".err");
  }
  // Only the link was cut: no drive failed. The lockstep machine, paced after its E-stop
  // without real-time scheduling, judges its drives silent only after half a second (decision
  // 127); before, a drive simulator starved at the E-stop gave 2004 and 2006 in half the runs.
  // The cut link axis (Z3) is left out: its node waits for its lost owner until the owner's DDS
  // lease runs out (about 300 ms here, enough for a 2004 before the change), and that wait is
  // DDS's timing, not this machine's.
  const std::regex drive_alarm(R"(alarm: (\S+) (2004|2006) )");
  for (const std::string host : {"ncu1", "ncu2", "ncu3"}) {
    const std::string out = slurp(cell.log(host) + ".out");
    for (auto it = std::sregex_iterator(out.begin(), out.end(), drive_alarm);
         it != std::sregex_iterator(); ++it) {
      EXPECT_EQ((*it)[1], "Z3") << host << ": " << it->str() << "\n" << out;
    }
  }
}

// A link axis whose channel is lost (its host down or cut off) quick-stops: no setpoint within
// the deadline (2001) or its owner's writer gone (2002), whichever comes first.
void expect_link_axis_quick_stopped(const std::vector<nlohmann::json>& trace,
                                    const std::string& axis) {
  bool stopped = false;
  for (const nlohmann::json& e : events(trace, "alarm", axis)) {
    stopped = stopped || e["number"] == 2002 || e["number"] == 2001;
  }
  EXPECT_TRUE(stopped) << axis << " quick-stopped: its owner is lost";
}

// After the link is back nothing moves again (decision 48: both sides ended their run, and only
// a new run starts the machine): healed, and given the time a run takes to start, no process of
// the machine runs on any host and the trace has not one event more.
void expect_nothing_moves_after_heal(const CellOnThreeHosts& cell,
                                     const std::vector<nlohmann::json>& trace) {
  ASSERT_EQ(hostnet(cell, {"heal"}).exit_code, 0);
  std::this_thread::sleep_for(5s);
  expect_nothing_runs_on(cell.hosts(), {"ncu1", "ncu2", "ncu3"}, 15s);
  EXPECT_EQ(read_trace(cell.trace()), trace) << "nothing was written after the heal";
}

// Every axis named stands still at the end of its part of the trace: its last two positions
// (K cycles apart) are the same. The merge happens on the coordinator's side, so only its
// side's parts are surely complete.
void expect_axes_at_rest_at_the_end(const std::vector<nlohmann::json>& trace,
                                    const std::vector<std::string>& axes) {
  for (const std::string& axis : axes) {
    const std::vector<nlohmann::json> pos = events(trace, "pos", axis);
    ASSERT_GE(pos.size(), 2U) << axis;
    const double last = pos.back()["act"].get<double>();
    const double before = pos[pos.size() - 2]["act"].get<double>();
    EXPECT_NEAR(last, before, 1e-4) << axis << " still moved at cycle " << pos.back()["cycle"];
  }
}

}  // namespace

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

// A host that goes down during the run: every process on ncu3 (its launcher, RouDi, CH3, X3 and
// X3's drive) killed at once. The coordinator notices ncu3's launcher gone when its DDS lease
// runs out and E-stops the rest, naming the host; Z3, on ncu2 and commanded by CH3, quick-stops
// when its owner is lost. The axes of ncu1 and ncu2 stand still at the end, and no process of
// the machine is left on any host.
TEST(Hosts, AHostThatGoesDownDuringTheRunEStopsTheRest) {
  const CellOnThreeHosts cell(167);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
  std::map<pid_t, std::string> on_ncu3 = processes_on(cell.hosts(), "ncu3");
  const auto runs = [&](const std::string& what) {
    return std::any_of(on_ncu3.begin(), on_ncu3.end(),
                       [&](const auto& p) { return p.second.find(what) != std::string::npos; });
  };
  ASSERT_TRUE(runs("--host ncu3") && runs("mcnc-channel") && runs("mcnc-axisnode") &&
              runs("mcnc-drivesim") && runs("iox-roudi"))
      << "ncu3 runs a launcher, a channel, an axis node, a drive and a RouDi: "
      << testing::PrintToString(on_ncu3);
  // A process started between a listing and the kill (a RouDi check) goes in the next round.
  for (int round = 0; round < 5 && !on_ncu3.empty(); ++round) {
    for (const auto& [pid, command] : on_ncu3) {
      ::kill(pid, SIGKILL);
    }
    on_ncu3 = processes_on(cell.hosts(), "ncu3");
  }
  ASSERT_TRUE(on_ncu3.empty()) << on_ncu3.begin()->second;
  EXPECT_EQ(ncu3.wait(30s), -SIGKILL);
  EXPECT_EQ(ncu1.wait(120s), 1) << "the coordinator E-stopped the run";
  const std::string out = slurp(cell.log("ncu1") + ".out") + slurp(cell.log("ncu1") + ".err");
  EXPECT_NE(out.find("host ncu3: its launcher is gone"), std::string::npos) << out;
  EXPECT_GE(ncu2.wait(120s), 0) << "ncu2's launcher ends with the run";

  const std::vector<nlohmann::json> trace = read_trace(cell.trace());
  bool named = false;
  for (const nlohmann::json& e : events(trace, "alarm", "launch")) {
    named = named || (e["number"] == 3001 &&
                      e["text"].get<std::string>().find("host ncu3") != std::string::npos);
  }
  EXPECT_TRUE(named) << "the E-stop's alarm names the host";
  expect_link_axis_quick_stopped(trace, "Z3");
  expect_axes_at_rest_at_the_end(trace, {"X1", "Z1", "A1", "S1", "X2", "Z2", "S2", "Z3"});
  expect_nothing_runs_on(cell.hosts(), {"ncu1", "ncu2", "ncu3"}, 15s);
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

// One machine clock: ncu2's CLOCK_MONOTONIC runs 3 ms ahead of ncu1's and ncu3's 7 ms behind
// (their time namespaces). Each follower's launcher measures its offset against the
// coordinator's clock, and in realtime every host's cycle N is due at the same machine time.
// From the trace: each host's estimate, and each axis node's due times taken back to ncu1's
// clock with the true offsets. Without the machine clock the due times would differ by the
// offsets themselves (3 and 7 ms); the bound here is 1 ms, the figure is in bench/README.md.
TEST(Hosts, RealtimeCyclesAreDueAtOneMachineTimeOnHostsWhoseClocksDiffer) {
  const CellOnThreeHosts cell(169);
  const std::vector<std::string> realtime{"--clock", "realtime"};
  Background ncu2(cell.launcher("ncu2", realtime), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3", realtime), cell.domain(), cell.log("ncu3"));
  const RunResult coordinator = run(cell.launcher("ncu1", realtime), cell.domain(), 240s);
  ncu2.wait(60s);
  ncu3.wait(60s);
  ASSERT_NE(coordinator.err.find("starting the run"), std::string::npos)
      << coordinator.out << coordinator.err;
  // Whether the part transfer keeps up in realtime depends on this host's load, and is not
  // what is tested here: the due times are, for as long as the run went on.
  const std::vector<nlohmann::json> trace = read_trace(cell.trace());

  const std::map<std::string, std::int64_t> true_offset{
      {"ncu1", 0}, {"ncu2", 3'000'000}, {"ncu3", -7'000'000}};
  std::map<std::string, std::int64_t> estimated;
  for (const nlohmann::json& e : events(trace, "clock", "launch")) {
    estimated[e["host"]] = e["offset_ns"].get<std::int64_t>();
    EXPECT_LE(std::llabs(e["offset_ns"].get<std::int64_t>() - true_offset.at(e["host"])),
              e["error_ns"].get<std::int64_t>() + 200'000)
        << e.dump();
  }
  ASSERT_EQ(estimated.size(), 3U) << "every host's clock is in the trace";

  // The axis nodes' hosts, as the machine file says.
  const mcnc::config::MachineConfig machine =
      mcnc::config::load_machine_file(source("launch/machines/cell_3ncu.yaml"));
  using Range = std::pair<std::int64_t, std::int64_t>;
  std::map<std::uint64_t, Range> due_range;       // by cycle
  std::map<std::uint64_t, Range> sync_due_range;  // by the cycle a SYNC belongs to
  std::map<std::uint64_t, int> sync_hosts;        // how many hosts' SYNCs of that cycle
  const auto widen = [](std::map<std::uint64_t, Range>& ranges, std::uint64_t cycle,
                        std::int64_t t) {
    auto [it, fresh] = ranges.try_emplace(cycle, t, t);
    it->second.first = std::min(it->second.first, t);
    it->second.second = std::max(it->second.second, t);
  };
  std::set<std::string> hosts_seen;
  std::set<std::string> sync_producers_seen;
  std::size_t ticks = 0;
  for (const nlohmann::json& e : trace) {
    if (e["ev"] != "tick") {
      continue;
    }
    const std::string axis = e["axis"].get<std::string>();
    const mcnc::config::HostConfig* on = machine.host_of(axis);
    ASSERT_NE(on, nullptr) << e.dump();
    const std::string host = on->name;
    // The launcher refines its estimate during the run; the node follows it.
    EXPECT_LE(std::llabs(e["offset_ns"].get<std::int64_t>() - true_offset.at(host)), 500'000)
        << e.dump();
    widen(due_range, e["cycle"].get<std::uint64_t>(),
          e["due_ns"].get<std::int64_t>() - true_offset.at(host));
    hosts_seen.insert(host);
    ++ticks;
    // A bus's SYNC producer: its SYNCs are due at one machine time on every host too, each
    // at its bus's offset inside the cycle (decision 128).
    const mcnc::config::AxisConfig* a = machine.find_axis(axis);
    const mcnc::config::BusConfig* bus = a == nullptr ? nullptr : machine.find_bus(a->bus);
    const bool producer = bus != nullptr && bus->sync_producer == axis;
    EXPECT_TRUE(producer || !e.contains("sync_cycle"))
        << "only a SYNC producer sends SYNC " << e.dump();
    if (producer && e.contains("sync_cycle")) {
      sync_producers_seen.insert(axis);
      ++sync_hosts[e["sync_cycle"].get<std::uint64_t>()];
      widen(sync_due_range, e["sync_cycle"].get<std::uint64_t>(),
            e["sync_due_ns"].get<std::int64_t>() - std::int64_t{bus->sync_offset_us} * 1000 -
                true_offset.at(host));
    }
  }
  EXPECT_EQ(hosts_seen.size(), 3U);
  EXPECT_EQ(sync_producers_seen.size(), 3U) << "one SYNC producer per host's bus";
  ASSERT_GT(ticks, 100U);
  EXPECT_GT(std::count_if(sync_hosts.begin(), sync_hosts.end(),
                          [](const auto& c) { return c.second == 3; }),
            100)
      << "cycles whose SYNC is in the trace from every host";
  for (const auto* ranges : {&due_range, &sync_due_range}) {
    std::size_t misaligned = 0;
    for (const auto& [cycle, range] : *ranges) {
      if (range.second - range.first > 1'000'000 && ++misaligned <= 5) {
        ADD_FAILURE() << "cycle " << cycle << ": " << (ranges == &due_range ? "due" : "SYNC due")
                      << " times " << (range.second - range.first) / 1000 << " us apart";
      }
    }
    EXPECT_EQ(misaligned, 0U);
  }
}

namespace {

// The small lathe on two hosts, at the link's cycle (2 ms): its bus, drives and axis nodes on
// ncu1, which coordinates, and its channel on ncu2, so that X1 and Z1 are both link axes. The
// machine file, trace and logs in a directory of the build tree, which the hosts share.
class LatheOnTwoHosts {
 public:
  LatheOnTwoHosts(int domain, int deadline_cycles)
      : domain_(domain),
        machine_("small_lathe.yaml", domain, deadline_cycles),
        dir_(std::string(MCNC_BINARY_DIR) + "/hosts-test-" + std::to_string(domain)),
        hosts_(prefix(), "ncu1,ncu2", "ncu2=5", "10.77." + std::to_string(domain)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::string text = slurp(machine_.path());
    const std::size_t cycle = text.find("cycle_us: 1000");
    if (cycle == std::string::npos) {
      throw std::runtime_error("small_lathe.yaml has no cycle_us: 1000");
    }
    text.replace(cycle, std::string("cycle_us: 1000").size(), "cycle_us: 2000");
    std::ofstream(dir_ + "/lathe_2ncu.yaml") << text
                                             << "\nhosts:\n"
                                                "  - {name: ncu1, runs: [X1, Z1, can0]}\n"
                                                "  - {name: ncu2, runs: [CH1]}\n";
  }
  ~LatheOnTwoHosts() { std::filesystem::remove_all(dir_); }
  LatheOnTwoHosts(const LatheOnTwoHosts&) = delete;
  LatheOnTwoHosts& operator=(const LatheOnTwoHosts&) = delete;

  // The host's launcher, in realtime, with a pos and a tick event every cycle.
  [[nodiscard]] std::vector<std::string> launcher(const std::string& host,
                                                  const std::string& program) const {
    return hosts_.on(host, {bin("mcnc"), "run", dir_ + "/lathe_2ncu.yaml", "--program",
                            "CH1=" + source(program), "--trace", trace(), "--trace-pos-every", "1",
                            "--clock", "realtime", "--timeout", "120", "--host", host});
  }
  [[nodiscard]] std::string prefix() const { return "mhl" + std::to_string(domain_); }
  [[nodiscard]] std::string trace() const { return dir_ + "/trace.jsonl"; }
  [[nodiscard]] std::string log(const std::string& host) const { return dir_ + "/" + host; }
  [[nodiscard]] int domain() const { return domain_; }

 private:
  int domain_;
  TestMachine machine_;
  std::string dir_;
  SimulatedHosts hosts_;
};

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The first cycle of `axis` due at or after `ns` on its host's clock (its tick events), or the
// cycle after its last tick.
std::uint64_t cycle_due_at(const std::vector<nlohmann::json>& trace, const std::string& axis,
                           std::int64_t ns) {
  std::uint64_t last = 0;
  for (const nlohmann::json& e : events(trace, "tick", axis)) {
    last = e["cycle"].get<std::uint64_t>();
    if (e["due_ns"].get<std::int64_t>() >= ns) {
      return last;
    }
  }
  return last + 1;
}

}  // namespace

// A partition in realtime: ncu2, the lathe's channel's host, cut off during a long cut in Z
// (launch/programs/long_feed.nc, 5 mm/s). Each link axis on ncu1 quick-stops (2001) within
// deadline_cycles of the last setpoint it received, and that setpoint came before the cut was
// complete (no setpoint crossed it); neither stopped before the cut began. The cycles are the
// axis nodes' own, from the trace: the cut's start and end taken to cycles by the nodes' due
// times (ncu1's clock is this one's), Z1's last setpoint from its commanded positions (a missing
// setpoint is bridged by braking, so the last full step of 0.01 mm is the last setpoint). A run
// whose host did not keep up in realtime before the cut (a timing alarm) is run again, up to
// three times.
TEST(Hosts, RealtimeLinkAxesCutOffFromTheirChannelQuickStopWithinTheDeadline) {
  constexpr int kDeadline = 50;  // 100 ms: this 2-core host stalls processes for tens of ms
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const LatheOnTwoHosts lathe(204, kDeadline);
    const std::string program = "launch/programs/long_feed.nc";
    Background ncu2(lathe.launcher("ncu2", program), lathe.domain(), lathe.log("ncu2"));
    Background ncu1(lathe.launcher("ncu1", program), lathe.domain(), lathe.log("ncu1"));
    ASSERT_TRUE(eventually([&] { return last_cmd(lathe.trace() + ".parts/Z1.jsonl", "Z1") < -2.0; },
                           120s, 200ms))
        << slurp(lathe.log("ncu1") + ".err");
    const std::int64_t cut_begins = monotonic_ns();
    ASSERT_EQ(hostnet(lathe.prefix(), {"cut", "ncu2"}).exit_code, 0);
    const std::int64_t cut_ends = monotonic_ns();
    EXPECT_EQ(ncu1.wait(120s), 1) << slurp(lathe.log("ncu1") + ".err");
    EXPECT_EQ(ncu2.wait(120s), 1) << slurp(lathe.log("ncu2") + ".err");
    const std::vector<nlohmann::json> trace = read_trace(lathe.trace());
    const std::uint64_t first = cycle_due_at(trace, "Z1", cut_begins);
    const std::uint64_t complete = cycle_due_at(trace, "Z1", cut_ends);
    std::vector<nlohmann::json> early;
    for (const nlohmann::json& e : events(trace, "alarm")) {
      if (e["cycle"].get<std::uint64_t>() < first) {
        early.push_back(e);
      }
    }
    if (!early.empty() && attempt < 3) {
      std::cout << "realtime attempt " << attempt << " stopped before the cut: " << early[0].dump()
                << "\n";
      continue;
    }
    EXPECT_TRUE(early.empty()) << early[0].dump();
    std::cout << "cut from cycle " << first << " to " << complete << "\n";

    std::map<std::string, std::uint64_t> stopped;  // the axis's 2001, by cycle
    for (const std::string axis : {"X1", "Z1"}) {
      for (const nlohmann::json& e : events(trace, "alarm", axis)) {
        if (e["number"] == 2001 && stopped.count(axis) == 0) {
          stopped[axis] = e["cycle"].get<std::uint64_t>();
        }
      }
      ASSERT_EQ(stopped.count(axis), 1U) << axis << " quick-stopped for want of setpoints";
      EXPECT_GE(stopped[axis], first) << axis;
      EXPECT_LE(stopped[axis], complete + kDeadline) << axis;
    }
    std::map<std::uint64_t, double> z1;  // cmd by cycle
    for (const nlohmann::json& e : events(trace, "pos", "Z1")) {
      z1[e["cycle"].get<std::uint64_t>()] = e["cmd"].get<double>();
    }
    std::uint64_t last_setpoint = 0;
    for (const auto& [cycle, cmd] : z1) {
      const auto before = z1.find(cycle - 1);
      if (cycle < stopped["Z1"] && before != z1.end() && before->second - cmd > 0.0099) {
        last_setpoint = cycle;
      }
    }
    std::cout << "Z1: last setpoint at cycle " << last_setpoint << ", quick stop at cycle "
              << stopped["Z1"] << "\n";
    EXPECT_GE(last_setpoint + kDeadline, first) << "Z1 had setpoints until the cut";
    EXPECT_LE(last_setpoint, complete) << "no setpoint crossed the cut";
    EXPECT_LE(stopped["Z1"] - last_setpoint, static_cast<std::uint64_t>(kDeadline));
    // CH1, on the other side, finds its axes' feedback older than the deadline: its axis is
    // lost (1202), long before DDS's lease says the nodes are gone (3 s).
    const std::vector<nlohmann::json> lost = events(trace, "alarm", "CH1");
    ASSERT_FALSE(lost.empty()) << "CH1 alarms";
    EXPECT_EQ(lost[0]["number"], 1202) << lost[0].dump();
    EXPECT_LE(lost[0]["cycle"].get<std::uint64_t>(), complete + 2 * kDeadline) << lost[0].dump();
    // The E-stop keeps the run's cycles: none of the stop's events is stamped beyond the 60 s
    // the stop may take.
    for (const nlohmann::json& e : trace) {
      ASSERT_LE(e["cycle"].get<std::uint64_t>(), complete + 30'000) << e.dump();
    }
    expect_axes_at_rest_at_the_end(trace, {"X1", "Z1"});
    return;
  }
}

// 1 % loss on the link in realtime, from before the launchers start: a lost setpoint or feedback
// sample is repaired within the writers' 20 ms heartbeat, well inside the deadline (decision
// 48), and the lathe runs xz_move.nc to its end without an alarm, both launchers ending clean
// and its last block ending at the program's point (X60 Z10: X1 at a radius of 30). Runs again
// when it ends in timing alarms only (the host's stalls, as run_realtime), up to three times.
TEST(Hosts, RealtimeLinkAxesRunOnUnderOnePercentLoss) {
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const LatheOnTwoHosts lathe(205, 50);
    ASSERT_EQ(hostnet(lathe.prefix(), {"loss", "1"}).exit_code, 0);
    const std::string program = "launch/programs/xz_move.nc";
    Background ncu2(lathe.launcher("ncu2", program), lathe.domain(), lathe.log("ncu2"));
    Background ncu1(lathe.launcher("ncu1", program), lathe.domain(), lathe.log("ncu1"));
    const int coordinator = ncu1.wait(180s);
    const int follower = ncu2.wait(60s);
    const std::vector<nlohmann::json> trace = read_trace(lathe.trace());
    const std::vector<nlohmann::json> alarms = events(trace, "alarm");
    const bool timing_only =
        !alarms.empty() && std::all_of(alarms.begin(), alarms.end(), [](const nlohmann::json& e) {
          const int n = e["number"].get<int>();
          return n == 2001 || n == 2006 || n == 2009 || n == 1201 || n == 1202 || n == 3001;
        });
    if (timing_only && attempt < 3) {
      std::cout << "realtime attempt " << attempt << " ended in timing alarms: " << alarms[0].dump()
                << "\n";
      continue;
    }
    EXPECT_EQ(coordinator, 0) << slurp(lathe.log("ncu1") + ".err");
    EXPECT_EQ(follower, 0) << slurp(lathe.log("ncu2") + ".err");
    for (const nlohmann::json& e : alarms) {
      ADD_FAILURE() << e.dump();
    }
    ASSERT_EQ(events(trace, "end", "CH1").size(), 1U);
    const std::map<std::string, double> end_point{{"X1", 30.0}, {"Z1", 10.0}};
    for (const auto& [axis, at] : end_point) {
      const std::vector<nlohmann::json> ends = events(trace, "pos", "CH1");
      const auto last = std::find_if(ends.rbegin(), ends.rend(),
                                     [&](const nlohmann::json& e) { return e["axis"] == axis; });
      ASSERT_NE(last, ends.rend()) << axis;
      EXPECT_NEAR((*last)["cmd"].get<double>(), at, 1e-6) << axis;
      EXPECT_NEAR((*last)["act"].get<double>(), at, 0.0005) << axis;
    }
    return;
  }
}

// A partition during motion, cut on the loader's side: ncu3 (CH3, X3) no longer hears ncu1 and
// ncu2. On ncu1's side the coordinator E-stops when ncu3's launcher's lease runs out; Z3, the
// link axis whose node is on ncu2 and whose channel is on ncu3, quick-stops when its owner is
// lost. On ncu3's side its launcher E-stops its own processes when the coordinator's lease
// runs out. Nothing moves after the stop: every axis stands where the stop left it.
TEST(Hosts, APartitionDuringMotionStopsTheMachineOnBothSidesOfTheCut) {
  const CellOnThreeHosts cell(170);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
  ASSERT_EQ(hostnet(cell, {"cut", "ncu3"}).exit_code, 0);
  expect_partition_stops_both_sides(cell, "ncu3", ncu1, ncu2, ncu3);
  // CH3, cut off from Z3's node on ncu2, says so before its launcher stops it (1202).
  const std::string ncu3_out = slurp(cell.log("ncu3") + ".out");
  EXPECT_NE(ncu3_out.find("alarm: CH3 1202 axis node lost"), std::string::npos) << ncu3_out;
  const std::vector<nlohmann::json> trace = read_trace(cell.trace());
  expect_link_axis_quick_stopped(trace, "Z3");
  expect_axes_at_rest_at_the_end(trace, {"X1", "Z1", "A1", "S1", "X2", "Z2", "S2", "Z3"});
  expect_nothing_moves_after_heal(cell, trace);
}

// The same cut on the coordinator's side: ncu1 alone. ncu2's and ncu3's launchers each E-stop
// their own host's processes when the coordinator's lease runs out.
TEST(Hosts, APartitionThatCutsOffTheCoordinatorStopsEveryHost) {
  const CellOnThreeHosts cell(171);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
  ASSERT_EQ(hostnet(cell, {"cut", "ncu1"}).exit_code, 0);
  expect_partition_stops_both_sides(cell, "ncu1", ncu1, ncu2, ncu3);
  const std::vector<nlohmann::json> trace = read_trace(cell.trace());
  expect_axes_at_rest_at_the_end(trace, {"X1", "Z1", "A1", "S1"});
  expect_nothing_moves_after_heal(cell, trace);
}

// Loss on every link between the hosts (`percent` of the packets each host receives from the
// others, iptables' statistic match) from before the launchers start, for `lasting` of the run
// or to its end (0 s): the machine starts and runs on in lockstep, only slower (a lost sample
// waits for its repair), and its trace is the one-host trace, event for event.
namespace {

void expect_loss_in_lockstep_only_slows(int one_host_domain, int domain, const std::string& percent,
                                        std::chrono::seconds lasting) {
  const auto one_host = run_programs("cell_3ncu.yaml", one_host_domain, CellOnThreeHosts::kCh1,
                                     CellOnThreeHosts::kCh2);
  const CellOnThreeHosts cell(domain);
  ASSERT_EQ(hostnet(cell, {"loss", percent}).exit_code, 0);
  Background ncu2(cell.launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  Background ncu1(cell.launcher("ncu1"), cell.domain(), cell.log("ncu1"));
  if (lasting > 0s) {
    ASSERT_TRUE(cell.run_under_way()) << slurp(cell.log("ncu1") + ".err");
    std::this_thread::sleep_for(lasting - 2s);  // two of it went by in run_under_way
    ASSERT_EQ(hostnet(cell, {"heal"}).exit_code, 0);
  }
  EXPECT_EQ(ncu1.wait(240s), 0) << slurp(cell.log("ncu1") + ".out")
                                << slurp(cell.log("ncu1") + ".err");
  EXPECT_EQ(ncu2.wait(60s), 0) << slurp(cell.log("ncu2") + ".err");
  EXPECT_EQ(ncu3.wait(60s), 0) << slurp(cell.log("ncu3") + ".err");
  expect_same_trace(one_host, trace_until_end(read_trace(cell.trace())));
}

}  // namespace

// 10 % loss until 8 s into the run. A process that waits for its inputs announces its latest
// samples again (decision 98): without that, a status sample lost just before its writer
// waited stayed lost with Cyclone DDS in about one run of six.
TEST(Hosts, TenPercentLossInLockstepOnlySlowsTheMachine) {
  expect_loss_in_lockstep_only_slows(172, 173, "10", 8s);
}

// 1 % loss for the whole run, start-up and stop included.
TEST(Hosts, OnePercentLossInLockstepOnlySlowsTheMachine) {
  expect_loss_in_lockstep_only_slows(198, 203, "1", 0s);
}

// 10 % loss in realtime: setpoints that do not come within `deadline_cycles` quick-stop their
// axes (alarm 2001), or the run goes on; either way no axis ever moves where the program does
// not take it. Every axis node's commanded positions stay inside what the same programs
// command in lockstep on one host, and no step between two of them is faster than the axis's
// rapid rate. Whether the run ends or stops depends on the host's load, and is not asserted.
TEST(Hosts, UnderTenPercentLossInRealtimeNoAxisMovesWhereTheProgramDoesNotTakeIt) {
  const auto reference =
      run_programs("cell_3ncu.yaml", 174, CellOnThreeHosts::kCh1, CellOnThreeHosts::kCh2);
  const CellOnThreeHosts cell(175);
  ASSERT_EQ(hostnet(cell, {"loss", "10"}).exit_code, 0);
  const std::vector<std::string> realtime{"--clock", "realtime"};
  Background ncu2(cell.launcher("ncu2", realtime), cell.domain(), cell.log("ncu2"));
  Background ncu3(cell.launcher("ncu3", realtime), cell.domain(), cell.log("ncu3"));
  const RunResult coordinator = run(cell.launcher("ncu1", realtime), cell.domain(), 300s);
  ncu2.wait(60s);
  ncu3.wait(60s);
  ASSERT_NE(coordinator.err.find("starting the run"), std::string::npos)
      << coordinator.out << coordinator.err;
  const std::vector<nlohmann::json> trace = read_trace(cell.trace());

  // Rapid rates (launch/machines/cell_3ncu.yaml), in units per cycle of 2 ms; a pos line every
  // 10 cycles. Spindles turn by their speed, not along the path: not checked.
  const std::map<std::string, double> rapid_per_min{{"X1", 8000}, {"Z1", 8000}, {"A1", 7200},
                                                    {"X2", 8000}, {"Z2", 8000}, {"X3", 12000},
                                                    {"Z3", 12000}};
  std::size_t checked = 0;
  for (const auto& [axis, rapid] : rapid_per_min) {
    double low = 1e300;
    double high = -1e300;
    for (const nlohmann::json& e : events(reference, "pos", axis)) {
      low = std::min(low, e["cmd"].get<double>());
      high = std::max(high, e["cmd"].get<double>());
    }
    // X1 and X2 are diameter axes: their positions are diameters, twice the radial move.
    const double scale = axis == "X1" || axis == "X2" ? 2.0 : 1.0;
    const double max_step = scale * rapid / 60.0 * 0.002 * 10 * 1.05 + 1e-6;
    std::optional<nlohmann::json> previous;
    for (const nlohmann::json& e : events(trace, "pos", axis)) {
      const double cmd = e["cmd"].get<double>();
      EXPECT_GE(cmd, low - 1e-6) << e.dump();
      EXPECT_LE(cmd, high + 1e-6) << e.dump();
      if (previous) {
        const double cycles = e["cycle"].get<double>() - (*previous)["cycle"].get<double>();
        EXPECT_LE(std::fabs(cmd - (*previous)["cmd"].get<double>()),
                  max_step * std::max(1.0, cycles / 10))
            << axis << " jumped: " << previous->dump() << " then " << e.dump();
      }
      previous = e;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100U);
}

// The cell on two hosts: the lower turret and the loader together on ncu2, so that CH3's X3
// and its link axis Z3 are both there. CT-G1141-01 (S2 on ncu2 follows S1 on ncu1, G114.1
// across hosts) gives the one-host trace, event for event.
TEST(Hosts, TheCellOnTwoHostsCouplesTheSpindlesAcrossThemAsOnOneHost) {
  const std::string g1141 = "tests/integration/programs/g1141/";
  const auto one_host = run_programs("cell_3ncu.yaml", 176, g1141 + "ch1.nc", g1141 + "ch2.nc");
  const int domain = 177;
  const TestMachine machine("cell_3ncu.yaml", domain);
  const std::string dir = std::string(MCNC_BINARY_DIR) + "/hosts-test-" + std::to_string(domain);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string text = slurp(machine.path());
  const std::size_t hosts_at = text.find("\nhosts:");
  ASSERT_NE(hosts_at, std::string::npos);
  text = text.substr(0, hosts_at) +
         "\nhosts:\n"
         "  - {name: ncu1, runs: [CH1, X1, Z1, A1, S1, can0, plc, hmi]}\n"
         "  - {name: ncu2, runs: [CH2, X2, Z2, S2, Z3, can1, CH3, X3, can2]}\n";
  std::ofstream(dir + "/cell_2ncu.yaml") << text;
  {
    const SimulatedHosts hosts("mhc" + std::to_string(domain), "ncu1,ncu2", "ncu2=-4",
                               "10.77." + std::to_string(domain));
    const auto launcher = [&](const std::string& host) {
      return hosts.on(
          host, {bin("mcnc"), "run", dir + "/cell_2ncu.yaml", "--program",
                 "CH1=" + source(g1141 + "ch1.nc"), "--program", "CH2=" + source(g1141 + "ch2.nc"),
                 "--trace", dir + "/trace.jsonl", "--timeout", "120", "--host", host});
    };
    Background ncu2(launcher("ncu2"), domain, dir + "/ncu2");
    const RunResult coordinator = run(launcher("ncu1"), domain, 240s);
    EXPECT_EQ(coordinator.exit_code, 0) << coordinator.out << coordinator.err;
    EXPECT_EQ(ncu2.wait(60s), 0) << slurp(dir + "/ncu2.err");
  }
  const auto two_hosts = trace_until_end(read_trace(dir + "/trace.jsonl"));
  std::filesystem::remove_all(dir);
  expect_same_trace(one_host, two_hosts);
  EXPECT_EQ(count(two_hosts, "couple", "slave", "S2"), 1U) << "S2 on ncu2 follows S1 on ncu1";
}

// Launchers as services: each host's `mcnc-launch … --host NAME --serve` stays up between
// runs, and `mcnc run … --services` on any host (ncu2 here, not the coordinator's) brings the
// whole machine up, runs it and stops it, twice on the same services: each run's trace is the
// one-host trace, and the asker ends with the coordinator's exit code and summary.
TEST(Hosts, LauncherServicesRunTheMachineForAnAskerOnAnyHost) {
  const auto one_host =
      run_programs("cell_3ncu.yaml", 178, CellOnThreeHosts::kCh1, CellOnThreeHosts::kCh2);
  const CellOnThreeHosts cell(179);
  const std::string machine = std::string(MCNC_BINARY_DIR) + "/hosts-test-179/cell_3ncu.yaml";
  std::map<std::string, std::unique_ptr<Background>> services;
  for (const std::string host : {"ncu1", "ncu2", "ncu3"}) {
    services[host] = std::make_unique<Background>(
        cell.hosts().on(host, {bin("mcnc-launch"), machine, "--host", host, "--serve"}),
        cell.domain(), cell.log("service-" + host));
  }
  for (int run_no = 1; run_no <= 2; ++run_no) {
    std::filesystem::remove(cell.trace());
    const RunResult asker =
        run(cell.hosts().on("ncu2", {bin("mcnc"), "run", machine, "--program",
                                     "CH1=" + source(CellOnThreeHosts::kCh1), "--program",
                                     "CH2=" + source(CellOnThreeHosts::kCh2), "--trace",
                                     cell.trace(), "--timeout", "120", "--services"}),
            cell.domain(), 300s);
    EXPECT_EQ(asker.exit_code, 0) << "run " << run_no << "\n" << asker.out << asker.err;
    EXPECT_NE(asker.out.find("CH1: program end M30"), std::string::npos)
        << "the coordinator's summary, run " << run_no << "\n"
        << asker.out;
    expect_same_trace(one_host, trace_until_end(read_trace(cell.trace())));
  }
  for (auto& [host, service] : services) {
    service->kill(SIGTERM);
    EXPECT_EQ(service->wait(30s), 0) << host << "\n" << slurp(cell.log("service-" + host) + ".err");
  }
}

// An asker whose machine has a host without a service names it, and nothing runs.
TEST(Hosts, AnAskerNamesTheHostsWithoutAService) {
  const CellOnThreeHosts cell(180);
  const std::string machine = std::string(MCNC_BINARY_DIR) + "/hosts-test-180/cell_3ncu.yaml";
  Background ncu1(
      cell.hosts().on("ncu1", {bin("mcnc-launch"), machine, "--host", "ncu1", "--serve"}),
      cell.domain(), cell.log("service-ncu1"));
  const RunResult asker =
      run(cell.hosts().on("ncu1", {bin("mcnc"), "run", machine, "--program",
                                   "CH1=" + source(CellOnThreeHosts::kCh1), "--services"}),
          cell.domain(), 200s);
  EXPECT_EQ(asker.exit_code, 1) << asker.out << asker.err;
  EXPECT_NE(asker.err.find("no launcher service ready on host ncu2, ncu3"), std::string::npos)
      << asker.err;
  ncu1.kill(SIGTERM);
  EXPECT_EQ(ncu1.wait(30s), 0);
  EXPECT_EQ(slurp(cell.log("service-ncu1") + ".err").find("asked"), std::string::npos)
      << "no run was asked of the service";
}

// Hosts that share no directory: each launcher's --trace is in its host's own /tmp (private
// to each simulated host). The followers send their parts to the coordinator, whose merged
// trace is the one-host trace.
TEST(Hosts, TheTraceIsWholeWhenTheHostsShareNoDirectory) {
  const auto one_host =
      run_programs("cell_3ncu.yaml", 181, CellOnThreeHosts::kCh1, CellOnThreeHosts::kCh2);
  const CellOnThreeHosts cell(182);
  const std::string machine = std::string(MCNC_BINARY_DIR) + "/hosts-test-182/cell_3ncu.yaml";
  const std::string trace = "/tmp/mcnc-cell-trace.jsonl";  // one per host
  const auto launcher = [&](const std::string& host) {
    return cell.hosts().on(
        host, {bin("mcnc"), "run", machine, "--program", "CH1=" + source(CellOnThreeHosts::kCh1),
               "--program", "CH2=" + source(CellOnThreeHosts::kCh2), "--trace", trace, "--timeout",
               "120", "--host", host});
  };
  Background ncu2(launcher("ncu2"), cell.domain(), cell.log("ncu2"));
  Background ncu3(launcher("ncu3"), cell.domain(), cell.log("ncu3"));
  const RunResult coordinator = run(launcher("ncu1"), cell.domain(), 240s);
  EXPECT_EQ(coordinator.exit_code, 0) << coordinator.out << coordinator.err;
  EXPECT_EQ(ncu2.wait(60s), 0) << slurp(cell.log("ncu2") + ".err");
  EXPECT_EQ(ncu3.wait(60s), 0) << slurp(cell.log("ncu3") + ".err");
  const std::string merged = cell.log("merged.jsonl");
  ASSERT_EQ(
      run(cell.hosts().on("ncu1", {"/bin/sh", "-c", "cat " + trace + " > " + merged}), -1, 30s)
          .exit_code,
      0);
  expect_same_trace(one_host, trace_until_end(read_trace(merged)));
}
