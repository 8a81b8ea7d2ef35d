#pragma once
// A node's PDO layout: which objects each of its PDOs carries, in order (CiA 301 §7.5.2.35-
// 7.5.2.38). The one description both ends use: the master writes it to the node by SDO at
// start-up (pdo_configuration), and packs and unpacks the PDO frames by it (pack, unpack); the
// node reads its own mapping objects back into a PdoMapping to do the same. Classic CAN: a PDO
// carries at most 8 bytes, and a mapping beyond them is refused (pdo_error). Pure, no
// allocation.
#include "common/can/can_frame.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::canopen {

struct MappedObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;  // 8, 16 or 32
};

// One PDO: its direction, number, transmission type and the objects it maps, in frame order.
struct PdoMapping {
  static constexpr std::size_t kMaxObjects = 8;
  static constexpr std::size_t kMaxBytes = 8;  // classic CAN

  bool receive = true;                 // RPDO (master -> node) or TPDO
  std::uint8_t number = 1;             // 1..4
  std::uint8_t transmission_type = 1;  // 1: synchronous, every SYNC
  std::array<MappedObject, kMaxObjects> objects{};
  std::size_t count = 0;

  // The frame's length in bytes (bits rounded up).
  [[nodiscard]] std::size_t bytes() const noexcept;
  // A mapping entry as the mapping object holds it: index << 16 | sub << 8 | bits.
  [[nodiscard]] static std::uint32_t entry(const MappedObject& object) noexcept;
  [[nodiscard]] static MappedObject object_of(std::uint32_t entry) noexcept;
};

// The PDOs of a node this project maps: RPDO1, RPDO2, TPDO1, TPDO2. A PDO with count 0 is not
// written at start-up (the node keeps its own) and not used by the master.
struct PdoLayout {
  PdoMapping rpdo1;
  PdoMapping rpdo2;
  PdoMapping tpdo1;
  PdoMapping tpdo2;
};

// Why `pdo` cannot be mapped, e.g. "TPDO1 maps 80 bits: a CAN frame carries 64"; nullptr when
// it can (an empty PDO can: it is not written).
const char* pdo_error(const PdoMapping& pdo) noexcept;
// The first PDO of `layout` that cannot be mapped, and why; nullptr when every one can.
const char* layout_error(const PdoLayout& layout) noexcept;

struct SdoWrite {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint32_t value = 0;
  std::uint8_t size = 0;  // bytes: 1, 2 or 4
};

struct SdoWriteList {
  std::array<SdoWrite, 16> writes{};
  std::size_t count = 0;
};

// The default COB-ID of a PDO (CiA 301 pre-defined connection set).
std::uint32_t pdo_cob_id(const PdoMapping& pdo, std::uint8_t node) noexcept;

// The writes that configure `pdo` on `node`, in the order the standard requires: invalidate the
// PDO (COB-ID bit 31), set the transmission type, clear the mapping count, write each entry,
// set the count, validate the COB-ID. False (nothing written) when the mapping is empty or
// pdo_error() names a reason.
bool pdo_configuration(std::uint8_t node, const PdoMapping& pdo, SdoWriteList& out) noexcept;

// The frame of `pdo` from `node`, each mapped object's value from value_of(index, sub) (its low
// `bits` bits, little endian). False when the mapping cannot be carried (pdo_error).
template <class ValueOf>
bool pack(const PdoMapping& pdo, std::uint8_t node, ValueOf&& value_of,
          can::CanFrame& out) noexcept;
// Each mapped object of `frame` to store(index, sub, raw, bits) (raw: the object's bits, zero
// extended; sign_extend() for signed objects). False, storing nothing, when the frame's length
// is not the mapped length (CiA 301: a PDO length error) or the mapping cannot be carried.
template <class Store>
bool unpack(const PdoMapping& pdo, const can::CanFrame& frame, Store&& store) noexcept;

// `raw` of `bits` bits as a two's complement value.
constexpr std::int32_t sign_extend(std::uint32_t raw, std::uint8_t bits) noexcept {
  if (bits >= 32) {
    return static_cast<std::int32_t>(raw);
  }
  const std::uint32_t sign = 1U << (bits - 1U);
  return static_cast<std::int32_t>((raw ^ sign) - sign);
}

template <class ValueOf>
bool pack(const PdoMapping& pdo, std::uint8_t node, ValueOf&& value_of,
          can::CanFrame& out) noexcept {
  if (pdo_error(pdo) != nullptr) {
    return false;
  }
  out = can::CanFrame{};
  out.id = pdo_cob_id(pdo, node);
  std::size_t at = 0;
  for (std::size_t i = 0; i < pdo.count; ++i) {
    const MappedObject& o = pdo.objects[i];
    const auto value = static_cast<std::uint32_t>(value_of(o.index, o.sub));
    for (std::size_t b = 0; b < o.bits / 8U; ++b) {
      out.data[at++] = static_cast<std::uint8_t>(value >> (8U * b));
    }
  }
  out.dlc = static_cast<std::uint8_t>(at);
  return true;
}

template <class Store>
bool unpack(const PdoMapping& pdo, const can::CanFrame& frame, Store&& store) noexcept {
  if (pdo_error(pdo) != nullptr || frame.dlc != pdo.bytes()) {
    return false;
  }
  std::size_t at = 0;
  for (std::size_t i = 0; i < pdo.count; ++i) {
    const MappedObject& o = pdo.objects[i];
    std::uint32_t raw = 0;
    for (std::size_t b = 0; b < o.bits / 8U; ++b) {
      raw |= static_cast<std::uint32_t>(frame.data[at++]) << (8U * b);
    }
    store(o.index, o.sub, raw, o.bits);
  }
  return true;
}

}  // namespace mcnc::canopen
