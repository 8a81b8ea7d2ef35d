#pragma once
// Multi-process test harness: a private machine file per test (own DDS domain, own CAN
// multicast group and port), running executables with captured output, reading traces.
#include <nlohmann/json.hpp>

#include <sys/types.h>
#include "../support/eventually.hpp"
#include "common/config/machine_config.hpp"

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace mcnc::test {

std::string bin(const std::string& name);         // path of an mcnc executable
std::string source(const std::string& relative);  // path in the source tree

// A copy of a machine file from launch/machines/ with its domain and bus URIs made private to
// this test (domain `domain`, group 239.255.<domain>.1, port 24000 + domain: below the
// ephemeral port range, where DDS sockets may hold any port), in a temp folder; a relative
// program_dir still names the directory beside the original file.
class TestMachine {
 public:
  // deadline_cycles > 0 replaces the file's (realtime tests run with looser timing: this VM
  // can stall a process for a few milliseconds under load).
  TestMachine(const std::string& machine_file, int domain, int deadline_cycles = 0);
  [[nodiscard]] int deadline_cycles() const { return deadline_cycles_; }
  ~TestMachine();
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& dir() const { return dir_; }
  [[nodiscard]] int domain() const { return domain_; }
  [[nodiscard]] std::string file(const std::string& name) const { return dir_ + "/" + name; }

 private:
  std::string dir_;
  std::string path_;
  int domain_;
  int deadline_cycles_ = 0;
  std::shared_ptr<void> domain_hold_;  // this process's share of the domain's lock
};

struct RunResult {
  int exit_code = -1;  // -signal when killed
  std::string out;
  std::string err;
};

// Runs argv to its end (killed after `timeout`), with MCNC_DOMAIN set when domain >= 0.
RunResult run(const std::vector<std::string>& argv, int domain, std::chrono::seconds timeout);

// A realtime run depends on the host giving its processes the CPU in time: a stall of the
// virtual machine longer than the machine's deadlines ends it in a timing alarm, as it must
// (2001 setpoint deadline, 2006 heartbeat, 2009 following error, and the channel's 1201/1202
// that follow). Runs argv up to `attempts` times while it ends in those alarms only, saying so
// on the test's output; any other result is returned at once.
RunResult run_realtime(const std::vector<std::string>& argv, std::chrono::seconds timeout,
                       int attempts = 3);

// A process started in the background, its output going to files in `log_dir`.
class Background {
 public:
  Background(const std::vector<std::string>& argv, int domain, const std::string& log_path);
  ~Background();  // SIGKILL if still running
  // Waits for it to exit; the exit code, -signal, or nullopt-like -1000 on timeout.
  int wait(std::chrono::seconds timeout);
  void kill(int sig);
  [[nodiscard]] pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
};

// The whole content of a file ("" when it cannot be read).
std::string slurp(const std::string& path);
// How many times `what` occurs in `text`.
std::size_t occurrences(const std::string& text, const std::string& what);
// The run report timeline's lane of channel `ch` (docs/report.md): its <g data-channel> group.
std::string svg_group(const std::string& svg, const std::string& ch);

// Inserts `text` into the machine file of `machine` after the first occurrence of `after` (whole
// lines, with their newlines). False, and the file unchanged, when `after` is not there.
bool insert_in_machine_file(const TestMachine& machine, const std::string& after,
                            const std::string& text);

// Every JSON line of a trace file (or trace part).
std::vector<nlohmann::json> read_trace(const std::string& path);
std::vector<nlohmann::json> events(const std::vector<nlohmann::json>& trace, const std::string& ev,
                                   const std::string& src = {});
// An axis's `cmd` or `act` per cycle, from its node's pos events.
std::map<std::uint64_t, double> axis_positions(const std::vector<nlohmann::json>& trace,
                                               const std::string& axis, const char* which);
// The cycle each line's block started in, from a channel's block events (the first per line).
std::map<int, std::uint64_t> block_starts(const std::vector<nlohmann::json>& trace,
                                          const std::string& channel = "CH1");

// A lockstep trace up to its program end, and its summary without the stop's cycle: what two
// runs of one machine and programs must have alike. Events after the last channel's end depend
// on how long the stop took and are left out.
std::vector<nlohmann::json> trace_until_end(const std::vector<nlohmann::json>& trace);

// Runs `program` (source tree path) on CH1 of `machine` with `mcnc run` and a trace, expects a
// clean end (exit 0); the trace.
std::vector<nlohmann::json> run_to_clean_end(const TestMachine& machine, const std::string& program,
                                             const std::vector<std::string>& extra = {});

// The last `cmd` of an axis's pos events in a trace (or trace part), or nan when it has none.
double last_cmd(const std::string& trace_path, const std::string& axis);

// Gives this test process, and every process it starts after, a host of its own as iceoryx sees
// it: a mount namespace where /dev/shm is empty and /tmp shows what the host's does, except
// iceoryx's socket and lock files. A RouDi started there is the only one its processes reach,
// and the host's RouDi (the suite's, shared by the tests in parallel) never sees them, so the
// test may kill it. A test machine made after the call lies in the private /tmp. Throws
// std::runtime_error (which fails the test) when the namespace cannot be made (it needs root).
void isolate_iceoryx_host();

// A RouDi of the test's own host (after isolate_iceoryx_host), as mcnc-launch starts one: at
// SCHED_FIFO launch::kRoudiPriority with the suite's configuration, its output in `log_path`.
// Returns once it registers a process (mcnc-roudi-check); fails the test when it does not within 20
// s. A test that kills a process on Cyclone DDS runs on such a host: iceoryx 2.0's RouDi can hang
// for good cleaning up after a process killed with SIGKILL, and the suite's RouDi serves every
// test after it.
std::unique_ptr<Background> start_host_roudi(const std::string& log_path);

// The machine file of `machine` with `machine.middleware: machine_wide`, and with `channels` as
// each channel's own middleware when not empty.
void use_middleware(const TestMachine& machine, const std::string& machine_wide,
                    const std::string& channels = "");

// Controller hosts simulated on this machine (tests/hosts/hostnet.py): each a network, mount
// and time namespace, on a bridge of their own. Made by the constructor (which fails the test
// when it cannot), removed with everything still running in them by the destructor.
class SimulatedHosts {
 public:
  // `prefix`: at most 8 letters and digits, unique to the test; `offsets_ms`: "a=3,b=-7";
  // `subnet`: the first three bytes of the hosts' addresses ("10.77.5").
  SimulatedHosts(std::string prefix, const std::string& hosts, const std::string& offsets_ms,
                 const std::string& subnet);
  ~SimulatedHosts();
  SimulatedHosts(const SimulatedHosts&) = delete;
  SimulatedHosts& operator=(const SimulatedHosts&) = delete;
  // argv run inside `host`.
  [[nodiscard]] std::vector<std::string> on(const std::string& host,
                                            const std::vector<std::string>& argv) const;

 private:
  std::string prefix_;
};

// `mcnc run` of a machine file of launch/machines/ on this host, with `programs` (channel ->
// source tree path); expects a clean end and returns the trace up to it.
std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::map<std::string, std::string>& programs);
std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::string& ch1, const std::string& ch2);

