#pragma once
// What each end of a CANopen bus needs to receive (for the transport's receive filter: on
// SocketCAN the kernel drops everything else). Pure.
#include "common/can/can_bus.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::canopen {

// The master of one node (an axis node): the node's EMCY, TPDO1, TPDO2, SDO responses and
// heartbeat; the bus's SYNC producer also SYNC and the RPDO1 of every other node of the bus (its
// lockstep SYNC waits for them). Any other node awaits only its own drive's answer to the SYNC,
// so those frames would only wake it. Returns how many filters it wrote; 0 when `out` is too
// small (then: no filter).
std::size_t master_filters(std::uint8_t node, bool sync_producer,
                           std::span<const std::uint8_t> other_nodes,
                           std::span<can::CanFilter> out) noexcept;

// The drives of a bus (the simulator): NMT, SYNC, and for each drive its RPDO1, RPDO2 and SDO
// requests. 0 when `out` is too small.
std::size_t device_filters(std::span<const std::uint8_t> nodes,
                           std::span<can::CanFilter> out) noexcept;

}  // namespace mcnc::canopen
