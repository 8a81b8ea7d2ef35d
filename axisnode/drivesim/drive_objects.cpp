#include "axisnode/drivesim/drive_objects.hpp"

#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/sdo_abort.hpp"

#include <algorithm>
#include <cstring>

namespace mcnc::drivesim {

namespace {

namespace abort = canopen::sdo_abort;

template <typename T>
std::uint32_t put(canopen::SdoValue& out, T value) noexcept {
  out.size = sizeof(T);
  std::memcpy(out.bytes.data(), &value, sizeof(T));  // little endian host, as CANopen
  return 0;
}

std::uint32_t value_of(const std::uint8_t* data, std::size_t size) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < size && i < 4; ++i) {
    v |= static_cast<std::uint32_t>(data[i]) << (8 * i);
  }
  return v;
}

// The size of the object's data type, for a write's length check.
std::uint32_t expect_size(std::size_t size, std::size_t wanted) noexcept {
  if (size == wanted) {
    return 0;
  }
  return size > wanted ? abort::kLengthTooHigh : abort::kLengthTooLow;
}

bool mappable(bool receive, std::uint16_t index) noexcept {
  if (receive) {
    return index == 0x6040 || index == 0x607A || index == 0x60FF || index == 0x6060 ||
           index == 0x60B8 || index == 0x6072 || index == 0x6071 || index == 0x6080;
  }
  return index == 0x6041 || index == 0x6064 || index == 0x606C || index == 0x60F4 ||
         index == 0x6061 || index == 0x6077 || index == 0x60B9 || index == 0x60BA ||
         index == 0x60BB;
}

}  // namespace

DriveObjects::DriveObjects(std::uint8_t node) noexcept : node_(node) {
  reset_communication();
}

void DriveObjects::reset_communication() noexcept {
  const std::uint8_t node = node_;
  rpdo_ = {};
  tpdo_ = {};
  heartbeat_ms_ = 0;
  // CiA 301 pre-defined connection set: RPDO1/TPDO1 valid, the others not.
  rpdo_[0].cob_id = 0x200U + node;
  rpdo_[1].cob_id = 0x80000000U | (0x300U + node);
  tpdo_[0].cob_id = 0x180U + node;
  tpdo_[1].cob_id = 0x80000000U | (0x280U + node);
  rpdo_[0].entries[0] = 0x60400010U;
  rpdo_[0].entries[1] = 0x607A0020U;
  rpdo_[0].count = 2;
  tpdo_[0].entries[0] = 0x60410010U;
  tpdo_[0].entries[1] = 0x60640020U;
  tpdo_[0].count = 2;
}

bool DriveObjects::encode_tpdo(std::size_t n, can::CanFrame& out) const noexcept {
  if (n >= tpdo_.size() || !tpdo_[n].valid()) {
    return false;
  }
  canopen::DriveFeedback values;
  values.statusword = live.statusword;
  values.position_actual = live.position;
  values.mode_display = mode_;
  values.velocity_actual = live.velocity;
  values.following_error = live.following_error;
  values.torque_actual = live.torque;
  values.touch_probe_status = live.touch_probe_status;
  values.probe_positive = live.probe_positive;
  values.probe_negative = live.probe_negative;
  if (!canopen::pack_feedback(mapping_of(tpdo_[n], false, n), node_, values, out)) {
    return false;
  }
  out.id = tpdo_[n].cob_id & can::kSffMask;  // as the master set it
  return true;
}

void RpdoValues::merge(const RpdoValues& other) noexcept {
  if (other.has_controlword) {
    controlword = other.controlword;
    has_controlword = true;
  }
  if (other.has_target_position) {
    target_position = other.target_position;
    has_target_position = true;
  }
  if (other.has_target_velocity) {
    target_velocity = other.target_velocity;
    has_target_velocity = true;
  }
  if (other.has_mode) {
    mode = other.mode;
    has_mode = true;
  }
  if (other.has_touch_probe) {
    touch_probe = other.touch_probe;
    has_touch_probe = true;
  }
  if (other.has_max_torque) {
    max_torque = other.max_torque;
    has_max_torque = true;
  }
  if (other.has_target_torque) {
    target_torque = other.target_torque;
    has_target_torque = true;
  }
  if (other.has_max_motor_speed) {
    max_motor_speed = other.max_motor_speed;
    has_max_motor_speed = true;
  }
}