// What one simulated host runs: its name and its `runs:` ("CH1, X1, can0").
struct HostPart {
  std::string name;
  std::string runs;
};

// A run of a machine file of launch/machines/ with `hosts` as its `hosts:` section, across
// simulated hosts (the second's clock 3 ms ahead, the third's 7 ms behind), a launcher on each,
// the first coordinating. Expects every launcher to end cleanly and every host's clock in the
// trace: the run really spanned them.
struct HostsRun {
  std::vector<nlohmann::json> trace;    // merged, up to its end
  mcnc::config::MachineConfig machine;  // the file as run: where each process was
  [[nodiscard]] std::string host_of(const std::string& process) const;
};
// `secured`: each host with its address in the file and the machine secured by `mcnc certs`;
// `without_multicast`: the hosts drop every multicast datagram from the others.
struct HostsRunOptions {
  bool secured = false;
  bool without_multicast = false;
};
HostsRun run_across_hosts(const std::string& machine_file, int domain,
                          const std::vector<HostPart>& hosts,
                          const std::map<std::string, std::string>& programs,
                          HostsRunOptions options = {});

// Two lockstep traces of the same machine and programs, one of them across hosts, are equal
// event for event (the hosts' clocks, only in a run across hosts, left out).
void expect_same_trace(const std::vector<nlohmann::json>& one_host,
                       std::vector<nlohmann::json> across);

// Events `ev` whose `key` is `value`, after cycle 0.
std::size_t count(const std::vector<nlohmann::json>& trace, const std::string& ev,
                  const std::string& key, const std::string& value);

// pids of processes whose command line contains `needle`.
std::vector<pid_t> pids_with_arg(const std::string& needle);

}  // namespace mcnc::test
