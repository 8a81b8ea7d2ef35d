#pragma once
// What the axis node's cycle asks of its drive, whatever carries it, in the manner of a
// ros2_control hardware interface: a lifecycle outside the cycle (configure: the drive's
// start-up; activate: the cyclic exchange begins; deactivate: the drive is left disabled), and
// in each cycle read() then write(). read() and write() are the cyclic path: noexcept, no
// allocation, a status instead of an exception. read() never waits on a lock another thread
// holds; write() waits only in lockstep, for the drive's answer to this cycle.
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/cia402/node_startup.hpp"
#include "canopen/sync_schedule.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace mcnc::axisnode {

enum class DriveLifecycle : std::uint8_t {
  unconfigured,  // not brought up yet
  inactive,      // started (NMT operational), no cyclic exchange
  active,        // read() and write() run
  failed,        // the start-up failed (configure's error says why)
};

enum class DriveStatus : std::uint8_t {
  ok,
  error,      // the bus is off, or the interface is not active: nothing reached the drive
  abandoned,  // write() in lockstep: the wait for the bus was given up (abandon() said so)
};

// What read() gives the cycle: the drive's last complete answer and the link's health.
struct DriveSample {
  canopen::DriveFeedback feedback;
  std::uint64_t answers = 0;  // complete answers (every TPDO of a SYNC) so far
  bool fresh = false;         // an answer came since the previous read()
  std::uint64_t heartbeats = 0;
  std::uint16_t last_emcy = 0;  // error code of the last EMCY, 0: none yet
  bool bus_off = false;
  // SYNC frames this node did not send, since activate() (the SYNC producer alone receives
  // SYNC): another SYNC producer on the bus.
  std::uint64_t foreign_syncs = 0;
};

// A timed SYNC that went out (realtime SYNC producer): its index (the machine cycle it belongs
// to), when it was due and how late it went out, on this host's CLOCK_MONOTONIC.
struct SentSync {
  std::uint64_t index = 0;
  std::int64_t due_ns = 0;
  std::int64_t late_ns = 0;
};

// How the cyclic exchange runs once active.
struct DriveActivation {
  // Lockstep: write() waits for the drive's answer to this cycle (and the SYNC producer, before
  // its SYNC, for every other node's RPDO). Changed per cycle with set_lockstep().
  bool lockstep = false;
  // Realtime SYNC producer: SYNC from a timer of its own at this schedule.
  std::optional<canopen::SyncSchedule> sync_timer;
  // A lockstep wait ends when this says so (stop, E-stop, owner gone); never on its own, which
  // would make results depend on load. Called on the cycle thread: must not allocate.
  std::function<bool()> abandon = [] { return false; };
  // A lockstep wait longer than this is logged (once per wait).
  std::chrono::milliseconds slow{2000};
};

class DriveInterface {
 public:
  virtual ~DriveInterface() = default;

  // --- Lifecycle, outside the cycle (may allocate, may block).
  // The drive's start-up as `config` says, with its PDO layout; nullopt when the drive is started
  // (inactive), otherwise why not (failed).
  virtual std::optional<std::string> configure(const canopen::NodeStartupConfig& config,
                                               std::chrono::milliseconds timeout) = 0;
  virtual void activate(const DriveActivation& activation) = 0;
  // The cyclic exchange ends: `last` goes out once (e.g. disable voltage), the drive is put in
  // pre-operational.
  virtual void deactivate(const canopen::DriveCommand& last) noexcept = 0;
  [[nodiscard]] virtual DriveLifecycle lifecycle() const noexcept = 0;

  // --- The cycle.
  // The drive's state as of now into state().
  virtual DriveStatus read(std::int64_t time_ns, std::int64_t period_ns) noexcept = 0;
  [[nodiscard]] virtual const DriveSample& state() const noexcept = 0;
  // The command write() sends; set by the cycle between read() and write().
  [[nodiscard]] virtual canopen::DriveCommand& command() noexcept = 0;
  virtual DriveStatus write(std::int64_t time_ns, std::int64_t period_ns) noexcept = 0;
  virtual void set_lockstep(bool lockstep) noexcept = 0;
};

}  // namespace mcnc::axisnode
