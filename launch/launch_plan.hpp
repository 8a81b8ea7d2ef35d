#pragma once
// What a launcher starts for a machine, and in which order (docs/operations.md): each bus's
// drive simulator first (they answer the nodes' NMT), then the axis nodes, the channels, the
// PLC, and the operator station when asked for; with each its command line and trace part. On a
// machine of several hosts (`hosts:`) a host's launcher starts only what that host runs, and
// still waits for every DDS process of the machine. Pure: the machine and the options in, the
// plan out.
#include "common/config/machine_config.hpp"
#include "launch/launcher.hpp"

#include <string>
#include <vector>

namespace mcnc::launch {

inline constexpr const char* kHmiName = "hmi";  // the operator station's child

struct ChildSpec {
  std::string name;               // as logs, alarms and the trace name it
  std::vector<std::string> argv;  // argv[0]: the executable's path
};

struct LaunchPlan {
  std::vector<ChildSpec> children;  // in start order
  // The DDS processes the run waits for, on every host: their names as they announce.
  std::vector<std::string> dds_processes;
  // The trace parts the merge reads, in its order inside a cycle: channels, axes, the PLC.
  std::vector<std::string> trace_parts;
};

// The trace part of process `name` in `parts_dir`.
std::string trace_part(const std::string& parts_dir, const std::string& name);

// `parts_dir`: where the processes write their trace parts ("": no trace). `host`: the host
// whose processes to start ("": every process, a machine of one host).
LaunchPlan launch_plan(const config::MachineConfig& machine, const LaunchOptions& options,
                       const std::string& parts_dir, const std::string& host = "");

}  // namespace mcnc::launch
