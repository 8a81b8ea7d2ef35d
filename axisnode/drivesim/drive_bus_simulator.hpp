#pragma once
// Simulated CiA 402 drives of one CAN bus, driven only by the frames they receive: NMT,
// RPDO1 (latched) and SYNC (applies the latched RPDO, steps each drive by one cycle, answers
// with TPDO1). Deterministic: the same frames give the same positions, whatever the clock.
#include "axisnode/cia402/canopen_frames.hpp"
#include "axisnode/cia402/cia402_state.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mcnc::drivesim {

struct DriveParams {
  std::uint8_t node_id = 1;
  double counts_per_unit = 10000.0;
  double time_constant_s = 0.004;   // first-order position loop (following error = v * tau)
  double max_velocity = 500.0;      // units/s
  double quick_stop_decel = 5000.0; // units/s^2
  double initial_position = 0.0;    // units
};

// One drive in cyclic synchronous position mode.
class SimulatedDrive {
public:
  SimulatedDrive(const DriveParams& params, double cycle_s) noexcept;
  [[nodiscard]] std::uint8_t node_id() const noexcept;
  [[nodiscard]] canopen::NmtState nmt_state() const noexcept;
  [[nodiscard]] cia402::State state() const noexcept;
  [[nodiscard]] double position() const noexcept;  // units
  [[nodiscard]] double velocity() const noexcept;  // units/s
  void on_nmt(canopen::NmtCommand command) noexcept;
  void on_rpdo(const canopen::RxPdoCsp& pdo) noexcept;  // latched until the next SYNC
  // One cycle: apply the latched controlword/target, move; the TPDO to answer with.
  canopen::TxPdoCsp on_sync() noexcept;
  // ...
};

class DriveBusSimulator {
public:
  DriveBusSimulator(const std::vector<DriveParams>& drives, double cycle_s);
  // Boot-up messages every drive sends at power on (heartbeat with state bootup).
  std::size_t power_on(std::span<canopen::CanFrame> out) noexcept;
  // Handles one received frame; writes the frames to send into `out` (boot-up after an NMT
  // reset, TPDOs after SYNC for operational drives) and returns how many.
  std::size_t handle(const canopen::CanFrame& in, std::span<canopen::CanFrame> out) noexcept;
  [[nodiscard]] const SimulatedDrive* find(std::uint8_t node_id) const noexcept;
  [[nodiscard]] unsigned long malformed_count() const noexcept;
  // ...
};

} // namespace mcnc::drivesim
