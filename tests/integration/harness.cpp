#include "harness.hpp"

#include "common/process/shm_cleanup.hpp"
#include "launch/host_roudi.hpp"
#include "roudi/iceoryx_tmp.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

extern char** environ;

namespace mcnc::test {

namespace fs = std::filesystem;

std::string bin(const std::string& name) {
  return std::string(MCNC_BIN_DIR) + "/" + name;
}
std::string source(const std::string& relative) {
  return std::string(MCNC_SOURCE_DIR) + "/" + relative;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

std::string svg_group(const std::string& svg, const std::string& ch) {
  const auto from = svg.find("<g data-channel=\"" + ch + "\">");
  if (from == std::string::npos) {
    return "";
  }
  return svg.substr(from, svg.find("\n</g>", from) - from);
}

bool insert_in_machine_file(const TestMachine& machine, const std::string& after,
                            const std::string& text) {
  std::string yaml = slurp(machine.path());
  const std::size_t at = yaml.find(after);
  if (at == std::string::npos) {
    return false;
  }
  yaml.insert(at + after.size(), text);
  std::ofstream(machine.path()) << yaml;
  return true;
}

namespace {

pid_t spawn(const std::vector<std::string>& argv, int domain, const std::string& out_path,
            const std::string& err_path) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::string(*e).rfind("MCNC_DOMAIN=", 0) != 0) {
      env_strings.emplace_back(*e);
    }
  }
  if (domain >= 0) {
    env_strings.push_back("MCNC_DOMAIN=" + std::to_string(domain));
  }
  std::vector<char*> env;
  for (auto& s : env_strings) {
    env.push_back(s.data());
  }
  env.push_back(nullptr);
  std::vector<std::string> args_copy = argv;
  std::vector<char*> args;
  for (auto& a : args_copy) {
    args.push_back(a.data());
  }
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error("cannot start " + argv[0]);
  }
  return pid;
}

int decode_status(int status) {
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status);
  }
  return WIFSIGNALED(status) ? -WTERMSIG(status) : -1;
}

// Two tests on one domain and its buses would read each other's samples and frames, and both
// fail in ways that say nothing of the cause (CI at 673a86c: two PolygonTurning tests on 117 side
// by side). So a machine holds an exclusive lock on its domain, across processes, for as long as
// it lives: a reused domain makes the second test wait, never mix. Machines of one process on one
// domain share the hold (a lock taken twice by one process would wait for itself).
std::shared_ptr<void> hold_domain(int domain) {
  static std::mutex mutex;
  static std::map<int, std::weak_ptr<void>> held;
  const std::lock_guard lock(mutex);
  if (auto hold = held[domain].lock()) {
    return hold;
  }
  const std::string path = "/tmp/mcnc-domain-" + std::to_string(domain) + ".lock";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  }
  while (::flock(fd, LOCK_EX) != 0) {
    if (errno != EINTR) {
      ::close(fd);
      throw std::runtime_error("cannot lock " + path + ": " + std::strerror(errno));
    }
  }
  std::shared_ptr<void> hold(new int(fd), [](void* p) {
    auto* f = static_cast<int*>(p);
    ::close(*f);  // closing the only descriptor releases the lock
    delete f;
  });
  held[domain] = hold;
  return hold;
}

}  // namespace

