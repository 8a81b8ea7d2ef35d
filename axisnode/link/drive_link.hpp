#pragma once
// The axis node's CAN side: one CiA 402 drive behind a CanBus, as a DriveInterface. A receive
// thread keeps what the bus said (boot-up, heartbeats, EMCY, this node's TPDOs unpacked by the
// PDO layout the start-up wrote; for the SYNC producer, which other nodes sent their RPDO since
// the last SYNC), publishes it as one snapshot the cycle takes whole (a double buffer: read()
// neither locks nor waits for the receive thread) and wakes the cyclic loop. write() packs the
// command into the RPDOs by the same layout. In lockstep the SYNC producer sends SYNC only after
// every node of the bus has sent its RPDO for the cycle, so the drives step in step.
#include "axisnode/link/drive_interface.hpp"
#include "common/can/can_bus.hpp"
#include "common/cycle/double_buffer.hpp"
#include "common/process/wakeup.hpp"

#include <array>
#include <atomic>
#include <bitset>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <thread>
#include <vector>

namespace mcnc::axisnode {

class DriveLink final : public DriveInterface {
 public:
  // `sync_producer`: this node sends the bus's SYNC, in lockstep once the RPDO1 of each of
  // `other_nodes` (the bus's other nodes) is seen.
  DriveLink(std::unique_ptr<can::CanBus> bus, std::uint8_t node_id, bool sync_producer,
            std::vector<std::uint8_t> other_nodes, process::Wakeup& wakeup);
  ~DriveLink() override;
  DriveLink(const DriveLink&) = delete;
  DriveLink& operator=(const DriveLink&) = delete;

  // The start-up (canopen::NodeStartup: reset communication, boot-up, device type, heartbeat
  // time, the PDO layout of `config`, mode of operation, NMT start); a layout that cannot be
  // mapped (longer than a CAN frame) fails it, naming the PDO.
  std::optional<std::string> configure(const canopen::NodeStartupConfig& config,
                                       std::chrono::milliseconds timeout) override;
  void activate(const DriveActivation& activation) override;
  void deactivate(const canopen::DriveCommand& last) noexcept override;
  [[nodiscard]] DriveLifecycle lifecycle() const noexcept override { return lifecycle_; }

  DriveStatus read(std::int64_t time_ns, std::int64_t period_ns) noexcept override;
  [[nodiscard]] const DriveSample& state() const noexcept override { return state_; }
  [[nodiscard]] canopen::DriveCommand& command() noexcept override { return command_; }
  // Realtime (not lockstep): the RPDOs go out, applied by the drive at the next SYNC; the
  // producer sends that SYNC here only when no SYNC timer runs (a lockstep run winding down in
  // real time). Lockstep: the RPDOs; the producer sends SYNC once every node's RPDO of the cycle
  // is seen; then every node waits for its drive's answer to that SYNC (an answer newer than
  // the last read()).
  DriveStatus write(std::int64_t time_ns, std::int64_t period_ns) noexcept override;
  void set_lockstep(bool lockstep) noexcept override { lockstep_ = lockstep; }

  // Realtime SYNC production: a thread of its own sends SYNC at the schedule's fixed offset
  // inside each cycle, whatever the cyclic loop is doing (a late wake-up skips, never bursts).
  // Stops with stop_sync_timer(), deactivate() or the link.
  void start_sync_timer(const canopen::SyncSchedule& schedule);
  void stop_sync_timer();
  [[nodiscard]] bool sync_timer_running() const noexcept { return sync_thread_.joinable(); }
  [[nodiscard]] std::uint64_t syncs_skipped() const noexcept { return syncs_skipped_.load(); }
  // How late each timed SYNC went out (ns after its due time), the last kLatenessRecords of
  // them in order; read after stop_sync_timer() (benchmarks).
  static constexpr std::size_t kLatenessRecords = 1U << 14;
  [[nodiscard]] std::vector<std::int64_t> sync_lateness() const;
  // The machine's start on this host's clock, as the host's estimate of the machine clock is
  // refined: the timed SYNCs from the next one on follow it, by 1 % of the cycle a SYNC at most
  // (SyncSchedule::follow_start).
  void follow_machine_start(std::int64_t start_ns) noexcept { sync_start_ns_.store(start_ns); }
  // The latest timed SYNC that went out. False before the first.
  bool latest_sync(SentSync& out) const noexcept;

