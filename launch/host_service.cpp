#include "launch/host_service.hpp"

#include "launch/machine_security.hpp"

#include "common/clock/cycle_clock.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "launch/child_process.hpp"
#include "launch/self_path.hpp"

#include <unistd.h>

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

namespace mcnc::launch {

using namespace std::chrono_literals;

namespace {

constexpr std::size_t kOutputLimit = 64 * 1024;
constexpr const char* kServicePrefix = "service-";

std::string read_tail(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string all = text.str();
  return all.size() > kOutputLimit ? all.substr(all.size() - kOutputLimit) : all;
}

std::string run_id() {
  char host[64] = {};
  ::gethostname(host, sizeof host - 1);
  return std::string(host) + "-" + std::to_string(::getpid()) + "-" +
         std::to_string(clock::monotonic_ns());
}

}  // namespace

int serve_host(const RunArguments& args) {
  const config::MachineConfig machine = process::load_machine_or_exit(args.machine_path);
  if (args.host.empty() || machine.hosts.empty()) {
    std::fprintf(stderr, "error: --serve needs --host and a machine with a hosts: section\n");
    return 2;
  }
  const std::string machine_path = std::filesystem::absolute(args.machine_path).string();
  process::install_stop_signals();
  // A host's service commands its host's runs as the launcher it starts would.
  process::ProcessNode node(
      process::resolve_domain(machine), kServicePrefix + args.host, dds::CyclicClock::realtime,
      process::resolve_middleware(machine, "launch"), dds::LocalTransport::network,
      // An onlooker: the launcher it starts takes the identity's index.
      process::resolve_security_or_exit(machine, launcher_identity(machine, args.host),
                                        {true, true}));
  std::mutex mutex;
  std::deque<RunRequest> requests;
  std::set<std::string> seen_ids;
  dds::Reader<RunRequest> request_reader(node.participant(),
                                         [&](const RunRequest& r, const dds::WriterId&) {
                                           node.wakeup().update([&] {
                                             if (seen_ids.insert(r.id()).second) {
                                               requests.push_back(r);
                                             }
                                           });
                                         });
  dds::Writer<RunOutcome> outcome_writer(node.participant());
  node.announce(PHASE_READY, 0, "launcher service of host " + args.host);
  spdlog::info("launcher service of host {} on {}", args.host, machine_path);

  while (process::g_stop_signal == 0) {
    std::optional<RunRequest> request;
    node.wakeup().wait_for([&] { return !requests.empty() || process::g_stop_signal != 0; }, 500ms);
    node.wakeup().update([&] {
      if (!requests.empty()) {
        request = requests.front();
        requests.pop_front();
      }
    });
    if (!request) {
      continue;
    }
    std::vector<std::string> argv{executable_dir() + "/mcnc-launch", machine_path};
    argv.insert(argv.end(), request->args().begin(), request->args().end());
    argv.insert(argv.end(), {"--host", args.host});
    const std::string output =
        (std::filesystem::temp_directory_path() / ("mcnc-run-" + args.host + ".log")).string();
    spdlog::info("run {} asked from {}", request->id(), request->cwd());
    RunOutcome outcome;
    outcome.id(request->id());
    outcome.host(args.host);
    try {
      ChildProcess launcher("mcnc-launch", argv);
      launcher.set_directory(request->cwd());
      launcher.set_output(output);
      launcher.start({});
      node.announce(PHASE_RUNNING, 0, "run " + request->id());
      bool asked_to_stop = false;
      while (!launcher.poll_exited()) {
        if (process::g_stop_signal != 0 && !asked_to_stop) {
          launcher.signal(SIGTERM);  // it E-stops and stops its run
          asked_to_stop = true;
        }
        std::this_thread::sleep_for(50ms);
      }
      outcome.exit_code(launcher.exit_code());
      outcome.output(read_tail(output));
    } catch (const std::exception& e) {
      outcome.exit_code(2);
      outcome.output(std::string("the launcher could not start: ") + e.what() + "\n");
    }
    std::filesystem::remove(output);
    spdlog::info("run {} ended: exit {}", request->id(), outcome.exit_code());
    outcome_writer.write(outcome);
    node.announce(PHASE_READY, 0, "launcher service of host " + args.host);
  }
  node.announce(PHASE_STOPPED);
  // The last outcome must reach its asker before the participant goes.
  std::this_thread::sleep_for(500ms);
  return 0;
}

int request_run(const RunArguments& args) {
  const config::MachineConfig machine = process::load_machine_or_exit(args.machine_path);
  if (machine.hosts.empty()) {
    std::fprintf(stderr, "error: --services: %s has no hosts: section\n",
                 args.machine_path.c_str());
    return 2;
  }
  process::install_stop_signals();
  process::ProcessNode node(process::resolve_domain(machine),
                            "mcnc-run-" + std::to_string(::getpid()), dds::CyclicClock::realtime,
                            process::resolve_middleware(machine, "launch"),
                            dds::LocalTransport::network,
                            process::resolve_security_or_exit(machine, "launch", {true, true}));
  std::map<std::string, ProcessPhase> services;  // under the wake-up lock, as outcomes
  std::map<std::string, RunOutcome> outcomes;
  const std::string id = run_id();
  dds::Reader<ProcessState> state_reader(
      node.participant(), [&](const ProcessState& s, const dds::WriterId&) {
        if (s.name().rfind(kServicePrefix, 0) == 0) {
          node.wakeup().update([&] { services[s.name()] = s.phase(); });
        }
      });
  dds::Reader<RunOutcome> outcome_reader(node.participant(),
                                         [&](const RunOutcome& o, const dds::WriterId&) {
                                           if (o.id() == id) {
                                             node.wakeup().update([&] { outcomes[o.host()] = o; });
                                           }
                                         });
  dds::Writer<RunRequest> request_writer(node.participant());

  // Every host's service, ready for a run.
  const auto silent = [&] {
    std::string names;
    for (const auto& h : machine.hosts) {
      const auto it = services.find(kServicePrefix + h.name);
      if (it == services.end() || it->second != PHASE_READY) {
        names += (names.empty() ? "" : ", ") + h.name;
      }
    }
    return names;
  };
  std::string waiting;
  node.wakeup().wait_for(
      [&] {
        waiting = silent();
        return waiting.empty() || process::g_stop_signal != 0;
      },
      std::chrono::seconds(60));
  if (!waiting.empty()) {
    std::fprintf(stderr,
                 "error: no launcher service ready on host %s (mcnc-launch %s --host "
                 "NAME --serve)\n",
                 waiting.c_str(), args.machine_path.c_str());
    return 1;
  }

  RunRequest request;
  request.id(id);
  request.cwd(std::filesystem::current_path().string());
  request.args(run_argv(args));
  request_writer.write(request);
  spdlog::info("run {} asked of {} hosts", id, machine.hosts.size());

  // The coordinator's outcome ends the run; the others' follow within seconds (a follower's
  // launcher ends with the coordinator's stop), or their service is gone.
  const std::string coordinator = machine.hosts.front().name;
  node.wakeup().wait_for(
      [&] { return outcomes.count(coordinator) != 0 || process::g_stop_signal != 0; },
      std::chrono::hours(24 * 365));
  node.wakeup().wait_for(
      [&] { return outcomes.size() == machine.hosts.size() || process::g_stop_signal != 0; },
      std::chrono::seconds(60));
  int exit_code = 1;
  node.wakeup().update([&] {
    if (const auto it = outcomes.find(coordinator); it != outcomes.end()) {
      std::fputs(it->second.output().c_str(), stdout);
      exit_code = it->second.exit_code();
    }
    for (const auto& h : machine.hosts) {
      const auto it = outcomes.find(h.name);
      if (it == outcomes.end()) {
        std::fprintf(stderr, "host %s: no outcome from its service\n", h.name.c_str());
        exit_code = exit_code == 0 ? 1 : exit_code;
      } else if (it->second.exit_code() != 0 && h.name != coordinator) {
        std::fprintf(stderr, "host %s: its part ended with exit %d\n", h.name.c_str(),
                     it->second.exit_code());
        exit_code = exit_code == 0 ? 1 : exit_code;
      }
    }
  });
  std::fflush(stdout);
  return exit_code;
}

}  // namespace mcnc::launch