TestMachine::TestMachine(const std::string& machine_file, int domain, int deadline_cycles)
    : domain_(domain), domain_hold_(hold_domain(domain)) {
  char tmpl[] = "/tmp/mcnc-test-XXXXXX";
  dir_ = mkdtemp(tmpl);
  std::string text = slurp(source("launch/machines/" + machine_file));
  // Private buses: group and port derived from the domain, the k-th bus in group .k.
  {
    const std::regex uri(R"(udp:[0-9.]+:[0-9]+)");
    std::string out;
    std::smatch m;
    int k = 0;
    while (std::regex_search(text, m, uri)) {
      out += m.prefix().str() + "udp:239.255." + std::to_string(domain) + "." +
             std::to_string(k + 1) + ":" + std::to_string(24000 + domain + 300 * k);
      ++k;
      text = m.suffix().str();
    }
    text = out + text;
  }
  text = std::regex_replace(text, std::regex(R"(\n  domain: *[0-9]+)"), "");
  text = std::regex_replace(text, std::regex(R"(machine:\n)"),
                            "machine:\n  domain: " + std::to_string(domain) + "\n");
  if (deadline_cycles > 0) {
    text = std::regex_replace(text, std::regex(R"(deadline_cycles: *[0-9]+)"),
                              "deadline_cycles: " + std::to_string(deadline_cycles));
  }
  // A program directory relative to the machine file stays the one beside the original.
  std::smatch dir;
  if (std::regex_search(text, dir, std::regex(R"(program_dir: *([^/\n][^\n]*))"))) {
    const fs::path original = fs::path(source("launch/machines")) / dir[1].str();
    text = dir.prefix().str() + "program_dir: " + original.lexically_normal().string() +
           dir.suffix().str();
  }
  std::smatch found;
  if (std::regex_search(text, found, std::regex(R"(deadline_cycles: *([0-9]+))"))) {
    deadline_cycles_ = std::stoi(found[1]);
  }
  path_ = dir_ + "/" + machine_file;
  std::ofstream(path_) << text;
}

TestMachine::~TestMachine() {
  std::error_code ec;
  if (std::getenv("MCNC_KEEP_TEST_DIRS") == nullptr) {
    fs::remove_all(dir_, ec);
  }
  process::remove_stale_dds_shm_files();
}

SimulatedHosts::SimulatedHosts(std::string prefix, const std::string& hosts,
                               const std::string& offsets_ms, const std::string& subnet)
    : prefix_(std::move(prefix)) {
  const RunResult r =
      run({"/usr/bin/env", "python3", source("tests/hosts/hostnet.py"), "up", "--prefix", prefix_,
           "--hosts", hosts, "--offset-ms", offsets_ms, "--subnet", subnet},
          -1, std::chrono::seconds(60));
  if (r.exit_code != 0) {
    (void)run(
        {"/usr/bin/env", "python3", source("tests/hosts/hostnet.py"), "down", "--prefix", prefix_},
        -1, std::chrono::seconds(60));
    throw std::runtime_error("simulated hosts " + hosts + " could not be made: " + r.err);
  }
}

SimulatedHosts::~SimulatedHosts() {
  (void)run(
      {"/usr/bin/env", "python3", source("tests/hosts/hostnet.py"), "down", "--prefix", prefix_},
      -1, std::chrono::seconds(60));
}

std::vector<std::string> SimulatedHosts::on(const std::string& host,
                                            const std::vector<std::string>& argv) const {
  std::vector<std::string> out{"/usr/bin/env", "python3",  source("tests/hosts/hostnet.py"),
                               "exec",         "--prefix", prefix_,
                               host,           "--"};
  out.insert(out.end(), argv.begin(), argv.end());
  return out;
}

RunResult run(const std::vector<std::string>& argv, int domain, std::chrono::seconds timeout) {
  char tmpl[] = "/tmp/mcnc-run-XXXXXX";
  const std::string dir = mkdtemp(tmpl);
  const pid_t pid = spawn(argv, domain, dir + "/out", dir + "/err");
  RunResult result;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      result.exit_code = decode_status(status);
      break;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGINT);
      std::this_thread::sleep_for(std::chrono::seconds(5));
      ::kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      result.exit_code = -1000;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  result.out = slurp(dir + "/out");
  result.err = slurp(dir + "/err");
  fs::remove_all(dir);
  return result;
}

