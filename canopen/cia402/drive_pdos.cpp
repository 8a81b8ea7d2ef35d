#include "canopen/cia402/drive_pdos.hpp"

#include <initializer_list>

namespace mcnc::canopen {

namespace {

PdoMapping pdo(bool receive, std::uint8_t number, std::initializer_list<MappedObject> objects) {
  PdoMapping p;
  p.receive = receive;
  p.number = number;
  for (const MappedObject& o : objects) {
    p.objects[p.count++] = o;
  }
  return p;
}

// The fixed shapes' layouts.
const PdoLayout& csp_layout() noexcept {
  static const PdoLayout layout = axis_pdos(false, false, false);
  return layout;
}
const PdoLayout& with_mode_layout() noexcept {
  static const PdoLayout layout = spindle_pdos();
  return layout;
}

CanFrame packed(const PdoMapping& mapping, std::uint8_t node, const DriveCommand& command) {
  CanFrame frame;
  pack_command(mapping, node, command, frame);
  return frame;
}

}  // namespace

PdoLayout axis_pdos(bool velocity_mode, bool velocity_actual, bool following_error) noexcept {
  PdoLayout p;
  p.rpdo1 = pdo(
      true, 1,
      {{0x6040, 0, 16}, {velocity_mode ? std::uint16_t{0x60FF} : std::uint16_t{0x607A}, 0, 32}});
  p.rpdo2 = pdo(true, 2, {});
  p.tpdo1 = pdo(false, 1, {{0x6041, 0, 16}, {0x6064, 0, 32}});
  p.tpdo2 = pdo(false, 2, {});
  if (velocity_actual) {
    p.tpdo2.objects[p.tpdo2.count++] = MappedObject{0x606C, 0, 32};
  }
  if (following_error) {
    p.tpdo2.objects[p.tpdo2.count++] = MappedObject{0x60F4, 0, 32};
  }
  return p;
}

PdoLayout spindle_pdos() noexcept {
  PdoLayout p;
  p.rpdo1 = pdo(true, 1, {{0x6040, 0, 16}, {0x607A, 0, 32}, {0x6060, 0, 8}});
  p.rpdo2 = pdo(true, 2, {{0x60FF, 0, 32}});
  p.tpdo1 = pdo(false, 1, {{0x6041, 0, 16}, {0x6064, 0, 32}, {0x6061, 0, 8}});
  p.tpdo2 = pdo(false, 2, {});
  return p;
}

PdoLayout homing_axis_pdos() noexcept {
  PdoLayout p = spindle_pdos();
  p.rpdo2 = pdo(true, 2, {});
  return p;
}

void add_touch_probe(PdoLayout& layout) noexcept {
  layout.rpdo1.objects[layout.rpdo1.count++] = MappedObject{0x60B8, 0, 16};
  layout.tpdo1.objects[layout.tpdo1.count++] = MappedObject{0x60B9, 0, 16};
  layout.tpdo2.objects[layout.tpdo2.count++] = MappedObject{0x60BA, 0, 32};
  layout.tpdo2.objects[layout.tpdo2.count++] = MappedObject{0x60BB, 0, 32};
}

void add_torque_limit(PdoLayout& layout) noexcept {
  layout.rpdo2.objects[layout.rpdo2.count++] = MappedObject{0x6072, 0, 16};
  layout.tpdo2.objects[layout.tpdo2.count++] = MappedObject{0x6077, 0, 16};
}

void add_torque_mode(PdoLayout& layout) noexcept {
  layout.rpdo1.objects[layout.rpdo1.count++] = MappedObject{0x6060, 0, 8};
  layout.tpdo1.objects[layout.tpdo1.count++] = MappedObject{0x6061, 0, 8};
  layout.rpdo2.objects[layout.rpdo2.count++] = MappedObject{0x6071, 0, 16};
  layout.rpdo2.objects[layout.rpdo2.count++] = MappedObject{0x6080, 0, 32};
}

bool pack_command(const PdoMapping& pdo, std::uint8_t node, const DriveCommand& command,
                  can::CanFrame& out) noexcept {
  const auto value_of = [&](std::uint16_t index, std::uint8_t) -> std::uint32_t {
    switch (index) {
      case 0x6040:
        return command.controlword;
      case 0x607A:
        return static_cast<std::uint32_t>(command.target_position);
      case 0x60FF:
        return static_cast<std::uint32_t>(command.target_velocity);
      case 0x6060:
        return static_cast<std::uint8_t>(command.mode);
      case 0x60B8:
        return command.touch_probe;
      case 0x6072:
        return command.max_torque;
      case 0x6071:
        return static_cast<std::uint16_t>(command.target_torque);
      case 0x6080:
        return command.max_motor_speed;
      default:
        return 0;  // an object the master does not command: zeros, as the mapping's length asks
    }
  };
  return pack(pdo, node, value_of, out);
}

bool pack_feedback(const PdoMapping& pdo, std::uint8_t node, const DriveFeedback& feedback,
                   can::CanFrame& out) noexcept {
  const auto value_of = [&](std::uint16_t index, std::uint8_t) -> std::uint32_t {
    switch (index) {
      case 0x6041:
        return feedback.statusword;
      case 0x6064:
        return static_cast<std::uint32_t>(feedback.position_actual);
      case 0x6061:
        return static_cast<std::uint8_t>(feedback.mode_display);
      case 0x606C:
        return static_cast<std::uint32_t>(feedback.velocity_actual);
      case 0x60F4:
        return static_cast<std::uint32_t>(feedback.following_error);
      case 0x6077:
        return static_cast<std::uint16_t>(feedback.torque_actual);
      case 0x60B9:
        return feedback.touch_probe_status;
      case 0x60BA:
        return static_cast<std::uint32_t>(feedback.probe_positive);
      case 0x60BB:
        return static_cast<std::uint32_t>(feedback.probe_negative);
      default:
        return 0;  // an object this project does not map: zeros, as the mapping's length asks
    }
  };
  return pack(pdo, node, value_of, out);
}

bool unpack_feedback(const PdoMapping& pdo, const can::CanFrame& frame,
                     DriveFeedback& feedback) noexcept {
  const auto store = [&](std::uint16_t index, std::uint8_t, std::uint32_t raw, std::uint8_t bits) {
    switch (index) {
      case 0x6041:
        feedback.statusword = static_cast<std::uint16_t>(raw);
        break;
      case 0x6064:
        feedback.position_actual = sign_extend(raw, bits);
        break;
      case 0x6061:
        feedback.mode_display = static_cast<std::int8_t>(sign_extend(raw, bits));
        break;
      case 0x606C:
        feedback.velocity_actual = sign_extend(raw, bits);
        break;
      case 0x60F4:
        feedback.following_error = sign_extend(raw, bits);
        break;
      case 0x6077:
        feedback.torque_actual = static_cast<std::int16_t>(sign_extend(raw, bits));
        break;
      case 0x60B9:
        feedback.touch_probe_status = static_cast<std::uint16_t>(raw);
        break;
      case 0x60BA:
        feedback.probe_positive = sign_extend(raw, bits);
        break;
      case 0x60BB:
        feedback.probe_negative = sign_extend(raw, bits);
        break;
      default:
        break;  // an object the master does not read
    }
  };
  return unpack(pdo, frame, store);
}

CanFrame encode_rpdo_csp(std::uint8_t node, const RxPdoCsp& pdo) noexcept {
  return packed(csp_layout().rpdo1, node, DriveCommand{pdo.controlword, pdo.target_position});
}

CanFrame encode_tpdo_csp(std::uint8_t node, const TxPdoCsp& pdo) noexcept {
  DriveFeedback feedback;
  feedback.statusword = pdo.statusword;
  feedback.position_actual = pdo.position_actual;
  feedback.mode_display = pdo.mode_display;
  CanFrame frame;
  pack_feedback(pdo.has_mode_display ? with_mode_layout().tpdo1 : csp_layout().tpdo1, node,
                feedback, frame);
  return frame;
}

CanFrame encode_rpdo1_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept {
  return packed(with_mode_layout().rpdo1, node,
                DriveCommand{pdo.controlword, pdo.target_position, pdo.target_velocity, pdo.mode});
}

CanFrame encode_rpdo2_spindle(std::uint8_t node, const RxPdoSpindle& pdo) noexcept {
  return packed(with_mode_layout().rpdo2, node,
                DriveCommand{pdo.controlword, pdo.target_position, pdo.target_velocity, pdo.mode});
}

std::optional<RxPdoCsp> decode_rpdo_csp(const CanFrame& frame) noexcept {
  if (classify(frame).kind != FrameKind::rpdo1) {
    return std::nullopt;
  }
  RxPdoCsp pdo;
  const auto store = [&](std::uint16_t index, std::uint8_t, std::uint32_t raw, std::uint8_t bits) {
    if (index == 0x6040) {
      pdo.controlword = static_cast<std::uint16_t>(raw);
    } else if (index == 0x607A) {
      pdo.target_position = sign_extend(raw, bits);
    }
  };
  if (!unpack(csp_layout().rpdo1, frame, store)) {
    return std::nullopt;
  }
  return pdo;
}

std::optional<TxPdoCsp> decode_tpdo_csp(const CanFrame& frame, bool with_mode) noexcept {
  if (classify(frame).kind != FrameKind::tpdo1) {
    return std::nullopt;
  }
  DriveFeedback feedback;
  if (!unpack_feedback(with_mode ? with_mode_layout().tpdo1 : csp_layout().tpdo1, frame,
                       feedback)) {
    return std::nullopt;
  }
  return TxPdoCsp{feedback.statusword, feedback.position_actual, feedback.mode_display, with_mode};
}

}  // namespace mcnc::canopen
