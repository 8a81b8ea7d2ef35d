#pragma once
// What a launcher starts for a machine, and in which order (docs/operations.md): each bus's
// drive simulator first (they answer the nodes' NMT), then the axis nodes, the channels, the
// PLC, and the operator station when asked for; with each its command line and trace part. On a
// machine of several hosts (`hosts:`) a host's launcher starts only what that host runs, and
// still waits for every DDS process of the machine. Pure: the machine and the options in, the
// plan out.
#include "common/config/machine_config.hpp"
#include "launch/launcher.hpp"

#include <cstddef>
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

// A secured machine of more DDS processes than this starts them in waves of kStartWave
// (decision 112): every pair of participants authenticates, and handshakes all begun at once
// queue behind each other for longer than Cyclone DDS's one-second resend, which then breaks
// them. The twin turret (15) and every smaller or unsecured machine start all at once.
inline constexpr std::size_t kUnstaggeredDdsProcesses = 16;
inline constexpr std::size_t kStartWave = 8;

// The plan's children in the waves they start in, as indices into plan.children in start
// order: the first wave holds every child that speaks no DDS (the drive simulators) and the
// first kStartWave DDS processes, each later wave the next kStartWave. One wave, every child,
// unless `secured` and the machine has more than kUnstaggeredDdsProcesses DDS processes.
std::vector<std::vector<std::size_t>> start_waves(const LaunchPlan& plan, bool secured);

}  // namespace mcnc::launch