  // RPDO1 frames of the bus's other nodes seen so far: a stopping SYNC producer waits until
  // they stop (axisnode/node/drive_stop.hpp).
  [[nodiscard]] std::uint64_t other_nodes_rpdos() const noexcept { return other_rpdos_.load(); }

  [[nodiscard]] std::uint64_t malformed_count() const noexcept;
  [[nodiscard]] std::uint64_t emcy_count() const noexcept { return emcys_.load(); }

 private:
  // What the receive thread publishes, whole.
  struct Snapshot {
    canopen::DriveFeedback feedback;
    std::uint64_t answers = 0;
    std::uint64_t heartbeats = 0;
    std::uint16_t last_emcy = 0;
    bool bus_off = false;
    std::uint64_t foreign_syncs = 0;
  };

  void receive_loop();
  void on_tpdo(const can::CanFrame& frame, const canopen::PdoMapping& mapping,
               std::uint64_t& count);
  void publish();
  void send_rpdos() noexcept;
  void send_sync(bool timed = false) noexcept;
  // Lockstep: waits until arrived(timeout) holds, or abandon() says so (false).
  template <class Arrived>
  bool wait_lockstep(Arrived arrived, const char* what) noexcept;

  std::unique_ptr<can::CanBus> bus_;
  std::uint8_t node_id_;
  bool sync_producer_;
  std::vector<std::uint8_t> other_nodes_;
  process::Wakeup& wakeup_;
  // Set by configure() before the receive thread starts: read by it without a lock.
  canopen::PdoLayout layout_{};
  DriveLifecycle lifecycle_ = DriveLifecycle::unconfigured;
  DriveActivation activation_{};
  bool lockstep_ = false;

  // The cycle's side.
  DriveSample state_{};
  canopen::DriveCommand command_{};
  std::uint64_t answers_read_ = 0;  // state_.answers at the last read()

  // The receive thread's side: its own copy, published whole into snapshot_.
  Snapshot received_{};
  std::uint64_t tpdo1_count_ = 0;
  std::uint64_t tpdo2_count_ = 0;
  cycle::DoubleBuffer<Snapshot> snapshot_;
  // Complete answers so far, for the lockstep wait's condition (written under the wakeup's lock).
  std::atomic<std::uint64_t> answers_{0};
  std::atomic<bool> stop_{false};
  // Set by activate(), cleared by deactivate(): the receive thread counts foreign SYNCs and
  // watches the drive's NMT state only while the cyclic exchange runs (a boot-up heartbeat of
  // the start-up is no fault).
  std::atomic<bool> watching_{false};
  // The drive's heartbeat said it left NMT operational: a lockstep wait for its answer ends
  // (written under the wakeup's lock).
  std::atomic<bool> left_operational_{false};
  std::atomic<std::uint64_t> emcys_{0};
  std::atomic<std::uint64_t> other_rpdos_{0};
  std::atomic<std::uint64_t> malformed_{0};
  // While configure() runs: this node's SDO responses and heartbeats, for the start-up
  // (guarded by the wakeup's lock).
  bool starting_ = false;
  std::deque<can::CanFrame> startup_frames_;
  // RPDOs seen from other nodes since the last SYNC (guarded by the wakeup's lock).
  std::bitset<128> rpdo_seen_;
  std::uint8_t sync_counter_ = 0;
  std::thread thread_;
  std::thread sync_thread_;
  std::atomic<bool> sync_stop_{false};
  std::atomic<std::uint64_t> syncs_skipped_{0};
  std::vector<std::int64_t> sync_late_ns_;  // a ring, written by the SYNC thread only
  std::uint64_t sync_late_count_ = 0;
  std::atomic<std::int64_t> sync_start_ns_{0};
  // The latest SYNC sent, for latest_sync(): slots by index, the index stored last (a reader
  // would need the SYNC thread to lap the slots between two loads to read a torn record).
  static constexpr std::size_t kSentSlots = 8;
  std::array<std::atomic<std::int64_t>, kSentSlots> sent_due_ns_{};
  std::array<std::atomic<std::int64_t>, kSentSlots> sent_late_ns_{};
  std::atomic<std::uint64_t> sent_index_plus_one_{0};  // 0: none sent yet
};

}  // namespace mcnc::axisnode