namespace {

// True when the run failed and every alarm `mcnc run` printed ("alarm: SRC NUMBER text") is one
// a stalled host causes.
bool ended_in_timing_alarms(const RunResult& r) {
  static const std::regex line(R"(^alarm: \S+ (\d+) )");
  bool any = false;
  std::istringstream in(r.out);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (!std::regex_search(l, m, line)) {
      continue;
    }
    const int number = std::stoi(m[1]);
    if (number != 2001 && number != 2006 && number != 2009 && number != 1201 && number != 1202) {
      return false;
    }
    any = true;
  }
  return r.exit_code != 0 && any;
}

}  // namespace

RunResult run_realtime(const std::vector<std::string>& argv, std::chrono::seconds timeout,
                       int attempts) {
  RunResult r;
  for (int attempt = 1; attempt <= attempts; ++attempt) {
    r = run(argv, -1, timeout);
    if (!ended_in_timing_alarms(r) || attempt == attempts) {
      break;
    }
    std::cout << "realtime attempt " << attempt << " ended in timing alarms, run again:\n" << r.out;
  }
  return r;
}

Background::Background(const std::vector<std::string>& argv, int domain,
                       const std::string& log_path)
    : pid_(spawn(argv, domain, log_path + ".out", log_path + ".err")) {}

Background::~Background() {
  if (!reaped_) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

int Background::wait(std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      reaped_ = true;
      return decode_status(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return -1000;
}

void Background::kill(int sig) {
  ::kill(pid_, sig);
}

std::vector<nlohmann::json> read_trace(const std::string& path) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  std::size_t number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty()) {
      continue;
    }
    try {
      lines.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " + e.what() + ": " + line);
    }
  }
  return lines;
}

double last_cmd(const std::string& trace_path, const std::string& axis) {
  double cmd = std::nan("");
  for (const auto& e : events(read_trace(trace_path), "pos")) {
    if (e["axis"] == axis) {
      cmd = e["cmd"];
    }
  }
  return cmd;
}

std::vector<nlohmann::json> events(const std::vector<nlohmann::json>& trace, const std::string& ev,
                                   const std::string& src) {
  std::vector<nlohmann::json> found;
  for (const auto& e : trace) {
    if (e.value("ev", "") == ev && (src.empty() || e.value("src", "") == src)) {
      found.push_back(e);
    }
  }
  return found;
}

std::map<std::uint64_t, double> axis_positions(const std::vector<nlohmann::json>& trace,
                                               const std::string& axis, const char* which) {
  std::map<std::uint64_t, double> at;
  for (const auto& p : events(trace, "pos", axis)) {
    at[p["cycle"].get<std::uint64_t>()] = p[which].get<double>();
  }
  return at;
}

std::map<int, std::uint64_t> block_starts(const std::vector<nlohmann::json>& trace,
                                          const std::string& channel) {
  std::map<int, std::uint64_t> at;
  for (const auto& b : events(trace, "block", channel)) {
    at.emplace(b["line"].get<int>(), b["cycle"].get<std::uint64_t>());
  }
  return at;
}

void isolate_iceoryx_host() {
  const auto fail = [](const std::string& what) {
    throw std::runtime_error("isolate_iceoryx_host: " + what);
  };
  if (::unshare(CLONE_NEWNS) != 0 ||
      ::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) {
    fail(std::string("mount namespace: ") + std::strerror(errno));
  }
  if (::mount("tmpfs", "/dev/shm", "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777") != 0) {
    fail(std::string("tmpfs on /dev/shm: ") + std::strerror(errno));
  }
  if (const std::string why = cover_iceoryx_files("/tmp"); !why.empty()) {
    fail(why);
  }
}

std::unique_ptr<Background> start_host_roudi(const std::string& log_path) {
  auto roudi = std::make_unique<Background>(
      std::vector<std::string>{"/usr/bin/chrt", "-f", std::to_string(mcnc::launch::kRoudiPriority),
                               "/usr/bin/iox-roudi", "-c", source("tests/roudi/roudi_config.toml"),
                               "-l", "warning"},
      -1, log_path);
  EXPECT_TRUE(eventually(
      [] { return run({bin("mcnc-roudi-check")}, -1, std::chrono::seconds(10)).exit_code == 0; },
      std::chrono::seconds(20)))
      << slurp(log_path + ".out") << slurp(log_path + ".err");
  return roudi;
}