bool DriveObjects::decode_rpdo(std::size_t n, const can::CanFrame& frame,
                               RpdoValues& out) const noexcept {
  if (n >= rpdo_.size() || !rpdo_[n].valid()) {
    return false;
  }
  const auto store = [&](std::uint16_t index, std::uint8_t, std::uint32_t raw, std::uint8_t bits) {
    switch (index) {
      case 0x6040:
        out.controlword = static_cast<std::uint16_t>(raw);
        out.has_controlword = true;
        break;
      case 0x607A:
        out.target_position = canopen::sign_extend(raw, bits);
        out.has_target_position = true;
        break;
      case 0x60FF:
        out.target_velocity = canopen::sign_extend(raw, bits);
        out.has_target_velocity = true;
        break;
      case 0x6060:
        out.mode = static_cast<std::int8_t>(canopen::sign_extend(raw, bits));
        out.has_mode = true;
        break;
      case 0x60B8:
        out.touch_probe = static_cast<std::uint16_t>(raw);
        out.has_touch_probe = true;
        break;
      case 0x6072:
        out.max_torque = static_cast<std::uint16_t>(raw);
        out.has_max_torque = true;
        break;
      case 0x6071:
        out.target_torque = static_cast<std::int16_t>(canopen::sign_extend(raw, bits));
        out.has_target_torque = true;
        break;
      case 0x6080:
        out.max_motor_speed = raw;
        out.has_max_motor_speed = true;
        break;
      default:
        break;
    }
  };
  return canopen::unpack(mapping_of(rpdo_[n], true, n), frame, store);
}

canopen::PdoMapping DriveObjects::mapping_of(const Pdo& pdo, bool receive, std::size_t n) noexcept {
  canopen::PdoMapping mapping;
  mapping.receive = receive;
  mapping.number = static_cast<std::uint8_t>(n + 1);
  mapping.transmission_type = pdo.transmission_type;
  mapping.count = pdo.count;
  for (std::size_t i = 0; i < pdo.count && i < mapping.objects.size(); ++i) {
    mapping.objects[i] = canopen::PdoMapping::object_of(pdo.entries[i]);
  }
  return mapping;
}

std::uint32_t DriveObjects::read_pdo(const Pdo& pdo, bool mapping, std::uint8_t sub,
                                     canopen::SdoValue& out) const noexcept {
  if (mapping) {
    if (sub == 0) {
      return put<std::uint8_t>(out, pdo.count);
    }
    if (sub > 8) {
      return abort::kNoSubindex;
    }
    return put<std::uint32_t>(out, pdo.entries[sub - 1U]);
  }
  switch (sub) {
    case 0:
      return put<std::uint8_t>(out, 2);
    case 1:
      return put<std::uint32_t>(out, pdo.cob_id);
    case 2:
      return put<std::uint8_t>(out, pdo.transmission_type);
    default:
      return abort::kNoSubindex;
  }
}

