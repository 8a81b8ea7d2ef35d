#pragma once
// How a child's end counts once the launcher has stopped the run (docs/operations.md, "Fast
// DDS 2.9.1 now and then aborts ..."). Fast DDS 2.9.1 may abort or hang a process while it
// deletes its participant; a child that had done its work by then must not fail the run.
namespace mcnc::launch {

enum class ChildEnd {
  clean,           // exited with code 0
  teardown,        // aborted, killed or left by its deadline (exit code 3) in its DDS
                   // teardown after its work: warn
  teardown_early,  // aborted before it announced its stop, in a run that had not failed:
                   // warn that its end work may not be done
  failed,          // any other abnormal end: the run fails
};

struct ChildExit {
  int exit_code = 0;                // ChildProcess::exit_code(): -signal when killed by one
  bool announced_stop = false;      // the launcher saw its PHASE_STOPPED
  bool killed_by_launcher = false;  // the launcher sent SIGKILL to the children still there
  bool run_failed = false;          // the run had failed before the stop
};

[[nodiscard]] ChildEnd classify_child_end(const ChildExit& e) noexcept;

}  // namespace mcnc::launch