void use_middleware(const TestMachine& machine, const std::string& machine_wide,
                    const std::string& channels) {
  std::string yaml = std::regex_replace(slurp(machine.path()), std::regex("\nmachine:\n"),
                                        "\nmachine:\n  middleware: " + machine_wide + "\n");
  if (!channels.empty()) {
    yaml = std::regex_replace(yaml, std::regex("\n  - name: (CH[0-9]+)\n"),
                              "\n  - name: $1\n    middleware: " + channels + "\n");
  }
  std::ofstream(machine.path()) << yaml;
}

std::vector<pid_t> pids_with_arg(const std::string& needle) {
  std::vector<pid_t> pids;
  for (const auto& proc : fs::directory_iterator("/proc")) {
    const std::string name = proc.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    std::string cmdline = slurp(proc.path().string() + "/cmdline");
    for (auto& c : cmdline) {
      c = c == '\0' ? ' ' : c;
    }
    if (cmdline.find(needle) != std::string::npos) {
      pids.push_back(static_cast<pid_t>(std::stoi(name)));
    }
  }
  return pids;
}

std::vector<nlohmann::json> run_to_clean_end(const TestMachine& machine, const std::string& program,
                                             const std::vector<std::string>& extra) {
  const std::string trace_file = machine.file("trace.jsonl");
  std::vector<std::string> argv{
      bin("mcnc"), "run",     machine.path(), "--program", "CH1=" + source(program),
      "--trace",   trace_file};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const RunResult r = run(argv, -1, std::chrono::seconds(300));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return read_trace(trace_file);
}

std::vector<nlohmann::json> trace_until_end(const std::vector<nlohmann::json>& trace) {
  std::uint64_t end_cycle = 0;
  for (const auto& e : events(trace, "end")) {
    end_cycle = std::max(end_cycle, e["cycle"].get<std::uint64_t>());
  }
  std::vector<nlohmann::json> kept;
  for (const auto& e : trace) {
    if (e["ev"] == "summary") {
      nlohmann::json summary = e;
      summary.erase("cycle");  // stamped when the stop finished: after the end
      kept.push_back(summary);
    } else if (e["cycle"].get<std::uint64_t>() <= end_cycle) {
      kept.push_back(e);
    }
  }
  return kept;
}

std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::map<std::string, std::string>& programs) {
  TestMachine machine(machine_file, domain);
  const std::string trace = machine.file("trace.jsonl");
  std::vector<std::string> argv{bin("mcnc"), "run", machine.path(), "--trace", trace};
  for (const auto& [channel, program] : programs) {
    argv.insert(argv.end(), {"--program", channel + "=" + source(program)});
  }
  const RunResult r = run(argv, -1, std::chrono::seconds(300));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return trace_until_end(read_trace(trace));
}

std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::string& ch1, const std::string& ch2) {
  return run_programs(machine_file, domain, {{"CH1", ch1}, {"CH2", ch2}});
}

std::string HostsRun::host_of(const std::string& process) const {
  const mcnc::config::HostConfig* host = machine.host_of(process);
  return host == nullptr ? "" : host->name;
}

