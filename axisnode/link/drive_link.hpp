#pragma once
// The axis node's CAN side: one CiA 402 drive behind a CanBus. A receive thread keeps what the
// bus said (boot-up, heartbeats, EMCY, this node's TPDO; for the SYNC producer, which other
// nodes sent their RPDO since the last SYNC) and wakes the cyclic loop. In lockstep the SYNC
// producer sends SYNC only after every node of the bus has sent its RPDO for the cycle, so the
// drives step in step.
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/cia402/node_startup.hpp"
#include "canopen/frames.hpp"
#include "canopen/sync_schedule.hpp"
#include "common/can/can_bus.hpp"
#include "common/process/process_node.hpp"

#include <atomic>
#include <bitset>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace mcnc::axisnode {

struct TpdoSample {
  canopen::TxPdoCsp pdo{};
  std::uint64_t count = 0;           // complete answers so far (TPDO1, and TPDO2 when mapped)
  std::int32_t velocity_actual = 0;  // 0x606C from TPDO2, counts/s (when mapped)
  std::int32_t following_error_actual = 0;  // 0x60F4 from TPDO2, counts (when mapped)
  std::int16_t torque_actual = 0;  // 0x6077 from TPDO2, per mille of rated torque (when mapped)
};

// What the node sends its drive each cycle. `mode` and `target_velocity_counts` go out only
// when the PDO layout carries them (set_pdo_layout).
struct DriveCommand {
  std::uint16_t controlword = 0;
  std::int32_t target_counts = 0;
  std::int32_t target_velocity_counts = 0;
  std::int8_t mode = 8;
};

class DriveLink {
 public:
  // `sync_producer`: this node sends the bus's SYNC, in lockstep once the RPDO1 of each of
  // `other_nodes` (the bus's other nodes) is seen.
  DriveLink(std::unique_ptr<can::CanBus> bus, std::uint8_t node_id, bool sync_producer,
            std::vector<std::uint8_t> other_nodes, process::Wakeup& wakeup);
  ~DriveLink();
  DriveLink(const DriveLink&) = delete;
  DriveLink& operator=(const DriveLink&) = delete;

  // The node's start-up by this master (canopen::NodeStartup: reset communication, boot-up,
  // device type, heartbeat time, PDO mapping, mode of operation, NMT start). nullopt when the
  // node is started; otherwise why not, naming the object a refused SDO was about.
  std::optional<std::string> bring_up(const canopen::NodeStartupConfig& config,
                                      std::chrono::milliseconds timeout);
  // The PDO layout, set before bring_up(): `with_mode` RPDO1/TPDO1 carry the modes of operation
  // and its display (canopen::spindle_pdos, homing_axis_pdos), `with_velocity` RPDO2 the target
  // velocity (a spindle).
  void set_pdo_layout(bool with_mode, bool with_velocity) noexcept {
    with_mode_.store(with_mode);
    with_velocity_.store(with_velocity);
  }
  void send_rpdo(const DriveCommand& command) noexcept;
  void send_sync(bool timed = false) noexcept;
  void send_nmt(canopen::NmtCommand command) noexcept;

  // Realtime SYNC production: a thread of its own sends SYNC at the schedule's fixed offset
  // inside each cycle, whatever the cyclic loop is doing (a late wake-up skips, never bursts).
  // Stops with stop_sync_timer() or the link.
  void start_sync_timer(const canopen::SyncSchedule& schedule);
  void stop_sync_timer();
  // TPDO2 as the start-up mapped it (0x606C, then 0x60F4, then 0x6077): set before
  // bring_up(). An answer to a SYNC counts as complete once both TPDOs are in.
  void set_tpdo2(bool velocity_actual, bool following_error, bool torque = false) noexcept {
    tpdo2_velocity_.store(velocity_actual);
    tpdo2_following_error_.store(following_error);
    tpdo2_torque_.store(torque);
  }
  [[nodiscard]] bool sync_timer_running() const noexcept { return sync_thread_.joinable(); }
  [[nodiscard]] std::uint64_t syncs_skipped() const noexcept { return syncs_skipped_.load(); }
  // How late each timed SYNC went out (ns after its due time), the last kLatenessRecords of
  // them in order; read after stop_sync_timer() (benchmarks).
  static constexpr std::size_t kLatenessRecords = 1U << 14;
  [[nodiscard]] std::vector<std::int64_t> sync_lateness() const;

