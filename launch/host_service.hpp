#pragma once
// A host's launcher as a service, and a run asked of the services from any host
// (docs/operations.md "A machine across hosts", decision 52).
//
// `mcnc-launch MACHINE --host NAME --serve` stays up between runs. It announces itself
// (`service-<host>`) and, for each RunRequest, starts that host's launcher (`mcnc-launch
// MACHINE ARGS --host NAME`) in the asker's working directory, one run at a time, and answers
// with a RunOutcome: the launcher's exit code and what it printed (its last 64 KiB).
//
// `mcnc run MACHINE ARGS --services`, on any host, waits until every host's service has
// announced itself (the start-up time-out, then it names the silent hosts), asks for the run,
// waits for every host's outcome, prints the coordinator's output and ends with its exit code
// (1 when a follower's part failed and the coordinator's did not say so).
#include "launch/run_command.hpp"

namespace mcnc::launch {

int serve_host(const RunArguments& args);
int request_run(const RunArguments& args);

}  // namespace mcnc::launch
