#pragma once
// PDO mapping by SDO at start-up (CiA 301 §7.5.2.35-7.5.2.38): what a master writes to a node
// to map objects into one of its PDOs, in the order the standard requires: invalidate the PDO
// (COB-ID bit 31), set the transmission type, clear the mapping count, write each entry
// (index << 16 | sub << 8 | bits), set the count, validate the COB-ID. Pure.
#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::canopen {

struct MappedObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;  // 8, 16 or 32
};

struct PdoConfig {
  bool receive = true;                 // RPDO (master -> node) or TPDO
  std::uint8_t number = 1;             // 1..4
  std::uint8_t transmission_type = 1;  // 1: synchronous, every SYNC
  std::array<MappedObject, 8> objects{};
  std::size_t count = 0;
};

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
std::uint32_t pdo_cob_id(const PdoConfig& pdo, std::uint8_t node) noexcept;

// The writes that configure `pdo` on `node`; false (and nothing written) when the mapping is
// empty, holds more than 8 objects or more than 64 bits, or the PDO number is not 1..4.
bool pdo_configuration(std::uint8_t node, const PdoConfig& pdo, SdoWriteList& out) noexcept;

// The PDOs of an axis drive (CiA 402): RPDO1 controlword 0x6040 and target position 0x607A
// (CSP) or target velocity 0x60FF (CSV); TPDO1 statusword 0x6041 and position actual 0x6064;
// TPDO2, only when asked (it costs a frame per axis and cycle on the bus), velocity actual
// 0x606C and/or following error actual 0x60F4. A PDO with count 0 is left as the node has it.
struct AxisPdos {
  PdoConfig rpdo1;
  PdoConfig rpdo2;
  PdoConfig tpdo1;
  PdoConfig tpdo2;
};
AxisPdos axis_pdos(bool velocity_mode, bool velocity_actual, bool following_error) noexcept;

// The PDOs of a spindle drive that switches between CSV (turning) and CSP (positioning,
// synchronisation) in operation, cycle by cycle: RPDO1 controlword 0x6040, target position
// 0x607A and modes of operation 0x6060 (7 bytes); RPDO2 target velocity 0x60FF; TPDO1
// statusword 0x6041, position actual 0x6064 and modes of operation display 0x6061 (7 bytes).
AxisPdos spindle_pdos() noexcept;
// The PDOs of an axis that homes at start-up (mode 6, then CSP): a spindle's RPDO1 and TPDO1
// (the modes of operation and its display travel with them), no RPDO2.
AxisPdos homing_axis_pdos() noexcept;

}  // namespace mcnc::canopen
