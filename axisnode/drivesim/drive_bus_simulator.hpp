#pragma once
// Simulated CiA 402 drives of one CAN bus, driven only by the frames they receive: NMT,
// RPDO1 (latched) and SYNC (applies the latched RPDO, steps each drive by one cycle, answers
// with TPDO1). Deterministic: the same frames give the same positions, whatever the clock.
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/cia402_state.hpp"
#include "canopen/frames.hpp"
#include "canopen/sdo_server.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mcnc::drivesim {

// The drives of one bus. Each answers SDO requests from its object dictionary, sends its
// TPDOs as mapped (while valid) and its heartbeat every producer time. Frames for node ids it
// does not own, and frames a drive does not consume (TPDOs, heartbeats, EMCYs of other
// nodes), are ignored. An NMT, SYNC or RPDO1 frame
// it would consume but that does not decode (wrong length, unknown NMT command, SYNC counter
// outside 1..240) is dropped and counted in malformed_count(). Outputs that do not fit in
// `out` are dropped (the state still advances); size `out` for kFramesPerDrive per drive.
class DriveBusSimulator {
 public:
  // Throws std::invalid_argument on a node id outside 1..127 or used twice.
  DriveBusSimulator(const std::vector<DriveParams>& drives, double cycle_s);
  // Each drive's SDO server refers to that drive's objects: not copied, not moved.
  DriveBusSimulator(const DriveBusSimulator&) = delete;
  DriveBusSimulator& operator=(const DriveBusSimulator&) = delete;
  // Frames one SYNC may produce per drive: an EMCY, TPDO1, TPDO2 and a heartbeat.
  static constexpr std::size_t kFramesPerDrive = 4;
  // Fault injection: the drive of `node` has `fault` at its SYNC number `at_sync`. False for a
  // node not on this bus.
  bool schedule_fault(std::uint8_t node, DriveFault fault, std::uint64_t at_sync) noexcept;
  // Fault injection: every SDO access to `index` of `node` is refused (device state). False
  // for a node not on this bus.
  bool refuse_sdo(std::uint8_t node, std::uint16_t index) noexcept;
  // Boot-up messages every drive sends at power on (heartbeat with state bootup).
  std::size_t power_on(std::span<canopen::CanFrame> out) noexcept;
  // Handles one received frame; writes the frames to send into `out` (boot-up after an NMT
  // reset, TPDOs after SYNC for operational drives) and returns how many.
  std::size_t handle(const canopen::CanFrame& in, std::span<canopen::CanFrame> out) noexcept;
  // The heartbeats due at `now_us` (wall clock) of drives an NMT command took out of
  // operational (SimulatedDrive::heartbeat_out_of_operation); how many it wrote to `out`.
  std::size_t heartbeats_out_of_operation(std::uint64_t now_us,
                                          std::span<canopen::CanFrame> out) noexcept;
  [[nodiscard]] const SimulatedDrive* find(std::uint8_t node_id) const noexcept;

  // Lockstep over UDP: a real bus shows a frame to every node at once, UDP multicast on
  // loopback hands it to one socket after another, so a SYNC may overtake an RPDO that the
  // SYNC producer has already seen. The shell holds a SYNC until every drive that is being fed
  // has each RPDO for this cycle that it received in the cycle before (a spindle's RPDO1 and
  // RPDO2: the one may be in while the other is overtaken).
  [[nodiscard]] bool rpdos_complete() const noexcept;
  // An RPDO that stopped coming (its node gone, or stopped) is no longer waited for until it
  // comes again.
  void stop_awaiting_silent_drives() noexcept;
  [[nodiscard]] unsigned long malformed_count() const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return drives_.size(); }

 private:
  static constexpr std::int16_t kNoDrive = -1;

  SimulatedDrive* find_mutable(std::uint8_t node_id) noexcept;
  std::size_t handle_nmt(const canopen::CanFrame& in, std::span<canopen::CanFrame> out) noexcept;
  std::size_t handle_sync(const canopen::CanFrame& in, std::span<canopen::CanFrame> out) noexcept;
  void handle_rpdo(const canopen::CanFrame& in, std::uint8_t node, std::size_t n) noexcept;

  std::size_t handle_sdo(const canopen::CanFrame& in, std::span<canopen::CanFrame> out) noexcept;
  std::vector<SimulatedDrive> drives_;
  std::vector<canopen::SdoServer> sdo_;            // one per drive, in the same order
  std::array<std::int16_t, 128> index_by_node_{};  // node id -> position in drives_
  unsigned long malformed_ = 0;
  // Per drive, a bit per RPDO (bit n: RPDO n+1): those received since the last SYNC, and
  // those received in the cycle before it (awaited in this one).
  std::vector<std::uint8_t> rpdos_got_;
  std::vector<std::uint8_t> rpdos_awaited_;
};

}  // namespace mcnc::drivesim
