#pragma once
// The cycle loop every cyclic DDS process runs (ARCHITECTURE.md §4): wait for discovery,
// announce ready, wait for the run start, then hand out cycle numbers. Lockstep: cycle N as
// soon as the process's inputs stamped N-1 are in. Realtime: at each tick, skipping ticks
// missed by more than a cycle. A process whose feed is gone (E-stop, its source left) goes on
// stepping paced to real time so that it can bring its outputs to a safe state.
#include "common/clock/cycle_clock.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <utility>

namespace mcnc::process {

class CycleLoop {
 public:
  // How long a process on a host of several waits, once the run starts, for its host's clock.
  static constexpr std::chrono::seconds kMachineClockWait{5};

  // `cycle_priority`: the SCHED_FIFO priority of the thread that runs the cycles, in realtime
  // (clock::kCyclePriority, or clock::kAxisCyclePriority for an axis node).
  CycleLoop(ProcessNode& node, int cycle_us, int cycle_priority = clock::kCyclePriority)
      : node_(node), period_ns_(std::int64_t{cycle_us} * 1000), cycle_priority_(cycle_priority) {}

  // Polls `discovered` until it holds, announces ready and waits for the run start. False when
  // the process is told to stop first. `clock_name` is the clock the process was started for.
  // Call it on the thread that runs the cycles: in realtime it raises that thread above the
  // process's other threads.
  bool start(const std::function<bool()>& discovered, const std::string& clock_name);

  // Waits until `cycle` may run and updates it (realtime may skip ticks). `ready(cycle)` says
  // whether the lockstep inputs of `cycle` are in; `feed_gone()` whether the process's source
  // has left. Both run under the wake-up lock. False when the run stops.
  template <class Ready, class Gone>
  bool next(std::uint64_t& cycle, Ready ready, Gone feed_gone) {
    Wakeup& wake = node_.wakeup();
    if (lockstep_ && !degraded_) {
      const auto may_go = [&] {
        const RunCommand cmd = node_.run_control().command;
        return ready(cycle) || feed_gone() || cmd == RUN_STOP || cmd == RUN_ESTOP ||
               g_stop_signal != 0;
      };
      wait_in_lockstep(cycle, may_go);
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
    if (!lockstep_ && !degraded_) {
      origin_ns_ = rc.start_ns;  // follows the host's clock offset as its launcher refines it
    }
    if (!lockstep_ || degraded_ || pace_) {
      cycle = clock::wait_for_cycle(origin_ns_, period_ns_, cycle, !lockstep_ || degraded_);
      woke_ns_ = clock::monotonic_ns();
      due_ns_ = origin_ns_ + static_cast<std::int64_t>(cycle) * period_ns_;
    }
    return true;
  }

  // After next() said the run stops: waits for the next cycle paced to real time (a lockstep
  // machine's inputs no longer come), so that the process can bring its outputs to rest
  // before it leaves. `cycle` is the one next() did not run, then the one after each call.
  void next_stopping(std::uint64_t& cycle) noexcept {
    if (lockstep_ && !degraded_) {
      degraded_ = true;
      origin_ns_ = clock::monotonic_ns() - static_cast<std::int64_t>(cycle) * period_ns_;
    }
    cycle = clock::wait_for_cycle(origin_ns_, period_ns_, cycle, true);
    woke_ns_ = clock::monotonic_ns();
    due_ns_ = origin_ns_ + static_cast<std::int64_t>(cycle) * period_ns_;
  }

  // Lockstep: `on_slow(cycle)` runs (under the wake-up lock) once a cycle has waited `after` for
  // its inputs, to say what it waits for.
  void on_slow_wait(std::chrono::milliseconds after, std::function<void(std::uint64_t)> on_slow) {
    slow_ = after;
    on_slow_ = std::move(on_slow);
  }

  // How soon a lockstep wait announces the process's latest cyclic samples again, and the
  // longest time between two announcements (decision 98).
  static constexpr std::chrono::milliseconds kFirstAnnounce{250};
  static constexpr std::chrono::milliseconds kLongestAnnounce{2000};

  [[nodiscard]] bool lockstep() const noexcept { return lockstep_; }
  // Stepping on its own: lockstep without a feed, paced to real time.
  [[nodiscard]] bool degraded() const noexcept { return degraded_; }
  // The machine is E-stopped (as of the last next()).
  [[nodiscard]] bool emergency_stop() const noexcept { return estop_; }
  // Realtime: when the current cycle was due and when its wake-up came, on this host's
  // CLOCK_MONOTONIC.
  [[nodiscard]] std::int64_t due_ns() const noexcept { return due_ns_; }
  [[nodiscard]] std::int64_t woke_ns() const noexcept { return woke_ns_; }
  // When cycle 0 was due on this host's clock (realtime: the run's start, as the host's launcher
  // refines its offset against machine time).
  [[nodiscard]] std::int64_t origin_ns() const noexcept { return origin_ns_; }

 private:
  // Lockstep waits never give up (decision 7). While one lasts, the process announces its
  // latest cyclic samples again, after kFirstAnnounce and then at doubling intervals up to
  // kLongestAnnounce: a reader that lost the last sample a process wrote before it waits
  // learns of it and asks for it (decision 98). A slow wait is told once per cycle.
  template <class MayGo>
  void wait_in_lockstep(std::uint64_t cycle, const MayGo& may_go) {
    using std::chrono::milliseconds;
    Wakeup& wake = node_.wakeup();
    milliseconds waited{0};
    milliseconds interval = kFirstAnnounce;
    milliseconds announce_at = kFirstAnnounce;
    bool told = !on_slow_;
    for (;;) {
      const milliseconds until = told ? announce_at : std::min(announce_at, slow_);
      if (wake.wait_for(may_go, until - waited)) {
        return;
      }
      waited = until;
      if (waited >= announce_at) {
        node_.participant().announce_latest_cyclic();  // not under the wake-up lock
        interval = std::min(interval * 2, kLongestAnnounce);
        announce_at += interval;
      }
      if (!told && waited >= slow_) {
        wake.with_lock([&] { on_slow_(cycle); });
        told = true;
      }
    }
  }

  ProcessNode& node_;
  std::int64_t period_ns_;
  int cycle_priority_;
  std::int64_t origin_ns_ = 0;
  bool lockstep_ = true;
  bool pace_ = false;
  bool degraded_ = false;
  bool estop_ = false;
  std::int64_t due_ns_ = 0;
  std::int64_t woke_ns_ = 0;
  std::chrono::milliseconds slow_{0};
  std::function<void(std::uint64_t)> on_slow_;
};

}  // namespace mcnc::process
