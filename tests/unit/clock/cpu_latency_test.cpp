// CpuLatencyRequest against the kernel's own CPU latency QoS device: the bound it applies while
// a request lives, and after.
#include "common/clock/cpu_latency.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <utility>

namespace mcnc::clock {
namespace {

bool kernel_has_cpu_latency_qos() {
  return ::access("/dev/cpu_dma_latency", W_OK) == 0;
}

TEST(CpuLatencyRequest, HoldsTheKernelsBoundWhileItLivesAndReleasesItAfter) {
  if (!kernel_has_cpu_latency_qos()) {
    GTEST_SKIP() << "no writable /dev/cpu_dma_latency (not root, or no CPU latency QoS)";
  }
  const std::int64_t before = cpu_latency_limit_us();
  if (before <= 7) {
    // A realtime machine of another test holds 0 now: 7 could not be told apart from it.
    GTEST_SKIP() << "another process holds a CPU latency bound of " << before << " us";
  }
  {
    CpuLatencyRequest request(7);
    ASSERT_TRUE(request.held());
    EXPECT_EQ(cpu_latency_limit_us(), 7);
    CpuLatencyRequest moved = std::move(request);
    EXPECT_FALSE(request.held());  // NOLINT(bugprone-use-after-move): the move is the point
    EXPECT_TRUE(moved.held());
    EXPECT_EQ(cpu_latency_limit_us(), 7);
  }
  EXPECT_EQ(cpu_latency_limit_us(), before);
}

TEST(CpuLatencyRequest, ADefaultRequestHoldsNothing) {
  const CpuLatencyRequest none;
  EXPECT_FALSE(none.held());
}

}  // namespace
}  // namespace mcnc::clock
