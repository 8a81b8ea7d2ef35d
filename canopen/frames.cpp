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

std::uint16_t get_u16(const CanFrame& frame, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(frame.data[at] | (frame.data[at + 1] << 8));
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

}  // namespace mcnc::canopen
