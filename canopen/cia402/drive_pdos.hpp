#pragma once
// The PDOs of a CiA 402 drive as this project maps them, and the drive-profile objects they
// carry. The layouts are canopen::PdoLayouts: the start-up writes them to the drive and the
// master packs and unpacks its cyclic frames by them (DriveCommand, DriveFeedback); the fixed
// shapes below them (RxPdoCsp, TxPdoCsp, RxPdoSpindle) are the same layouts' frames, for the
// simulated drive's tests and the benchmarks. Pure, no allocation.
#include "canopen/frames.hpp"
#include "canopen/pdo_layout.hpp"

#include <cstdint>
#include <optional>

namespace mcnc::canopen {

// The PDOs of an axis drive: RPDO1 controlword 0x6040 and target position 0x607A (CSP) or
// target velocity 0x60FF (CSV); TPDO1 statusword 0x6041 and position actual 0x6064; TPDO2, only
// when asked (it costs a frame per axis and cycle on the bus), velocity actual 0x606C and/or
// following error actual 0x60F4.
PdoLayout axis_pdos(bool velocity_mode, bool velocity_actual, bool following_error) noexcept;
// The PDOs of a spindle drive that switches between CSV (turning) and CSP (positioning,
// synchronisation) in operation, cycle by cycle: RPDO1 controlword 0x6040, target position
// 0x607A and modes of operation 0x6060 (7 bytes); RPDO2 target velocity 0x60FF; TPDO1
// statusword 0x6041, position actual 0x6064 and modes of operation display 0x6061 (7 bytes).
PdoLayout spindle_pdos() noexcept;
// The PDOs of an axis that homes at start-up (mode 6, then CSP): a spindle's RPDO1 and TPDO1
// (the modes of operation and its display travel with them), no RPDO2.
PdoLayout homing_axis_pdos() noexcept;
// An axis layout (axis_pdos, no TPDO2 objects of its own) with touch probe 1 (CiA 402 §
// touch probe function; docs/drives.md): RPDO1 adds the function 0x60B8 (8 bytes), TPDO1 the
// status 0x60B9 (8 bytes), TPDO2 the positive and negative edge positions 0x60BA and 0x60BB
// (8 bytes). One frame more per cycle, and only on the axes that have a probe.
void add_touch_probe(PdoLayout& layout) noexcept;
// An axis layout (axis_pdos) with the torque limit that G160 sets (docs/drives.md): RPDO2 the
// max torque 0x6072 (2 bytes), TPDO2 the torque actual value 0x6077 (2 bytes, after what it
// maps already), both per mille of the motor's rated torque. One frame more per cycle.
void add_torque_limit(PdoLayout& layout) noexcept;
// An axis layout with add_torque_limit's objects and cyclic synchronous torque (CST, mode 10)
// beside CSP, switched cycle by cycle: RPDO1 adds the modes of operation 0x6060 (7 bytes),
// TPDO1 its display 0x6061 (7 bytes), RPDO2 the target torque 0x6071 (per mille of the rated
// torque) and the max motor speed 0x6080 (rpm, CST's speed limit) after 0x6072 (8 bytes). No
// frame more than add_torque_limit's. Call it after add_torque_limit.
void add_torque_mode(PdoLayout& layout) noexcept;
// 0x6072 with no limit asked: 1000 % of the rated torque, above any drive's peak, so that the
// drive's own limit applies.
inline constexpr std::uint16_t kNoTorqueLimit = 10000;

// Touch probe 1's bits in its function 0x60B8 and status 0x60B9 (CiA 402): enable, sample the
// first event only, sample the positive / negative edge; the status says enabled and which
// edge's position is stored.
namespace touch_probe {
inline constexpr std::uint16_t kEnable = 1U << 0;
// 0x60B8 bit 1: latch every edge (continuous), not the first one only (G31.8).
inline constexpr std::uint16_t kContinuous = 1U << 1;
inline constexpr std::uint16_t kPositiveEdge = 1U << 4;
inline constexpr std::uint16_t kNegativeEdge = 1U << 5;
inline constexpr std::uint16_t kEnabled = 1U << 0;
inline constexpr std::uint16_t kPositiveStored = 1U << 1;
inline constexpr std::uint16_t kNegativeStored = 1U << 2;
// 0x60B9 bits 6-7 (user-defined in ETG.6010): in continuous mode, the edges latched, counted
// modulo 4, so that a master reading one position per SYNC sees an edge it missed.
inline constexpr int kEdgeCountShift = 6;
inline constexpr std::uint16_t kEdgeCountMask = 3U << kEdgeCountShift;
}  // namespace touch_probe

// What a master sends its drive in a cycle; an RPDO carries what its mapping names of it.
struct DriveCommand {
  std::uint16_t controlword = 0;              // 0x6040
  std::int32_t target_position = 0;           // 0x607A, counts
  std::int32_t target_velocity = 0;           // 0x60FF, counts/s
  std::int8_t mode = 8;                       // 0x6060
  std::uint16_t touch_probe = 0;              // 0x60B8, touch probe function
  std::uint16_t max_torque = kNoTorqueLimit;  // 0x6072, per mille of the rated torque
  std::int16_t target_torque = 0;             // 0x6071, per mille of the rated torque (CST)
  std::uint32_t max_motor_speed = 0;          // 0x6080, rpm (CST's speed limit)
};
// What a drive's TPDOs said; a TPDO sets what its mapping names, the rest stays.
struct DriveFeedback {
  std::uint16_t statusword = 0;          // 0x6041
  std::int32_t position_actual = 0;      // 0x6064, counts
  std::int8_t mode_display = 0;          // 0x6061
  std::int32_t velocity_actual = 0;      // 0x606C, counts/s
  std::int32_t following_error = 0;      // 0x60F4, counts
  std::int16_t torque_actual = 0;        // 0x6077, per mille of the rated torque
  std::uint16_t touch_probe_status = 0;  // 0x60B9
  std::int32_t probe_positive = 0;       // 0x60BA, counts at the positive edge
  std::int32_t probe_negative = 0;       // 0x60BB, counts at the negative edge
};

// The frame of RPDO `pdo` from `command`; false when the mapping cannot be carried.
bool pack_command(const PdoMapping& pdo, std::uint8_t node, const DriveCommand& command,
                  can::CanFrame& out) noexcept;
// The frame of TPDO `pdo` from `feedback` (a drive's side: the simulator); false when the mapping
// cannot be carried.
bool pack_feedback(const PdoMapping& pdo, std::uint8_t node, const DriveFeedback& feedback,
                   can::CanFrame& out) noexcept;
// TPDO `pdo` into `feedback`; false (nothing set) on a length that is not the mapped one.
bool unpack_feedback(const PdoMapping& pdo, const can::CanFrame& frame,
                     DriveFeedback& feedback) noexcept;

// The frames of the layouts above, in fixed shapes. RPDO1 of an axis in CSP: controlword +
// target position (6 bytes).
struct RxPdoCsp {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;
};
// TPDO1 of an axis in CSP: statusword + position actual value (6 bytes); a spindle's (and a
// homing axis's) adds the modes of operation display (a 7th byte).
struct TxPdoCsp {
  std::uint16_t statusword = 0;
  std::int32_t position_actual = 0;
  std::int8_t mode_display = 0;
  bool has_mode_display = false;
};
// A spindle's RPDO1: controlword + target position + modes of operation, 7 bytes; and its
// RPDO2: target velocity, 4 bytes.
struct RxPdoSpindle {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;
  std::int8_t mode = 8;
  std::int32_t target_velocity = 0;
};

CanFrame encode_rpdo_csp(std::uint8_t node, const RxPdoCsp& pdo) noexcept;
CanFrame encode_tpdo_csp(std::uint8_t node, const TxPdoCsp& pdo) noexcept;  // 7 bytes with mode
CanFrame encode_rpdo1_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept;
CanFrame encode_rpdo2_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept;
// nullopt on a wrong id or a wrong length (a malformed frame is dropped by the caller and
// counted).
std::optional<RxPdoCsp> decode_rpdo_csp(const CanFrame& frame) noexcept;
// 6 bytes; with_mode: 7, the last the modes of operation display (a spindle's mapping).
std::optional<TxPdoCsp> decode_tpdo_csp(const CanFrame& frame, bool with_mode = false) noexcept;

}  // namespace mcnc::canopen
