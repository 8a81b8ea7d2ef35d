#pragma once
// A launcher's part in DDS Security (docs/operations.md, "Security"): which identities the
// processes it starts present, and the check of their files before anything starts.
#include "common/config/machine_config.hpp"

#include <string>
#include <vector>

namespace mcnc::launch {

// On a machine of several hosts, a launcher other than the first host's follows the run.
[[nodiscard]] bool is_follower(const config::MachineConfig& machine, const std::string& host);
// The name a launcher's participant, and so its identity, has: "launch", or "launch-<host>"
// for a follower.
[[nodiscard]] std::string launcher_identity(const config::MachineConfig& machine,
                                            const std::string& host);

// The identities of the DDS processes a launcher on `host` ("": one host runs all) starts, its
// own first.
[[nodiscard]] std::vector<std::string> started_identities(const config::MachineConfig& machine,
                                                          const std::string& host, bool with_hmi);

// Before anything starts: on an unsecured machine, says so once on stderr and returns true; on
// a secured one, checks the files of every identity the launcher starts and returns false after
// printing the first problem (it names the file), true when all are good.
bool check_machine_security(const config::MachineConfig& machine, const std::string& host,
                            bool with_hmi);

}  // namespace mcnc::launch
