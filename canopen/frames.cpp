#include "canopen/frames.hpp"

#include <cstddef>

namespace mcnc::canopen {
namespace {

constexpr std::uint8_t kMaxNode = 127;

CanFrame make_frame(std::uint32_t id, std::uint8_t dlc) noexcept {
  CanFrame frame;
  frame.id = id;
  frame.dlc = dlc;
  return frame;
}

void put_u16(CanFrame& frame, std::size_t at, std::uint16_t value) noexcept {
  frame.data[at] = static_cast<std::uint8_t>(value & 0xFFU);
  frame.data[at + 1] = static_cast<std::uint8_t>(value >> 8);
}

void put_i32(CanFrame& frame, std::size_t at, std::int32_t value) noexcept {
  const auto bits = static_cast<std::uint32_t>(value);
  for (std::size_t i = 0; i < 4; ++i) {
    frame.data[at + i] = static_cast<std::uint8_t>((bits >> (8 * i)) & 0xFFU);
  }
}

std::uint16_t get_u16(const CanFrame& frame, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(frame.data[at] | (frame.data[at + 1] << 8));
}

std::int32_t get_i32(const CanFrame& frame, std::size_t at) noexcept {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    bits |= static_cast<std::uint32_t>(frame.data[at + i]) << (8 * i);
  }
  // Two's complement conversion is well defined since C++20.
  return static_cast<std::int32_t>(bits);
}

// Node-addressed COB-IDs are base + node with node 1..127. The flag bits (EFF/RTR/ERR) make the
// id fall outside every range, so such frames are never taken for CANopen traffic.
bool node_id_in(std::uint32_t id, std::uint32_t base, std::uint8_t& node) noexcept {
  if (id <= base || id > base + kMaxNode) {
    return false;
  }
  node = static_cast<std::uint8_t>(id - base);
  return true;
}

bool known_nmt_command(std::uint8_t value) noexcept {
  switch (static_cast<NmtCommand>(value)) {
    case NmtCommand::start:
    case NmtCommand::stop:
    case NmtCommand::enter_preoperational:
    case NmtCommand::reset_node:
    case NmtCommand::reset_communication:
      return true;
  }
  return false;
}

bool known_nmt_state(std::uint8_t value) noexcept {
  switch (static_cast<NmtState>(value)) {
    case NmtState::bootup:
    case NmtState::stopped:
    case NmtState::operational:
    case NmtState::preoperational:
      return true;
  }
  return false;
}

}  // namespace

CanFrame encode_nmt(NmtCommand command, std::uint8_t node) noexcept {
  CanFrame frame = make_frame(kNmtId, 2);
  frame.data[0] = static_cast<std::uint8_t>(command);
  frame.data[1] = node;
  return frame;
}

CanFrame encode_sync(std::uint8_t counter) noexcept {
  CanFrame frame = make_frame(kSyncId, counter == 0 ? 0 : 1);
  frame.data[0] = counter;
  return frame;
}

CanFrame encode_heartbeat(std::uint8_t node, NmtState state) noexcept {
  CanFrame frame = make_frame(kHeartbeatBase + node, 1);
  frame.data[0] = static_cast<std::uint8_t>(state);
  return frame;
}

CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept {
  CanFrame frame = make_frame(kEmcyBase + node, 8);
  put_u16(frame, 0, emcy.error_code);
  frame.data[2] = emcy.error_register;
  return frame;
}

CanFrame encode_rpdo_csp(std::uint8_t node, const RxPdoCsp& pdo) noexcept {
  CanFrame frame = make_frame(kRpdo1Base + node, 6);
  put_u16(frame, 0, pdo.controlword);
  put_i32(frame, 2, pdo.target_position);
  return frame;
}

CanFrame encode_tpdo_csp(std::uint8_t node, const TxPdoCsp& pdo) noexcept {
  CanFrame frame = make_frame(kTpdo1Base + node, pdo.has_mode_display ? 7 : 6);
  put_u16(frame, 0, pdo.statusword);
  put_i32(frame, 2, pdo.position_actual);
  if (pdo.has_mode_display) {
    frame.data[6] = static_cast<std::uint8_t>(pdo.mode_display);
  }
  return frame;
}

