#pragma once
// Start-up helpers shared by the process shells.
#include "common/config/machine_config.hpp"
#include "common/security/identity_files.hpp"

#include <csignal>
#include <optional>
#include <string>

namespace CLI {
class App;
}
namespace mcnc::dds {
enum class CyclicClock;
}

namespace mcnc::process {

// The options every process shell takes: --machine, --clock, --log-level.
struct ShellOptions {
  std::string machine_path;
  std::string clock = "lockstep";  // realtime: SCHED_FIFO and locked memory from the start
  std::string log_level;
};
void add_shell_options(CLI::App& app, ShellOptions& options);
// The heartbeat its clock asks of the process's cyclic writers (dds::CyclicClock).
dds::CyclicClock cyclic_clock(const ShellOptions& options);

// What a process does when the launcher that started it dies (a `kill -9` of it included).
enum class WhenLauncherDies {
  stop,     // it gets SIGTERM, as from the launcher: it stops as safely as it would then
  outlive,  // it goes on and watches launcher_gone() (a simulated drive: the hardware stays)
};

// The first things a process does once it knows its name: its logger, real-time scheduling
// when the clock is realtime (before any thread starts, so that all inherit it), and the stop
// signals.
void start_process(const std::string& process_name, const ShellOptions& options,
                   WhenLauncherDies when = WhenLauncherDies::stop);

// Loads and validates the machine file; on error prints "<path>: <key path>: <reason>" to
// stderr and exits with code 2 (bad input: nothing is started).
config::MachineConfig load_machine_or_exit(const std::string& path);

// A process on Cyclone DDS moves its cyclic samples through its host's RouDi, and its
// participant would wait for ever for one: when none answers, prints why to stderr and exits
// with code 2 (nothing is started). `process` as the machine file names it (CH1, X1, PLC, HMI).
void require_roudi_or_exit(const config::MachineConfig& machine, const std::string& process);

// The DDS Security files a process of the machine presents as `identity` (docs/operations.md,
// "Security"): nullopt when the machine file names no security_dir (unsecured). When they do
// not let it join (a file missing or unreadable, a certificate expired or of another CA, a key
// not the certificate's, documents not signed by the CA), prints the reason, which names the
// file, and exits with code 2: nothing is started.
std::optional<security::IdentityFiles> resolve_security_or_exit(
    const config::MachineConfig& machine, const std::string& identity);
// How a participant of a secured machine discovers (decisions 137, 151).
struct SecuredDiscovery {
  bool across_hosts = false;  // the machine runs across the hosts of its hosts: section
  bool onlooker = false;      // no index of its own (as the viewer): a launcher's service
};
// The same for a participant that is not the process its identity names for discovery: a
// launcher (which knows its host from --host) and the tools that share its identity.
std::optional<security::IdentityFiles> resolve_security_or_exit(
    const config::MachineConfig& machine, const std::string& identity, SecuredDiscovery discovery);
// The same check without exiting: nullopt when the identity's files are good (or the machine is
// unsecured), else the reason.
std::optional<std::string> security_problem(const config::MachineConfig& machine,
                                            const std::string& identity);

// SIGINT/SIGTERM set this flag (installed by install_stop_signals()). When MCNC_DIE_WITH_PARENT
// is set (mcnc-launch sets it for its children), the process also gets SIGTERM when its parent
// dies (`WhenLauncherDies::stop`), so a killed launcher leaves nothing running.
extern volatile std::sig_atomic_t g_stop_signal;
// How many SIGINT/SIGTERM came: a signal after a given moment, which g_stop_signal, once set,
// cannot tell.
extern volatile std::sig_atomic_t g_stop_signals;
void install_stop_signals(WhenLauncherDies when = WhenLauncherDies::stop);
// True once the launcher that started this process is gone: its parent is no longer the
// process MCNC_LAUNCHER_PID names (a service manager that adopts orphans is not pid 1). False
// for a process no launcher started.
bool launcher_gone() noexcept;

}  // namespace mcnc::process
