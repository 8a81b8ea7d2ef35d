#include "canopen/pdo_mapping.hpp"

namespace mcnc::canopen {

namespace {

constexpr std::uint32_t kInvalid = 0x80000000U;  // COB-ID bit 31: the PDO does not exist

void add(SdoWriteList& out, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
         std::uint8_t size) noexcept {
  out.writes[out.count++] = SdoWrite{index, sub, value, size};
}

PdoConfig pdo(bool receive, std::uint8_t number, std::initializer_list<MappedObject> objects) {
  PdoConfig p;
  p.receive = receive;
  p.number = number;
  for (const MappedObject& o : objects) {
    p.objects[p.count++] = o;
  }
  return p;
}

}  // namespace

std::uint32_t pdo_cob_id(const PdoConfig& pdo, std::uint8_t node) noexcept {
  const std::uint32_t base = pdo.receive ? 0x200U : 0x180U;
  return base + 0x100U * static_cast<std::uint32_t>(pdo.number - 1) + node;
}

bool pdo_configuration(std::uint8_t node, const PdoConfig& pdo, SdoWriteList& out) noexcept {
  if (pdo.number < 1 || pdo.number > 4 || pdo.count == 0 || pdo.count > pdo.objects.size()) {
    return false;
  }
  unsigned bits = 0;
  for (std::size_t i = 0; i < pdo.count; ++i) {
    bits += pdo.objects[i].bits;
  }
  if (bits > 64) {
    return false;
  }
  const auto offset = static_cast<std::uint16_t>(pdo.number - 1);
  const std::uint16_t communication = (pdo.receive ? 0x1400 : 0x1800) + offset;
  const std::uint16_t mapping = (pdo.receive ? 0x1600 : 0x1A00) + offset;
  const std::uint32_t cob_id = pdo_cob_id(pdo, node);
  out.count = 0;
  add(out, communication, 1, kInvalid | cob_id, 4);
  add(out, communication, 2, pdo.transmission_type, 1);
  add(out, mapping, 0, 0, 1);
  for (std::size_t i = 0; i < pdo.count; ++i) {
    const MappedObject& o = pdo.objects[i];
    add(out, mapping, static_cast<std::uint8_t>(i + 1),
        (static_cast<std::uint32_t>(o.index) << 16) | (static_cast<std::uint32_t>(o.sub) << 8) |
            o.bits,
        4);
  }
  add(out, mapping, 0, static_cast<std::uint32_t>(pdo.count), 1);
  add(out, communication, 1, cob_id, 4);
  return true;
}

AxisPdos axis_pdos(bool velocity_mode, bool velocity_actual, bool following_error) noexcept {
  AxisPdos p;
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

AxisPdos spindle_pdos() noexcept {
  AxisPdos p;
  p.rpdo1 = pdo(true, 1, {{0x6040, 0, 16}, {0x607A, 0, 32}, {0x6060, 0, 8}});
  p.rpdo2 = pdo(true, 2, {{0x60FF, 0, 32}});
  p.tpdo1 = pdo(false, 1, {{0x6041, 0, 16}, {0x6064, 0, 32}, {0x6061, 0, 8}});
  p.tpdo2 = pdo(false, 2, {});
  return p;
}

AxisPdos homing_axis_pdos() noexcept {
  AxisPdos p = spindle_pdos();
  p.rpdo2 = pdo(true, 2, {});
  return p;
}

}  // namespace mcnc::canopen
