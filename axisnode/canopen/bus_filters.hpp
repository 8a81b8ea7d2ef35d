#pragma once
// What each end of a CANopen bus needs to receive (for the transport's receive filter: on
// SocketCAN the kernel drops everything else). Pure.
#include "common/can/can_bus.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::canopen {

// The master of one node (an axis node): SYNC, the node's EMCY, TPDO1, TPDO2, SDO responses
// and heartbeat, and the RPDO1 of every other node of the bus (the lockstep SYNC waits for
// them). Returns how many filters it wrote; 0 when `out` is too small (then: no filter).
std::size_t master_filters(std::uint8_t node, std::span<const std::uint8_t> other_nodes,
                           std::span<can::CanFilter> out) noexcept;

// The drives of a bus (the simulator): NMT, SYNC, and for each drive its RPDO1, RPDO2 and SDO
// requests. 0 when `out` is too small.
std::size_t device_filters(std::span<const std::uint8_t> nodes,
                           std::span<can::CanFilter> out) noexcept;

}  // namespace mcnc::canopen
