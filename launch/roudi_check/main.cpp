// mcnc-roudi-check: does the host's iceoryx RouDi register a process? Registers with it as an
// iceoryx runtime, with no port, and leaves again. mcnc-launch runs it before a machine on
// Cyclone DDS starts: a RouDi whose socket is bound may still not serve (iceoryx 2.0 can hang
// for good while it cleans up after a process killed with SIGKILL, holding a lock that process
// held), and every process of the machine would then abort in its participant's creation.
// Exit 0: registered and left. Exit 2: no RouDi answers at all. Any other end (iceoryx's own
// abort, or not ending: the caller's time limit) means RouDi does not serve.
#include "idl/dds_participant.hpp"

#include <iceoryx_hoofs/log/logmanager.hpp>
#include <iceoryx_posh/runtime/posh_runtime.hpp>

#include <unistd.h>

#include <cstdio>
#include <string>

int main() {
  if (!mcnc::dds::roudi_answers()) {
    std::fprintf(stderr, "mcnc-roudi-check: no iceoryx RouDi answers at %s\n",
                 mcnc::dds::kRoudiSocket);
    return 2;
  }
  iox::log::LogManager::GetLogManager().SetDefaultLogLevel(iox::log::LogLevel::kError);
  const std::string name = "mcnc_roudi_check_" + std::to_string(::getpid());
  // Returns once RouDi has acknowledged the registration; the runtime leaves at exit.
  iox::runtime::PoshRuntime::initRuntime(iox::RuntimeName_t(iox::cxx::TruncateToCapacity, name));
  return 0;
}
