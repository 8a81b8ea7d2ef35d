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
// SCHED_FIFO priorities of a realtime machine, lowest first (decision 55): every thread of a
// realtime process, its middleware's receive threads among them; the cycle thread of a channel
// or the PLC; the cycle thread of an axis node and its CAN receive thread (the drive's
// answers), which close the drive's loop at the tick. A
// burst of samples or of discovery then never delays a tick. The SYNC timer runs above those:
// the SYNC is the bus's clock, when the drives take their setpoints, and hosts align their
// cycles by it (decision 128); an axis-node cycle still running at the SYNC's due time sends
// its RPDO for the next SYNC, as a late node on a real bus does. The host's RouDi and the
// launcher's supervision run above all of them (launch/).
inline constexpr int kRealtimePriority = 38;
inline constexpr int kCyclePriority = 39;
inline constexpr int kAxisCyclePriority = 40;
inline constexpr int kSyncPriority = 41;
// Whether a realtime process asks the kernel to keep idle CPUs polling (CpuLatencyRequest at 0
// for the process's life, decision 138) or leaves them to the kernel's idle states.
enum class IdleCpus { poll, kernel_default };
// Best effort for the realtime clock: 1 ns timer slack, SCHED_FIFO and mlockall where permitted,
// and idle CPUs that poll. Call it first thing in main(), before any thread starts: threads
// inherit the policy, and the DDS and CAN receive threads must not wait behind ordinary work.
// Returns a short description of what was applied (for the log). Call it once.
const char* prepare_realtime_process(IdleCpus idle = IdleCpus::poll) noexcept;
// Raises the calling thread (a cycle thread, or an axis node's CAN threads) to `priority` when
// it runs at SCHED_FIFO (prepare_realtime_process() was permitted). False when it does not, or
// may not.
bool raise_realtime_thread(int priority) noexcept;

}  // namespace mcnc::clock
