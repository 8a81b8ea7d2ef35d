#include "common/clock/cycle_clock.hpp"

#include "common/clock/cpu_latency.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cstdio>
#include <ctime>

namespace mcnc::clock {

std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t t_ns) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t_ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(t_ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

std::uint64_t wait_for_cycle(std::int64_t origin_ns, std::int64_t period_ns, std::uint64_t cycle,
                             bool skip_missed) noexcept {
  const std::int64_t target = origin_ns + static_cast<std::int64_t>(cycle) * period_ns;
  const std::int64_t now = monotonic_ns();
  if (skip_missed && now > target + period_ns) {
    return static_cast<std::uint64_t>((now - origin_ns) / period_ns);
  }
  sleep_until_ns(target);
  return cycle;
}

const char* prepare_realtime_process(IdleCpus idle) noexcept {
  // The default 50 us timer slack would add to every wake-up.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  sched_param param{};
  param.sched_priority = kRealtimePriority;
  const bool fifo = sched_setscheduler(0, SCHED_FIFO, &param) == 0;
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  // Held until the process ends: every cycle of its life wakes from a polling CPU.
  static CpuLatencyRequest awake;
  if (idle == IdleCpus::poll) {
    awake = CpuLatencyRequest(0);
  }
  static_assert(kRealtimePriority == 38, "the description below names it");
  static char description[160];
  std::snprintf(description, sizeof description, "timer slack 1 ns, %s, %s, %s",
                fifo ? "SCHED_FIFO 38" : "SCHED_FIFO not permitted",
                locked ? "memory locked" : "mlockall not permitted",
                idle == IdleCpus::kernel_default ? "idle CPUs as the kernel sets them"
                : awake.held()                   ? "idle CPUs poll (CPU latency 0)"
                                                 : "idle CPUs as the kernel sets them (no CPU "
                                                   "latency request permitted)");
  return description;
}

bool raise_realtime_thread(int priority) noexcept {
  int policy = 0;
  sched_param param{};
  if (pthread_getschedparam(pthread_self(), &policy, &param) != 0 || policy != SCHED_FIFO) {
    return false;
  }
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace mcnc::clock
