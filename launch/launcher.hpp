#pragma once
// mcnc-launch's behaviour, shared with `mcnc run`: start every process of a machine, wait until
// all are discovered, start the run (lockstep or realtime), supervise, stop. A child that exits
// unexpectedly E-stops the machine: channels reset, drives quick stop, then a clean shutdown
// and a non-zero result.
#include "common/clock/cycle_clock.hpp"
#include "common/config/machine_config.hpp"
#include "idl/topics.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace mcnc::launch {

// A realtime machine whose processes need more CPU than the host has starves every ordinary
// process, the launcher's own middleware threads among them. So in realtime the launcher's
// supervising thread runs above the machine and its RouDi (common/clock, host_roudi.hpp), and
// when no channel has been heard for kMachineSilentLimit it E-stops the machine: its run
// timeout, an interrupt and the stop that follows still work on such a host.
inline constexpr int kSupervisorPriority = clock::kSyncPriority + 2;
inline constexpr std::chrono::seconds kMachineSilentLimit{5};
// How long the processes may take to answer the scripted operator's commands (they answer as a
// command arrives, not at its cycle).
inline constexpr std::chrono::seconds kScriptAnswerLimit{5};

// An operator command the launcher sends at a given cycle (`mcnc run --operator`): a scripted
// operator, deterministic in lockstep.
struct ScriptedOperatorCommand {
  std::uint64_t cycle = 0;
  std::uint32_t channel = 0;  // 0: the whole machine
  OperatorAction action = OP_NONE;
  double value = 0.0;  // an override, in percent
};

struct LaunchOptions {
  std::string machine_path;
  std::map<std::string, std::string> programs;  // channel name -> program file
  ClockKind clock = LOCKSTEP_CLOCK;
  bool pace = false;       // lockstep paced to real time
  std::string trace_path;  // merged trace; empty: no trace
  int trace_pos_every = 10;
  std::string bin_dir;  // where the mcnc-* executables are
  std::string log_level;
  double start_timeout_s = 60.0;  // discovery and drive bring-up
  double run_timeout_s = 0.0;     // 0: no limit
  // Extra arguments of each bus's mcnc-drivesim (fault injection), by bus name.
  std::map<std::string, std::vector<std::string>> drivesim_args;
  std::string program_dir;    // overrides the machine file's program_dir for every channel
  std::string retained_file;  // overrides the machine file's retained_file
  // Sent with the run start, each taking effect at its cycle. The run goes on past alarms
  // until the last of them has taken effect; then alarms raised before the last reset no
  // longer stop it (they still make the result a failure).
  std::vector<ScriptedOperatorCommand> operator_script;
  // The operator station: mcnc-hmi on this HOST:PORT beside the machine ("": none). It is
  // not part of the run: it starts with it and stops at its end, and its exit stops nothing.
  std::string hmi_listen;
  bool manual_start = false;  // the channels wait for CYCLE START
  // The host's iceoryx RouDi serves the machine's shared memory: when it stops answering (killed,
  // or stopped under the machine), the machine is E-stopped like after a lost process, since
  // nothing would then clean up after a process that dies.
  bool watch_roudi = false;
  // A machine of several hosts (`hosts:`): the host whose processes this launcher starts ("":
  // every process, here). The first host's launcher coordinates: it starts, E-stops and stops
  // the run, and merges the trace from every host's parts (a directory the hosts share). Another
  // host's launcher follows the run control the coordinator sends, supervises its own
  // processes, and raises alarm 3001 for one that is lost, which makes the coordinator E-stop
  // the machine.
  std::string host;
};

struct ChannelProgress {
  std::string name;
  bool has_program = false;
  ::mcnc::ChannelState state = CH_RESET;
  std::uint32_t block = 0;
  std::uint32_t block_total = 0;
  std::int32_t line = 0;
  std::uint32_t alarms = 0;
  bool ended = false;
  std::int32_t end_code = -1;
  std::uint64_t cycle = 0;
  std::uint64_t run_start_cycle = 0;  // as the channel reports it
  std::uint64_t end_cycle = 0;        // as the channel reports it
  bool seen_running = false;
};

struct LaunchResult {
  int exit_code = 1;  // 0: every program ended without alarm
  std::uint64_t cycles = 0;
  std::vector<ChannelProgress> channels;
  std::vector<std::string> alarms;  // "src number text"
  std::string failure;              // why it did not end cleanly
};

const char* to_string(::mcnc::ChannelState state) noexcept;

class Launcher {
 public:
  Launcher(config::MachineConfig machine, LaunchOptions options);
  // Runs the machine to the end. `on_progress` is called about ten times a second;
  // `on_result` with the result once the run's processes are gone and its trace is written,
  // before the launcher's own DDS participant is deleted.
  LaunchResult run(const std::function<void(const std::vector<ChannelProgress>&)>& on_progress,
                   const std::function<void(const LaunchResult&)>& on_result = {});

 private:
  config::MachineConfig machine_;
  LaunchOptions options_;
};

}  // namespace mcnc::launch
