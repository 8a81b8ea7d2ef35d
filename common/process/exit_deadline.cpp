#include "common/process/exit_deadline.hpp"

#include "common/process/startup.hpp"

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

TeardownBound::TeardownBound(std::chrono::milliseconds limit, int exit_code,
                             std::function<void()> before_exit) {
  const std::sig_atomic_t signals_before = g_stop_signals;
  try {
    watch_ =
        std::thread([this, limit, exit_code, signals_before, before_exit = std::move(before_exit)] {
          const auto end = std::chrono::steady_clock::now() + limit;
          std::unique_lock<std::mutex> lock(mutex_);
          // Polled: a signal handler cannot notify a condition variable.
          while (!disarmed_ && std::chrono::steady_clock::now() < end &&
                 g_stop_signals == signals_before) {
            disarmed_signal_.wait_for(lock, std::chrono::milliseconds(50));
          }
          if (disarmed_) {
            return;
          }
          if (before_exit) {
            before_exit();
          }
          std::_Exit(exit_code);
        });
  } catch (const std::system_error&) {
    // No thread: no bound.
  }
}

TeardownBound::~TeardownBound() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disarmed_ = true;
  }
  disarmed_signal_.notify_all();
  if (watch_.joinable()) {
    watch_.join();
  }
}

}  // namespace mcnc::process
