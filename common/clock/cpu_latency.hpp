#pragma once
// A request to the kernel's CPU latency QoS (/dev/cpu_dma_latency) that idle CPUs wake within a
// bound. At 0 an idle CPU polls instead of halting, so a timer's wake-up does not first wait for
// the CPU (in a virtual machine, the host) to bring it back from its idle state (decision 138).
// The request holds while the object lives, and the kernel drops it when the process ends, also
// when it crashes.
#include <cstdint>

namespace mcnc::clock {

class CpuLatencyRequest {
 public:
  // No request: held() is false.
  CpuLatencyRequest() noexcept = default;
  // Asks that idle CPUs wake within `max_us` microseconds. held() says whether the kernel took
  // the request: false where the file is absent (no CPU latency QoS) or not writable (not root).
  explicit CpuLatencyRequest(std::int32_t max_us) noexcept;
  CpuLatencyRequest(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest& operator=(CpuLatencyRequest&& other) noexcept;
  CpuLatencyRequest(const CpuLatencyRequest&) = delete;
  CpuLatencyRequest& operator=(const CpuLatencyRequest&) = delete;
  ~CpuLatencyRequest();

  [[nodiscard]] bool held() const noexcept { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// The bound the kernel applies now, the least of every process's requests, in microseconds; -1
// where it cannot be read.
[[nodiscard]] std::int64_t cpu_latency_limit_us() noexcept;

}  // namespace mcnc::clock
