#include "common/process/cycle_loop.hpp"

#include <spdlog/spdlog.h>

namespace mcnc::process {

bool CycleLoop::start(const std::function<bool()>& discovered, const std::string& clock_name) {
  while (!discovered()) {
    if (g_stop_signal != 0) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  node_.announce(PHASE_READY);
  node_.wakeup().wait_for(
      [&] { return node_.run_control().command != RUN_NONE || g_stop_signal != 0; },
      std::chrono::hours(24));
  if (node_.run_control().command != RUN_START || g_stop_signal != 0) {
    return false;
  }
  // Across hosts the start is in machine time: this host's offset must be known first. The
  // coordinator starts a run only once every host has announced its clock, so this wait is
  // short unless the host's launcher is gone.
  if (!node_.wakeup().wait_for([&] { return node_.machine_clock_known() || g_stop_signal != 0; },
                               kMachineClockWait) ||
      g_stop_signal != 0) {
    const std::string why = "no machine clock from host " + node_.host() + "'s launcher within " +
                            std::to_string(kMachineClockWait.count()) + " s";
    spdlog::error("{}", why);
    node_.announce(PHASE_FAILED, 0, why);
    return false;
  }
  const RunControlView rc = node_.run_control();
  lockstep_ = rc.clock == LOCKSTEP_CLOCK;
  pace_ = rc.pace;
  origin_ns_ = rc.start_ns;
  if (lockstep_ != (clock_name == "lockstep")) {
    spdlog::warn("the run uses the {} clock; this process was started for {}",
                 lockstep_ ? "lockstep" : "realtime", clock_name);
  }
  if (!lockstep_) {
    (void)clock::raise_realtime_thread(cycle_priority_);  // not at SCHED_FIFO: nothing to raise
  }
  node_.announce(PHASE_RUNNING);
  return true;
}

}  // namespace mcnc::process
