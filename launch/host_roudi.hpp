#pragma once
// The host's iceoryx RouDi, for a machine with processes on Cyclone DDS: their cyclic samples
// travel through its shared memory, and without it their participants could not start. RouDi is
// one per host, shared by every machine and domain on it (each domain has its own iceoryx
// service name, idl/cyclonedds_participant.cpp).
#include "common/clock/cycle_clock.hpp"
#include "launch/child_process.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::config {
struct MachineConfig;
}

namespace mcnc::launch {

// The processes of a machine that speak DDS ("launch" and "status" among them), by name.
std::vector<std::string> dds_process_names(const config::MachineConfig& machine, bool with_hmi);
// True when any of them but the launcher runs on Cyclone DDS (and so needs RouDi).
bool needs_roudi(const config::MachineConfig& machine, bool with_hmi);

// iceoryx's RouDi configuration (TOML) for `processes` DDS processes: one segment whose pools
// hold every cyclic sample of their histories and queues, with room to spare.
std::string roudi_config(std::size_t processes);

// RouDi removes a process whose keep-alive it has not handled for 1.5 s. Its work is small and
// bounded (registrations and port requests at start-up, keep-alives), so it runs above
// everything of the host's: above ordinary load, which starved it at a lockstep machine's
// start beside a CPU hog, and above a realtime machine's processes and their cycle threads
// (up to clock::kSyncPriority).
inline constexpr int kRoudiPriority = clock::kSyncPriority + 1;

class HostRoudi {
 public:
  // Uses the RouDi that answers, once it has registered a process (mcnc-roudi-check, 5 s at
  // most), and warns when it runs below SCHED_FIFO kRoudiPriority. Else, unless
  // `must_be_running`, starts iox-roudi at that priority (where permitted) with a configuration
  // sized for `processes` and waits until it answers. Throws std::runtime_error saying why when
  // none answers, or the one that answers registers no process: nothing of the machine may
  // start then.
  HostRoudi(std::size_t processes, bool must_be_running);
  // Stops the RouDi it started (SIGTERM, SIGKILL after 5 s): call it after the machine's
  // processes are gone, since RouDi ends the processes still registered with it.
  ~HostRoudi();
  // The same stop, now (from any thread; once).
  void stop() noexcept;
  HostRoudi(const HostRoudi&) = delete;
  HostRoudi& operator=(const HostRoudi&) = delete;

  [[nodiscard]] bool started() const noexcept { return child_.has_value(); }

 private:
  std::optional<ChildProcess> child_;
  std::string config_path_;
};

}  // namespace mcnc::launch
