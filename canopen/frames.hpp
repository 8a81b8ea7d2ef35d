#pragma once
// CiA 301 frames used by the axis node and the drive simulator: NMT, SYNC, boot-up/heartbeat,
// EMCY and the one RPDO / TPDO pair of cyclic synchronous position. Encoding and decoding only.
#include "common/can/can_frame.hpp"

#include <cstdint>
#include <optional>

namespace mcnc::canopen {

using can::CanFrame;

enum class NmtCommand : std::uint8_t {
  start = 0x01,
  stop = 0x02,
  enter_preoperational = 0x80,
  reset_node = 0x81,
  reset_communication = 0x82,
};

enum class NmtState : std::uint8_t {
  bootup = 0x00,
  stopped = 0x04,
  operational = 0x05,
  preoperational = 0x7F
};

inline constexpr std::uint32_t kNmtId = 0x000;
inline constexpr std::uint32_t kSyncId = 0x080;
inline constexpr std::uint32_t kEmcyBase = 0x080;
inline constexpr std::uint32_t kTpdo1Base = 0x180;
inline constexpr std::uint32_t kRpdo1Base = 0x200;
inline constexpr std::uint32_t kTpdo2Base = 0x280;
inline constexpr std::uint32_t kRpdo2Base = 0x300;
inline constexpr std::uint32_t kHeartbeatBase = 0x700;

// RPDO1 of an axis in CSP: controlword (0x6040) + target position (0x607A).
struct RxPdoCsp {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;
};
// TPDO1 of an axis in CSP: statusword (0x6041) + position actual value (0x6064); a spindle's
// adds modes of operation display (0x6061, a 7th byte).
struct TxPdoCsp {
  std::uint16_t statusword = 0;
  std::int32_t position_actual = 0;
  std::int8_t mode_display = 0;
  bool has_mode_display = false;
};
// A spindle's RPDO1: controlword + target position + modes of operation (0x6060), 7 bytes;
// and its RPDO2: target velocity (0x60FF), 4 bytes.
struct RxPdoSpindle {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;
  std::int8_t mode = 8;
  std::int32_t target_velocity = 0;
};
struct Emcy {
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;
};

// node: 1..127 (0 in NMT = all nodes). All multi-byte values little endian.
CanFrame encode_nmt(NmtCommand command, std::uint8_t node) noexcept;
CanFrame encode_sync(std::uint8_t counter) noexcept;  // counter 1..240, 0 = no counter byte
CanFrame encode_heartbeat(std::uint8_t node, NmtState state) noexcept;
CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept;
CanFrame encode_rpdo_csp(std::uint8_t node, const RxPdoCsp& pdo) noexcept;
CanFrame encode_tpdo_csp(std::uint8_t node, const TxPdoCsp& pdo) noexcept;  // 7 bytes with mode
CanFrame encode_rpdo1_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept;
CanFrame encode_rpdo2_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept;

// What a frame is, by its COB-ID. Decoders return nullopt on a wrong id or a wrong length
// (a malformed frame is dropped by the caller and counted).
enum class FrameKind { nmt, sync, emcy, tpdo1, rpdo1, tpdo2, rpdo2, heartbeat, other };
struct FrameClass {
  FrameKind kind = FrameKind::other;
  std::uint8_t node = 0;  // 0 for NMT and SYNC
};
FrameClass classify(const CanFrame& frame) noexcept;

struct NmtFrame {
  NmtCommand command;
  std::uint8_t node;
};
std::optional<NmtFrame> decode_nmt(const CanFrame& frame) noexcept;
std::optional<std::uint8_t> decode_sync(const CanFrame& frame) noexcept;  // the counter (0 if none)
std::optional<NmtState> decode_heartbeat(const CanFrame& frame) noexcept;
std::optional<Emcy> decode_emcy(const CanFrame& frame) noexcept;
std::optional<RxPdoCsp> decode_rpdo_csp(const CanFrame& frame) noexcept;
// 6 bytes; with_mode: 7, the last the modes of operation display (a spindle's mapping).
std::optional<TxPdoCsp> decode_tpdo_csp(const CanFrame& frame, bool with_mode = false) noexcept;

}  // namespace mcnc::canopen
