#include "common/process/startup.hpp"

#include "common/security/discovery_peers.hpp"
#include "common/security/pki/pki.hpp"

#include "common/clock/cycle_clock.hpp"
#include "common/log/logging.hpp"
#include "common/process/process_node.hpp"
#include "idl/dds_participant.hpp"
#include "idl/topics.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <sys/prctl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace mcnc::process {

void add_shell_options(CLI::App& app, ShellOptions& options) {
  app.add_option("--machine", options.machine_path, "machine file (YAML)")->required();
  app.add_option("--clock", options.clock,
                 "lockstep or realtime (realtime: SCHED_FIFO, memory locked)")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app.add_option("--log-level", options.log_level, "trace|debug|info|warn|error|off");
}

dds::CyclicClock cyclic_clock(const ShellOptions& options) {
  return options.clock == "lockstep" ? dds::CyclicClock::lockstep : dds::CyclicClock::realtime;
}

void require_roudi_or_exit(const config::MachineConfig& machine, const std::string& process) {
  if (resolve_middleware(machine, process) == dds::Middleware::cyclonedds &&
      !dds::roudi_answers()) {
    std::fprintf(stderr,
                 "error: %s runs on Cyclone DDS and no iceoryx RouDi answers at %s (start "
                 "iox-roudi, or run the machine with mcnc-launch, which starts one)\n",
                 process.c_str(), dds::kRoudiSocket);
    std::exit(2);
  }
}

void start_process(const std::string& process_name, const ShellOptions& options,
                   WhenLauncherDies when) {
  log::setup(process_name, options.log_level);
  if (options.clock == "realtime") {
    spdlog::info("realtime clock: {}", clock::prepare_realtime_process());
  }
  install_stop_signals(when);
}

volatile std::sig_atomic_t g_stop_signal = 0;
volatile std::sig_atomic_t g_stop_signals = 0;

config::MachineConfig load_machine_or_exit(const std::string& path) {
  try {
    return config::load_machine_file(path);
  } catch (const config::ConfigError& e) {
    std::fprintf(stderr, "error: machine file %s: %s\n", path.c_str(), e.what());
    std::exit(2);
  }
}

std::optional<std::string> security_problem(const config::MachineConfig& machine,
                                            const std::string& identity) {
  if (machine.security_dir.empty()) {
    return std::nullopt;
  }
  return security::check_identity(security::identity_files(machine.security_dir, identity),
                                  std::chrono::system_clock::now());
}

std::optional<security::IdentityFiles> resolve_security_or_exit(
    const config::MachineConfig& machine, const std::string& identity) {
  // A process a launcher started on one of the machine's hosts has MCNC_HOST; the viewer looks
  // on wherever the machine runs.
  const bool across_hosts =
      identity == security::kViewerIdentity ? !machine.hosts.empty() : !resolve_host().empty();
  return resolve_security_or_exit(machine, identity, SecuredDiscovery{across_hosts, false});
}

std::optional<security::IdentityFiles> resolve_security_or_exit(
    const config::MachineConfig& machine, const std::string& identity, SecuredDiscovery discovery) {
  if (machine.security_dir.empty()) {
    return std::nullopt;
  }
  if (const auto problem = security_problem(machine, identity)) {
    std::fprintf(stderr, "error: DDS Security identity %s: %s\n", identity.c_str(),
                 problem->c_str());
    std::exit(2);
  }
  security::IdentityFiles files = security::identity_files(machine.security_dir, identity);
  files.discovery = security::discovery_peers(
      machine, discovery.onlooker ? std::string(security::kViewerIdentity) : identity,
      discovery.across_hosts);
  return files;
}

namespace {
void on_stop_signal(int /*signal*/) {
  g_stop_signal = 1;
  g_stop_signals = g_stop_signals + 1;
}
pid_t g_launcher_pid = 0;  // 0: not started by a launcher
}  // namespace

void install_stop_signals(WhenLauncherDies when) {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  const char* die = std::getenv("MCNC_DIE_WITH_PARENT");
  if (die == nullptr || std::string(die) != "1") {
    return;
  }
  // The launcher's pid, or the parent's when it did not say (an older launcher): a launcher
  // that died before this line leaves a parent that is not it, whoever adopted the process.
  const char* launcher = std::getenv("MCNC_LAUNCHER_PID");
  g_launcher_pid = launcher != nullptr ? static_cast<pid_t>(std::atol(launcher)) : getppid();
  if (when == WhenLauncherDies::stop) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (launcher_gone()) {
      g_stop_signal = 1;
    }
  }
}

bool launcher_gone() noexcept {
  return g_launcher_pid > 0 && getppid() != g_launcher_pid;
}

}  // namespace mcnc::process
