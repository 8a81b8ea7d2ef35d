#include "common/can/transport/fd_wait.hpp"

#include <poll.h>

#include <cerrno>
#include <ctime>

namespace mcnc::can {

BusResult wait_readable(int fd, std::chrono::nanoseconds timeout) noexcept {
  if (timeout.count() < 0) {
    timeout = std::chrono::nanoseconds::zero();
  }
  const auto secs = std::chrono::duration_cast<std::chrono::seconds>(timeout);
  timespec wait{};
  wait.tv_sec = static_cast<time_t>(secs.count());
  wait.tv_nsec = static_cast<long>((timeout - secs).count());
  pollfd pfd{fd, POLLIN, 0};
  const int ready = ::ppoll(&pfd, 1, &wait, nullptr);
  if (ready > 0) {
    return BusResult::ok;
  }
  if (ready == 0 || errno == EINTR) {
    return BusResult::timeout;
  }
  return BusResult::error;
}

}  // namespace mcnc::can
