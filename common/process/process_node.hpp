#pragma once
// What every mcnc process that speaks DDS has: its participant, its ProcessState announcement,
// the run control from mcnc-launch, the alarm writer, and one wake-up that DDS callbacks and
// other receive threads signal so that the cyclic loop can wait for "something arrived".
#include "common/operator/operator_admission.hpp"
#include "common/operator/operator_inbox.hpp"
#include "common/process/wakeup.hpp"
#include "idl/dds_participant.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace mcnc::config {
struct MachineConfig;
}

namespace mcnc::process {

// The DDS domain: MCNC_DOMAIN when set, else the machine file's.
int resolve_domain(const config::MachineConfig& machine);
// A process's DDS implementation: what the machine file names for it (its own entry, else the
// machine's `middleware`), else MCNC_MIDDLEWARE, else the built-in default.
dds::Middleware resolve_middleware(const config::MachineConfig& machine,
                                   const std::string& process);

// The latest run control, readable without locks from the cyclic loop.
struct RunControlView {
  std::uint64_t generation = 0;
  RunCommand command = RUN_NONE;
  ClockKind clock = LOCKSTEP_CLOCK;
  // Cycle 0 on this process's CLOCK_MONOTONIC: the run's start in machine time plus its host's
  // clock offset (0 on one host).
  std::int64_t start_ns = 0;
  bool pace = false;
};

// The host a launcher started this process on (MCNC_HOST), empty when the machine runs on one
// host. Such a process keeps machine time by its host's HostClock (launch/machine_clock.hpp).
std::string resolve_host();

class ProcessNode {
 public:
  // `clock` chooses the cyclic writers' heartbeat (dds::CyclicClock); no `middleware`:
  // MCNC_MIDDLEWARE, else the default.
  // `security`: its identity on a secured machine (process::resolve_security_or_exit).
  ProcessNode(int domain, std::string name, dds::CyclicClock clock = dds::CyclicClock::realtime,
              std::optional<dds::Middleware> middleware = std::nullopt,
              dds::LocalTransport local = dds::LocalTransport::shared_memory,
              std::optional<security::IdentityFiles> security = std::nullopt);
  ProcessNode(const ProcessNode&) = delete;
  ProcessNode& operator=(const ProcessNode&) = delete;

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  dds::Participant& participant() noexcept { return participant_; }
  Wakeup& wakeup() noexcept { return wakeup_; }

  void announce(ProcessPhase phase, std::uint64_t cycle = 0, const std::string& detail = {});
  // The end work is done: announces PHASE_STOPPED and arms the exit deadline
  // (kStopToExitLimit, common/process/exit_deadline.hpp) against a DDS teardown that hangs;
  // its exit code says whether this process had raised alarms.
  void announce_stopped();
  [[nodiscard]] RunControlView run_control() const noexcept;
  // The machine clock: true once this process's host has announced its offset against machine
  // time, or at once when the machine runs on one host (resolve_host() empty).
  [[nodiscard]] bool machine_clock_known() const noexcept { return clock_known_.load(); }
  // This host's CLOCK_MONOTONIC minus machine time, as last announced.
  [[nodiscard]] std::int64_t clock_offset_ns() const noexcept { return clock_offset_ns_.load(); }
  [[nodiscard]] const std::string& host() const noexcept { return host_; }
  // A peer that leaves may be leaving because the run ends: its STOP and ours were sent
  // together but may arrive in either order. True when STOP (or a stop signal) arrives within
  // `grace`; the caller then ends instead of raising an alarm.
  bool stop_arrives_within(std::chrono::milliseconds grace);
  // Raises an alarm from this process: copies it into a fixed-size queue and returns; a thread
  // of this node publishes it (sequence numbered) and logs it. Safe in the per-cycle path: no
  // allocation, no blocking, no logging there. One thread raises alarms. Text longer than the
  // record is cut; a full queue drops the alarm and counts it in alarms_lost(). A program
  // alarm says where: `file` (nullptr: none), `line` and `column` (0: not known).
  bool raise_alarm(std::uint32_t number, const char* text, std::uint64_t cycle, int channel = 0,
                   int axis = 0, int line = 0, int column = 0, const char* file = nullptr) noexcept;
  [[nodiscard]] std::uint64_t alarms_lost() const noexcept { return alarms_lost_.load(); }
  // This process serves the operator commands of `scope`: from now on each one it serves is
  // taken into its OperatorInbox or refused (operator_admission.hpp) as it arrives, and answered
  // on OperatorAnswer either way. A process that serves none ignores them. Call before it
  // announces READY; once only.
  void serve_operator_commands(OperatorScope scope, AdmissionLimits limits);
  // The oldest operator command due at `cycle` of the current run (OperatorInbox); `cycle` is
  // also the machine's cycle that arriving commands are judged by. Short lock, no allocation:
  // callable from the cyclic loop.
  std::optional<OperatorRequest> take_operator_request(std::uint64_t cycle) noexcept;
  [[nodiscard]] std::uint64_t operator_requests_refused() const noexcept {
    return operator_refused_.load();
  }
  ~ProcessNode();

 private:
  std::string name_;
  dds::Participant participant_;
  Wakeup wakeup_;
  dds::Writer<ProcessState> state_writer_;
  dds::Writer<Alarm> alarm_writer_;
  std::atomic<std::uint64_t> alarm_seq_{0};
  std::atomic<std::uint64_t> rc_generation_{0};
  std::atomic<int> rc_command_{RUN_NONE};
  std::atomic<int> rc_clock_{LOCKSTEP_CLOCK};
  std::atomic<std::int64_t> rc_start_ns_{0};
  std::atomic<bool> rc_pace_{false};
  dds::Reader<RunControl> run_control_reader_;
  void on_operator_command(const OperatorCommand& command);
  OperatorInbox operator_inbox_;  // under wakeup_'s lock
  std::atomic<std::uint64_t> operator_refused_{0};
  std::atomic<std::uint64_t> operator_cycle_{0};  // the last cycle taken from the inbox
  // Set once by serve_operator_commands, before `serving_`.
  OperatorScope operator_scope_;
  AdmissionLimits admission_limits_;
  std::optional<dds::Writer<OperatorAnswer>> answer_writer_;
  std::atomic<bool> serving_{false};
  dds::Reader<OperatorCommand> operator_reader_;
  std::string host_;
  std::atomic<bool> clock_known_{false};
  std::atomic<std::int64_t> clock_offset_ns_{0};
  std::optional<dds::Reader<HostClock>> host_clock_reader_;

  struct AlarmRecord {
    std::uint32_t number = 0;
    std::array<char, 192> text{};
    std::uint64_t cycle = 0;
    int channel = 0;
    int axis = 0;
    int line = 0;
    int column = 0;
    std::array<char, 128> file{};
  };
  void publish_alarms();
  static constexpr std::size_t kAlarmSlots = 64;
  std::array<AlarmRecord, kAlarmSlots> alarm_slots_{};
  std::atomic<std::uint64_t> alarm_head_{0};  // written by the raising thread
  std::atomic<std::uint64_t> alarm_tail_{0};  // written by the publishing thread
  std::atomic<std::uint64_t> alarms_lost_{0};
  std::atomic<std::uint64_t> alarm_signal_{0};  // bumped by a raise and by shutdown
  std::atomic<bool> alarm_stop_{false};
  std::thread alarm_thread_;
};

}  // namespace mcnc::process
