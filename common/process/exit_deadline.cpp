#include "common/process/exit_deadline.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <thread>

namespace mcnc::process {

void arm_exit_deadline(std::chrono::milliseconds limit) {
  // Detached: the thread must not be joined by a destructor that may itself be the one that
  // hangs; a process that ends first ends it with everything else.
  std::thread([limit] {
    std::this_thread::sleep_for(limit);
    spdlog::warn("still here {} ms after the stop (DDS teardown hung): leaving without it",
                 limit.count());
    std::_Exit(kExitTeardownHung);
  }).detach();
}

}  // namespace mcnc::process
