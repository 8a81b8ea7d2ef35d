#include "common/process/startup.hpp"

#include <sys/prctl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

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
void on_stop_signal(int /*signal*/) {
  g_stop_signal = 1;
}
}  // namespace

void install_stop_signals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  const char* die = std::getenv("MCNC_DIE_WITH_PARENT");
  if (die != nullptr && std::string(die) == "1") {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() == 1) {  // the parent died before we got here
      g_stop_signal = 1;
    }
  }
}

}  // namespace mcnc::process
