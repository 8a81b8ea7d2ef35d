#include "launch/child_end.hpp"

#include "common/process/exit_deadline.hpp"

#include <csignal>

namespace mcnc::launch {

ChildEnd classify_child_end(const ChildExit& e) noexcept {
  if (e.exit_code == 0) {
    return ChildEnd::clean;
  }
  // It left by its own exit deadline, which it arms only after its end work. (With alarms it
  // had raised, kExitTeardownHungAfterAlarms, they may not have arrived: that fails below.)
  if (e.exit_code == process::kExitTeardownHung) {
    return ChildEnd::teardown;
  }
  // An abort once the run was over is Fast DDS tearing down a participant while the others
  // leave (an assertion in PDP::check_remote_participant_liveliness), before or after the
  // process said it stopped. An abort during the run failed it already.
  if (e.exit_code == -SIGABRT) {
    if (e.announced_stop) {
      return ChildEnd::teardown;
    }
    return e.run_failed ? ChildEnd::failed : ChildEnd::teardown_early;
  }
  // Killed because it had not left long after the stop: when it had said it stopped, it hangs
  // in the same teardown and its work was done and reported.
  if (e.exit_code == -SIGKILL && e.killed_by_launcher && e.announced_stop) {
    return ChildEnd::teardown;
  }
  return ChildEnd::failed;
}

}  // namespace mcnc::launch
