#pragma once
// The cycle loop every cyclic DDS process runs (ARCHITECTURE.md §4): wait for discovery,
// announce ready, wait for the run start, then hand out cycle numbers. Lockstep: cycle N as
// soon as the process's inputs stamped N-1 are in. Realtime: at each tick, skipping ticks
// missed by more than a cycle. A process whose feed is gone (E-stop, its source left) goes on
// stepping paced to real time so that it can bring its outputs to a safe state.
#include "common/clock/cycle_clock.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

namespace mcnc::process {

class CycleLoop {
 public:
  CycleLoop(ProcessNode& node, int cycle_us)
      : node_(node), period_ns_(std::int64_t{cycle_us} * 1000) {}

  // Polls `discovered` until it holds, announces ready and waits for the run start. False when
  // the process is told to stop first. `clock_name` is the clock the process was started for.
  bool start(const std::function<bool()>& discovered, const std::string& clock_name);

  // Waits until `cycle` may run and updates it (realtime may skip ticks). `ready(cycle)` says
  // whether the lockstep inputs of `cycle` are in; `feed_gone()` whether the process's source
  // has left. Both run under the wake-up lock. False when the run stops.
  template <class Ready, class Gone>
  bool next(std::uint64_t& cycle, Ready ready, Gone feed_gone) {
    Wakeup& wake = node_.wakeup();
    if (lockstep_ && !degraded_) {
      wake.wait_for(
          [&] {
            const RunCommand cmd = node_.run_control().command;
            return ready(cycle) || feed_gone() || cmd == RUN_STOP || cmd == RUN_ESTOP ||
                   g_stop_signal != 0;
          },
          std::chrono::hours(24));
    }
    const RunControlView rc = node_.run_control();
    if (rc.command == RUN_STOP || g_stop_signal != 0) {
      return false;
    }
    estop_ = rc.command == RUN_ESTOP;
    bool gone = false;
    wake.update([&] { gone = feed_gone(); });
    if (lockstep_ && !degraded_ && (estop_ || gone)) {
      degraded_ = true;
      origin_ns_ = clock::monotonic_ns() - static_cast<std::int64_t>(cycle) * period_ns_;
    }
    if (!lockstep_ || degraded_ || pace_) {
      cycle = clock::wait_for_cycle(origin_ns_, period_ns_, cycle, !lockstep_ || degraded_);
    }
    return true;
  }

  [[nodiscard]] bool lockstep() const noexcept { return lockstep_; }
  // Stepping on its own: lockstep without a feed, paced to real time.
  [[nodiscard]] bool degraded() const noexcept { return degraded_; }
  // The machine is E-stopped (as of the last next()).
  [[nodiscard]] bool emergency_stop() const noexcept { return estop_; }

 private:
  ProcessNode& node_;
  std::int64_t period_ns_;
  std::int64_t origin_ns_ = 0;
  bool lockstep_ = true;
  bool pace_ = false;
  bool degraded_ = false;
  bool estop_ = false;
};

}  // namespace mcnc::process