std::uint32_t DriveObjects::write_pdo(Pdo& pdo, bool receive, bool mapping, std::uint8_t sub,
                                      std::uint32_t value, std::size_t size) noexcept {
  if (!mapping) {
    if (sub == 1) {
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      pdo.cob_id = value;
      return 0;
    }
    if (sub == 2) {
      if (const std::uint32_t e = expect_size(size, 1)) {
        return e;
      }
      if (value > 240 && value < 254) {
        return abort::kInvalidValue;  // reserved transmission types
      }
      pdo.transmission_type = static_cast<std::uint8_t>(value);
      return 0;
    }
    return sub == 0 ? abort::kReadOnly : abort::kNoSubindex;
  }
  if (pdo.valid()) {
    return abort::kDeviceState;  // CiA 301: invalidate the PDO before changing its mapping
  }
  if (sub == 0) {
    if (const std::uint32_t e = expect_size(size, 1)) {
      return e;
    }
    if (value > 8) {
      return abort::kValueTooHigh;
    }
    unsigned bits = 0;
    for (std::uint32_t i = 0; i < value; ++i) {
      bits += pdo.entries[i] & 0xFFU;
    }
    if (bits > 64) {
      return abort::kPdoTooLong;
    }
    pdo.count = static_cast<std::uint8_t>(value);
    return 0;
  }
  if (sub > 8) {
    return abort::kNoSubindex;
  }
  if (pdo.count != 0) {
    return abort::kDeviceState;  // entries change only while the count is 0
  }
  if (const std::uint32_t e = expect_size(size, 4)) {
    return e;
  }
  const auto index = static_cast<std::uint16_t>(value >> 16);
  const std::uint32_t bits = value & 0xFFU;
  if (!mappable(receive, index) || (bits != 8 && bits != 16 && bits != 32)) {
    return abort::kNotMappable;
  }
  pdo.entries[sub - 1U] = value;
  return 0;
}

std::uint32_t DriveObjects::read(std::uint16_t index, std::uint8_t sub,
                                 canopen::SdoValue& out) noexcept {
  if (refused_code_ != 0 && index == refused_index_) {
    return refused_code_;
  }
  if (index >= 0x1400 && index <= 0x1401) {
    return read_pdo(rpdo_[index - 0x1400U], false, sub, out);
  }
  if (index >= 0x1600 && index <= 0x1601) {
    return read_pdo(rpdo_[index - 0x1600U], true, sub, out);
  }
  if (index >= 0x1800 && index <= 0x1801) {
    return read_pdo(tpdo_[index - 0x1800U], false, sub, out);
  }
  if (index >= 0x1A00 && index <= 0x1A01) {
    return read_pdo(tpdo_[index - 0x1A00U], true, sub, out);
  }
  if (sub != 0) {
    return abort::kNoSubindex;
  }
  switch (index) {
    case 0x1000:
      return put<std::uint32_t>(out, kDeviceType);
    case 0x1008: {
      constexpr char kName[] = "mcnc drivesim";
      out.size = sizeof kName - 1;
      std::copy_n(kName, out.size, out.bytes.begin());
      return 0;
    }
    case 0x1017:
      return put<std::uint16_t>(out, heartbeat_ms_);
    case 0x6040:
      return put<std::uint16_t>(out, controlword_);
    case 0x6041:
      return put<std::uint16_t>(out, live.statusword);
    case 0x6060:
    case 0x6061:
      return put<std::int8_t>(out, mode_);
    case 0x6064:
      return put<std::int32_t>(out, live.position);
    case 0x606C:
      return put<std::int32_t>(out, live.velocity);
    case 0x607A:
      return put<std::int32_t>(out, target_position_);
    case 0x60F4:
      return put<std::int32_t>(out, live.following_error);
    case 0x6076:
      return put<std::uint32_t>(out, live.rated_torque);
    case 0x6077:
      return put<std::int16_t>(out, live.torque);
    case 0x607C:
      return put<std::int32_t>(out, home_offset_);
    case 0x6098:
      return put<std::int8_t>(out, homing_method_);
    case 0x6085:
      return put<std::uint32_t>(out, quick_stop_dec_);
    case 0x60FF:
      return put<std::int32_t>(out, target_velocity_);
    case 0x60B8:
      return put<std::uint16_t>(out, touch_probe_);
    case 0x6072:
      return put<std::uint16_t>(out, max_torque_);
    case 0x6071:
      return put<std::int16_t>(out, target_torque_);
    case 0x6080:
      return put<std::uint32_t>(out, max_motor_speed_);
    case 0x60B9:
      return put<std::uint16_t>(out, live.touch_probe_status);
    case 0x60BA:
      return put<std::int32_t>(out, live.probe_positive);
    case 0x60BB:
      return put<std::int32_t>(out, live.probe_negative);
    default:
      return abort::kNoObject;
  }
}

