#include "common/process/exit_deadline.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <thread>

namespace mcnc::process {

void arm_exit_deadline(const char* process_name, std::chrono::milliseconds limit,
                       int exit_code) noexcept {
  // Written now and with write(2) then: by the deadline, static destruction may have taken the
  // logger down.
  std::array<char, 160> text{};
  const int n = std::snprintf(text.data(), text.size(),
                              "[%s] still here %lld ms after its stop (DDS teardown hung): "
                              "leaving with exit code %d\n",
                              process_name, static_cast<long long>(limit.count()), exit_code);
  const std::size_t length = n > 0 ? std::min(static_cast<std::size_t>(n), text.size() - 1) : 0;
  try {
    // Detached: it must not be joined by a destructor that may itself be the one that hangs;
    // a process that ends first ends it with everything else.
    std::thread([limit, exit_code, text, length] {
      std::this_thread::sleep_for(limit);
      (void)!::write(STDERR_FILENO, text.data(), length);
      std::_Exit(exit_code);
    }).detach();
  } catch (const std::system_error&) {
    // No thread: the launcher's kill remains the bound.
  }
}

}  // namespace mcnc::process