CanFrame encode_rpdo1_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept {
  CanFrame frame = make_frame(kRpdo1Base + node, 7);
  put_u16(frame, 0, pdo.controlword);
  put_i32(frame, 2, pdo.target_position);
  frame.data[6] = static_cast<std::uint8_t>(pdo.mode);
  return frame;
}

CanFrame encode_rpdo2_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept {
  CanFrame frame = make_frame(kRpdo2Base + node, 4);
  put_i32(frame, 0, pdo.target_velocity);
  return frame;
}

FrameClass classify(const CanFrame& frame) noexcept {
  const std::uint32_t id = frame.id;
  FrameClass result;
  if (id == kNmtId) {
    result.kind = FrameKind::nmt;
  } else if (id == kSyncId) {
    result.kind = FrameKind::sync;
  } else if (node_id_in(id, kEmcyBase, result.node)) {
    result.kind = FrameKind::emcy;
  } else if (node_id_in(id, kTpdo1Base, result.node)) {
    result.kind = FrameKind::tpdo1;
  } else if (node_id_in(id, kRpdo1Base, result.node)) {
    result.kind = FrameKind::rpdo1;
  } else if (node_id_in(id, kTpdo2Base, result.node)) {
    result.kind = FrameKind::tpdo2;
  } else if (node_id_in(id, kRpdo2Base, result.node)) {
    result.kind = FrameKind::rpdo2;
  } else if (node_id_in(id, kHeartbeatBase, result.node)) {
    result.kind = FrameKind::heartbeat;
  }
  return result;
}

std::optional<NmtFrame> decode_nmt(const CanFrame& frame) noexcept {
  if (frame.id != kNmtId || frame.dlc != 2 || !known_nmt_command(frame.data[0]) ||
      frame.data[1] > kMaxNode) {
    return std::nullopt;
  }
  return NmtFrame{static_cast<NmtCommand>(frame.data[0]), frame.data[1]};
}

std::optional<std::uint8_t> decode_sync(const CanFrame& frame) noexcept {
  if (frame.id != kSyncId) {
    return std::nullopt;
  }
  if (frame.dlc == 0) {
    return std::uint8_t{0};
  }
  // CiA 301: the counter runs 1..240; anything else is not a valid SYNC.
  if (frame.dlc == 1 && frame.data[0] >= 1 && frame.data[0] <= 240) {
    return frame.data[0];
  }
  return std::nullopt;
}

std::optional<NmtState> decode_heartbeat(const CanFrame& frame) noexcept {
  std::uint8_t node = 0;
  if (!node_id_in(frame.id, kHeartbeatBase, node) || frame.dlc != 1 ||
      !known_nmt_state(frame.data[0])) {
    return std::nullopt;
  }
  return static_cast<NmtState>(frame.data[0]);
}

std::optional<Emcy> decode_emcy(const CanFrame& frame) noexcept {
  std::uint8_t node = 0;
  if (!node_id_in(frame.id, kEmcyBase, node) || frame.dlc != 8) {
    return std::nullopt;
  }
  return Emcy{get_u16(frame, 0), frame.data[2]};
}

std::optional<RxPdoCsp> decode_rpdo_csp(const CanFrame& frame) noexcept {
  std::uint8_t node = 0;
  if (!node_id_in(frame.id, kRpdo1Base, node) || frame.dlc != 6) {
    return std::nullopt;
  }
  return RxPdoCsp{get_u16(frame, 0), get_i32(frame, 2)};
}

std::optional<TxPdoCsp> decode_tpdo_csp(const CanFrame& frame, bool with_mode) noexcept {
  std::uint8_t node = 0;
  if (!node_id_in(frame.id, kTpdo1Base, node) || frame.dlc != (with_mode ? 7 : 6)) {
    return std::nullopt;
  }
  TxPdoCsp pdo{get_u16(frame, 0), get_i32(frame, 2)};
  if (with_mode) {
    pdo.mode_display = static_cast<std::int8_t>(frame.data[6]);
    pdo.has_mode_display = true;
  }
  return pdo;
}

}  // namespace mcnc::canopen
