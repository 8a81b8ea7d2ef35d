#pragma once
// CiA 301 frames used by the axis node and the drive simulator: NMT, SYNC, boot-up/heartbeat and
// EMCY, and what a frame is by its COB-ID. Encoding and decoding only; PDOs are packed by their
// layout (pdo_layout.hpp).
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

struct Emcy {
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;
};

// node: 1..127 (0 in NMT = all nodes). All multi-byte values little endian.
CanFrame encode_nmt(NmtCommand command, std::uint8_t node) noexcept;
CanFrame encode_sync(std::uint8_t counter) noexcept;  // counter 1..240, 0 = no counter byte
CanFrame encode_heartbeat(std::uint8_t node, NmtState state) noexcept;
CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept;

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

}  // namespace mcnc::canopen