  // One cycle on the bus. Realtime (`lockstep` false): the RPDO goes out, applied by the drive
  // at the next SYNC; the producer sends that SYNC here only when no SYNC timer runs (a lockstep
  // run winding down in real time). Lockstep:
  // RPDO; the producer sends SYNC once every node's RPDO of the cycle is seen; then every node
  // waits for its drive's answer to that SYNC (TPDO count past `tpdos_seen`). A lockstep wait never
  // gives up on its own, which would make results depend on load: it ends when `abandon()` says so
  // (stop, E-stop, owner gone), and logs when it has waited longer than `slow`.
  void exchange(const DriveCommand& command, bool lockstep, std::uint64_t tpdos_seen,
                const std::function<bool()>& abandon, std::chrono::milliseconds slow);

  [[nodiscard]] TpdoSample tpdo() noexcept;
  [[nodiscard]] std::uint64_t malformed_count() const noexcept;
  [[nodiscard]] std::uint64_t emcy_count() const noexcept { return emcys_.load(); }
  // The error code of the last EMCY (0: none yet).
  [[nodiscard]] std::uint16_t last_emcy() const noexcept { return last_emcy_.load(); }
  // The bus went bus off (an error frame said so; SocketCAN).
  [[nodiscard]] bool bus_off() const noexcept { return bus_off_.load(); }
  // Heartbeats of this node received so far (any NMT state).
  [[nodiscard]] std::uint64_t heartbeats() const noexcept { return heartbeats_.load(); }

 private:
  void receive_loop();
  // Lockstep waits (false on timeout).
  bool wait_other_rpdos(std::chrono::milliseconds timeout);
  bool wait_tpdo_after(std::uint64_t tpdos_seen, std::chrono::milliseconds timeout);

  std::unique_ptr<can::CanBus> bus_;
  std::uint8_t node_id_;
  bool sync_producer_;
  std::vector<std::uint8_t> other_nodes_;
  process::Wakeup& wakeup_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> bootups_{0};
  std::atomic<std::uint64_t> heartbeats_{0};
  std::atomic<bool> bus_off_{false};
  std::atomic<std::uint16_t> last_emcy_{0};
  // While bring_up() runs: this node's SDO responses and heartbeats, for the start-up
  // (guarded by the wakeup's lock).
  bool starting_ = false;
  std::deque<canopen::CanFrame> startup_frames_;
  std::atomic<std::uint64_t> emcys_{0};
  std::atomic<std::uint64_t> malformed_{0};
  std::atomic<std::uint64_t> tpdo_count_{0};
  std::atomic<std::uint16_t> tpdo_statusword_{0};
  std::atomic<std::int32_t> tpdo_position_{0};
  std::atomic<std::int8_t> tpdo_mode_display_{0};
  // The PDO layout: set before bring_up(), read by the receive thread.
  std::atomic<bool> with_mode_{false};
  std::atomic<bool> with_velocity_{false};
  std::atomic<bool> tpdo2_velocity_{false};
  std::atomic<bool> tpdo2_following_error_{false};
  std::atomic<bool> tpdo2_torque_{false};
  std::uint64_t tpdo1_count_ = 0;  // guarded by the wakeup's lock
  std::uint64_t tpdo2_count_ = 0;
  std::atomic<std::int32_t> tpdo2_velocity_value_{0};
  std::atomic<std::int32_t> tpdo2_following_error_value_{0};
  std::atomic<std::int16_t> tpdo2_torque_value_{0};
  // RPDOs seen from other nodes since the last SYNC (guarded by the wakeup's lock).
  std::bitset<128> rpdo_seen_;
  std::uint8_t sync_counter_ = 0;
  std::thread thread_;
  std::thread sync_thread_;
  std::atomic<bool> sync_stop_{false};
  std::atomic<std::uint64_t> syncs_skipped_{0};
  std::vector<std::int64_t> sync_late_ns_;  // a ring, written by the SYNC thread only
  std::uint64_t sync_late_count_ = 0;
};

}  // namespace mcnc::axisnode
