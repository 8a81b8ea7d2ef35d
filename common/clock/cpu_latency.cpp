#include "common/clock/cpu_latency.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <utility>

namespace mcnc::clock {
namespace {

constexpr const char* kCpuLatencyDevice = "/dev/cpu_dma_latency";

}  // namespace

CpuLatencyRequest::CpuLatencyRequest(std::int32_t max_us) noexcept {
  const int fd = ::open(kCpuLatencyDevice, O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    return;
  }
  // The device takes the bound as a binary 32-bit value; the request lasts while `fd` is open.
  if (::write(fd, &max_us, sizeof max_us) != static_cast<ssize_t>(sizeof max_us)) {
    ::close(fd);
    return;
  }
  fd_ = fd;
}

CpuLatencyRequest::CpuLatencyRequest(CpuLatencyRequest&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)) {}

CpuLatencyRequest& CpuLatencyRequest::operator=(CpuLatencyRequest&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) {
      ::close(fd_);
    }
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

CpuLatencyRequest::~CpuLatencyRequest() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

std::int64_t cpu_latency_limit_us() noexcept {
  const int fd = ::open(kCpuLatencyDevice, O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    return -1;
  }
  std::int32_t value = 0;
  const bool read_all = ::read(fd, &value, sizeof value) == static_cast<ssize_t>(sizeof value);
  ::close(fd);
  return read_all ? value : -1;
}

}  // namespace mcnc::clock
