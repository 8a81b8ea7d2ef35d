#include "common/process/startup.hpp"

#include <cstdio>
#include <cstdlib>

namespace mcnc::process {

volatile std::sig_atomic_t g_stop_signal = 0;

config::MachineConfig load_machine_or_exit(const std::string& path) {
  try {
    return config::load_machine_file(path);
  } catch (const config::ConfigError& e) {
    std::fprintf(stderr, "error: machine file %s: %s\n", path.c_str(), e.what());
    std::exit(2);
  }
}

namespace {
void on_stop_signal(int /*signal*/) { g_stop_signal = 1; }
} // namespace

void install_stop_signals() {
  struct sigaction action{};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

} // namespace mcnc::process
