#pragma once
// A bound on how long a process may take to leave once its end work is done. Fast DDS 2.9.1
// (Debian 12) now and then hangs while it deletes a participant whose peers leave at the same
// moment (docs/operations.md). A process stuck there has done its work, but the launcher could
// only kill it, and a kill cannot tell "stuck after the work" from "killed before it"; the stop
// announcement that would tell is lost in the same hang (docs/decisions.md 28).
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace mcnc::process {

// The exit codes of a process that left by its deadline: its end work was done, its DDS
// teardown was not. With kExitTeardownHungAfterAlarms it had raised alarms (or lost some),
// which may not have reached anyone: that end fails the run.
inline constexpr int kExitTeardownHung = 3;
inline constexpr int kExitTeardownHungAfterAlarms = 4;

// The deadline the DDS processes arm when they announce their stop: an axis node waits up to
// 2 s for its channels to go, which leaves 2 s for the participant's deletion.
inline constexpr std::chrono::milliseconds kStopToExitLimit{4000};

// Called once, after the end work (trace flushed, retained data saved, stop announced). If the
// process is still there `limit` later, it says so on stderr (naming itself) and leaves at once
// with `exit_code`, skipping every destructor still to run. A process that leaves in time never
// notices. Without a thread to spare, there is no deadline.
void arm_exit_deadline(const char* process_name, std::chrono::milliseconds limit,
                       int exit_code) noexcept;

// A bound on a stretch of a process's end that may hang in its DDS implementation: Cyclone DDS
// 0.10's teardown waits for its security handshake thread, which can spin for good after a
// handshake's time-out (a race in its state machine, fixed upstream after 0.10.2), and a stop
// signal only sets g_stop_signal. Armed, it watches on a thread of its own; when it is not
// disarmed (destroyed) within `limit`, or a stop signal comes after it was armed, it runs
// `before_exit` there and leaves at once with `exit_code`, skipping every destructor still to
// run. Without a thread to spare, there is no bound.
class TeardownBound {
 public:
  TeardownBound(std::chrono::milliseconds limit, int exit_code, std::function<void()> before_exit);
  ~TeardownBound();  // disarms it
  TeardownBound(const TeardownBound&) = delete;
  TeardownBound& operator=(const TeardownBound&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable disarmed_signal_;
  bool disarmed_ = false;
  std::thread watch_;
};

}  // namespace mcnc::process