HostsRun run_across_hosts(const std::string& machine_file, int domain,
                          const std::vector<HostPart>& hosts,
                          const std::map<std::string, std::string>& programs,
                          HostsRunOptions options) {
  const TestMachine machine(machine_file, domain);
  // In the build tree: the hosts share it, each has a /tmp of its own.
  const std::string dir = std::string(MCNC_BINARY_DIR) + "/hosts-run-" + std::to_string(domain);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text = slurp(machine.path());
  text = text.substr(0, text.find("\nhosts:")) + "\nhosts:\n";
  std::string names;
  std::string offsets;
  const std::vector<std::string> offset_ms{"3", "-7", "5", "-2"};
  const std::string subnet = "10.77." + std::to_string(domain);
  if (options.secured) {
    text = std::regex_replace(text, std::regex("(^|\n)machine:\n"),
                              "$1machine:\n  security_dir: certs\n");
  }
  for (std::size_t i = 0; i < hosts.size(); ++i) {
    // hostnet.py gives the hosts subnet.1, subnet.2, ... in this order.
    const std::string address =
        options.secured ? ", address: " + subnet + "." + std::to_string(i + 1) : "";
    text += "  - {name: " + hosts[i].name + address + ", runs: [" + hosts[i].runs + "]}\n";
    names += (i == 0 ? "" : ",") + hosts[i].name;
    if (i > 0) {
      offsets += (i == 1 ? "" : ",") + hosts[i].name + "=" + offset_ms.at(i - 1);
    }
  }
  const std::string machine_path = dir + "/" + machine_file;
  std::ofstream(machine_path) << text;
  if (options.secured) {
    const RunResult certs =
        run({bin("mcnc"), "certs", machine_path, dir + "/certs"}, -1, std::chrono::seconds(120));
    EXPECT_EQ(certs.exit_code, 0) << certs.out << certs.err;
  }
  HostsRun result{{}, mcnc::config::load_machine_file(machine_path)};
  {
    const SimulatedHosts simulated("mhx" + std::to_string(domain), names, offsets, subnet);
    for (std::size_t i = 0; options.without_multicast && i < hosts.size(); ++i) {
      // On the host's link to the others only: a bus's CAN frames stay on its loopback.
      const RunResult drop =
          run(simulated.on(hosts[i].name, {"iptables", "-w", "-A", "INPUT", "-i", "eth0", "-d",
                                           "224.0.0.0/4", "-j", "DROP"}),
              -1, std::chrono::seconds(30));
      EXPECT_EQ(drop.exit_code, 0) << drop.err;
    }
    const auto launcher = [&](const std::string& host) {
      std::vector<std::string> argv{
          bin("mcnc"), "run", machine_path, "--trace", dir + "/trace.jsonl",
          "--timeout", "120", "--host",     host};
      for (const auto& [channel, program] : programs) {
        argv.insert(argv.end(), {"--program", channel + "=" + source(program)});
      }
      return simulated.on(host, argv);
    };
    std::vector<std::unique_ptr<Background>> followers;
    for (std::size_t i = 1; i < hosts.size(); ++i) {
      followers.push_back(
          std::make_unique<Background>(launcher(hosts[i].name), domain, dir + "/" + hosts[i].name));
    }
    const RunResult coordinator =
        run(launcher(hosts.front().name), domain, std::chrono::seconds(240));
    EXPECT_EQ(coordinator.exit_code, 0) << coordinator.out << coordinator.err;
    for (std::size_t i = 1; i < hosts.size(); ++i) {
      EXPECT_EQ(followers[i - 1]->wait(std::chrono::seconds(60)), 0)
          << slurp(dir + "/" + hosts[i].name + ".err");
    }
  }
  const std::vector<nlohmann::json> trace = read_trace(dir + "/trace.jsonl");
  std::set<std::string> clocks;
  for (const nlohmann::json& e : events(trace, "clock", "launch")) {
    clocks.insert(e["host"].get<std::string>());
  }
  EXPECT_EQ(clocks.size(), hosts.size()) << "every host's clock is in the trace";
  result.trace = trace_until_end(trace);
  fs::remove_all(dir);
  return result;
}

void expect_same_trace(const std::vector<nlohmann::json>& one_host,
                       std::vector<nlohmann::json> across) {
  std::erase_if(across, [](const nlohmann::json& e) { return e["ev"] == "clock"; });
  ASSERT_GT(one_host.size(), 1000U);
  ASSERT_EQ(one_host.size(), across.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < one_host.size() && differ < 5; ++i) {
    if (one_host[i] != across[i]) {
      ++differ;
      ADD_FAILURE() << "event " << i << "\n" << one_host[i].dump() << "\n" << across[i].dump();
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

}  // namespace mcnc::test
