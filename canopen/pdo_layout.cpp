#include "canopen/pdo_layout.hpp"

namespace mcnc::canopen {

namespace {

constexpr std::uint32_t kInvalid = 0x80000000U;  // COB-ID bit 31: the PDO does not exist

void add(SdoWriteList& out, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
         std::uint8_t size) noexcept {
  out.writes[out.count++] = SdoWrite{index, sub, value, size};
}

}  // namespace

std::size_t PdoMapping::bytes() const noexcept {
  unsigned bits = 0;
  for (std::size_t i = 0; i < count && i < objects.size(); ++i) {
    bits += objects[i].bits;
  }
  return (bits + 7U) / 8U;
}

std::uint32_t PdoMapping::entry(const MappedObject& object) noexcept {
  return (static_cast<std::uint32_t>(object.index) << 16) |
         (static_cast<std::uint32_t>(object.sub) << 8) | object.bits;
}

MappedObject PdoMapping::object_of(std::uint32_t entry) noexcept {
  return MappedObject{static_cast<std::uint16_t>(entry >> 16),
                      static_cast<std::uint8_t>(entry >> 8), static_cast<std::uint8_t>(entry)};
}

const char* pdo_error(const PdoMapping& pdo) noexcept {
  if (pdo.number < 1 || pdo.number > 4) {
    return "a PDO's number is 1 to 4";
  }
  if (pdo.count > pdo.objects.size()) {
    return "a PDO maps at most 8 objects";
  }
  unsigned bits = 0;
  for (std::size_t i = 0; i < pdo.count; ++i) {
    const std::uint8_t b = pdo.objects[i].bits;
    if (b != 8 && b != 16 && b != 32) {
      return "a mapped object is 8, 16 or 32 bits long";
    }
    bits += b;
  }
  if (bits > 8U * PdoMapping::kMaxBytes) {
    return "the mapping is longer than the 8 bytes a classic CAN frame carries";
  }
  return nullptr;
}

const char* layout_error(const PdoLayout& layout) noexcept {
  for (const PdoMapping* pdo : {&layout.rpdo1, &layout.rpdo2, &layout.tpdo1, &layout.tpdo2}) {
    if (const char* error = pdo_error(*pdo)) {
      return error;
    }
  }
  return nullptr;
}

std::uint32_t pdo_cob_id(const PdoMapping& pdo, std::uint8_t node) noexcept {
  const std::uint32_t base = pdo.receive ? 0x200U : 0x180U;
  return base + 0x100U * static_cast<std::uint32_t>(pdo.number - 1) + node;
}

bool pdo_configuration(std::uint8_t node, const PdoMapping& pdo, SdoWriteList& out) noexcept {
  if (pdo.count == 0 || pdo_error(pdo) != nullptr) {
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
    add(out, mapping, static_cast<std::uint8_t>(i + 1), PdoMapping::entry(pdo.objects[i]), 4);
  }
  add(out, mapping, 0, static_cast<std::uint32_t>(pdo.count), 1);
  add(out, communication, 1, cob_id, 4);
  return true;
}

}  // namespace mcnc::canopen
