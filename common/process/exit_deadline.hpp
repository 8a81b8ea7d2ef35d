#pragma once
// A bound on how long a process may take to leave once its end work is done. Fast DDS 2.9.1
// (Debian 12) now and then hangs for good while it deletes a participant whose peers leave at
// the same moment (docs/operations.md). A process that hangs there has done and reported its
// work, but the launcher could only kill it, and a kill cannot tell "hung after the work" from
// "killed before it": the run failed although nothing was wrong with it (docs/decisions.md 28).
#include <chrono>

namespace mcnc::process {

// The exit code of a process that left by its deadline: its end work was done, its DDS
// teardown was not.
inline constexpr int kExitTeardownHung = 3;

// The deadline the DDS processes arm when they announce their stop: an axis node lingers up to
// 2 s for its channels to go, and a participant is deleted in well under a second when nothing
// hangs.
inline constexpr std::chrono::milliseconds kStopToExitLimit{4000};

// Called once, after the end work (trace flushed, retained data saved, stop announced). If the
// process is still there `limit` later, it logs a warning and leaves at once with
// kExitTeardownHung, skipping every destructor still to run. A process that leaves in time
// never notices.
void arm_exit_deadline(std::chrono::milliseconds limit);

}  // namespace mcnc::process
