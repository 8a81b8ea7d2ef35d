#pragma once
// Wall-clock pieces of the two cycle clocks (ARCHITECTURE.md §4). In `realtime` a process wakes
// at start + N * cycle on CLOCK_MONOTONIC; in `lockstep` it runs when its inputs are complete and
// only sleeps when the run is paced to real time.
#include <cstdint>

namespace mcnc::clock {

std::int64_t monotonic_ns() noexcept;
// Sleeps until the absolute CLOCK_MONOTONIC time `t_ns` (clock_nanosleep TIMER_ABSTIME).
void sleep_until_ns(std::int64_t t_ns) noexcept;
// Sleeps until cycle `cycle` starts (origin + cycle * period). With `skip_missed`, a wake-up more
// than a whole period late returns the cycle the clock is in now: missed ticks are skipped, not
// run back to back (a burst would starve the bus of time between SYNCs).
std::uint64_t wait_for_cycle(std::int64_t origin_ns, std::int64_t period_ns, std::uint64_t cycle,
                             bool skip_missed) noexcept;
// The SCHED_FIFO priority of a realtime process, every thread of it.
inline constexpr int kRealtimePriority = 40;
// Best effort for the realtime clock: 1 ns timer slack, SCHED_FIFO and mlockall where permitted.
// Call it first thing in main(), before any thread starts: threads inherit the policy, and the
// DDS and CAN receive threads must not wait behind ordinary work. Returns a short description
// of what was applied (for the log).
const char* prepare_realtime_process() noexcept;

}  // namespace mcnc::clock