std::uint32_t DriveObjects::write(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                                  std::size_t size) noexcept {
  if (refused_code_ != 0 && index == refused_index_) {
    return refused_code_;
  }
  const std::uint32_t value = value_of(data, size);
  if (index >= 0x1400 && index <= 0x1401) {
    return write_pdo(rpdo_[index - 0x1400U], true, false, sub, value, size);
  }
  if (index >= 0x1600 && index <= 0x1601) {
    return write_pdo(rpdo_[index - 0x1600U], true, true, sub, value, size);
  }
  if (index >= 0x1800 && index <= 0x1801) {
    return write_pdo(tpdo_[index - 0x1800U], false, false, sub, value, size);
  }
  if (index >= 0x1A00 && index <= 0x1A01) {
    return write_pdo(tpdo_[index - 0x1A00U], false, true, sub, value, size);
  }
  if (sub != 0) {
    return index == 0x1000 || (index >= 0x6040 && index <= 0x60FF) ? abort::kNoSubindex
                                                                   : abort::kNoObject;
  }
  switch (index) {
    case 0x1000:
    case 0x1008:
    case 0x6041:
    case 0x6061:
    case 0x6064:
    case 0x606C:
    case 0x60F4:
    case 0x6076:
    case 0x6077:
    case 0x60B9:
    case 0x60BA:
    case 0x60BB:
      return abort::kReadOnly;
    case 0x60B8:
      if (const std::uint32_t e = expect_size(size, 2)) {
        return e;
      }
      touch_probe_ = static_cast<std::uint16_t>(value);
      return 0;
    case 0x6072:
      if (const std::uint32_t e = expect_size(size, 2)) {
        return e;
      }
      max_torque_ = static_cast<std::uint16_t>(value);
      return 0;
    case 0x6071:
      if (const std::uint32_t e = expect_size(size, 2)) {
        return e;
      }
      target_torque_ = static_cast<std::int16_t>(static_cast<std::uint16_t>(value));
      return 0;
    case 0x6080:
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      max_motor_speed_ = value;
      return 0;
    case 0x1017:
      if (const std::uint32_t e = expect_size(size, 2)) {
        return e;
      }
      heartbeat_ms_ = static_cast<std::uint16_t>(value);
      return 0;
    case 0x6040:
      if (const std::uint32_t e = expect_size(size, 2)) {
        return e;
      }
      controlword_ = static_cast<std::uint16_t>(value);
      return 0;
    case 0x6060: {
      if (const std::uint32_t e = expect_size(size, 1)) {
        return e;
      }
      const auto mode = static_cast<std::int8_t>(value);
      if (mode != 6 && mode != 8 && mode != 9 && mode != 10) {
        return abort::kInvalidValue;  // homing, CSP, CSV and CST are what this drive does
      }
      mode_ = mode;
      return 0;
    }
    case 0x607A:
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      target_position_ = static_cast<std::int32_t>(value);
      return 0;
    case 0x60FF:
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      target_velocity_ = static_cast<std::int32_t>(value);
      return 0;
    case 0x607C:
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      home_offset_ = static_cast<std::int32_t>(value);
      return 0;
    case 0x6085:
      if (const std::uint32_t e = expect_size(size, 4)) {
        return e;
      }
      if (value == 0) {
        return abort::kInvalidValue;  // a quick stop must stop
      }
      quick_stop_dec_ = value;
      return 0;
    case 0x6098: {
      if (const std::uint32_t e = expect_size(size, 1)) {
        return e;
      }
      const auto method = static_cast<std::int8_t>(value);
      if (method != 35 && method != 37) {
        return abort::kInvalidValue;  // no switches on a simulated axis: only "here is home"
      }
      homing_method_ = method;
      return 0;
    }
    default:
      return abort::kNoObject;
  }
}

}  // namespace mcnc::drivesim
