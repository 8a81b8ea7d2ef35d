#pragma once
// An axis node's set-up from the machine file: its roles (who may own it, what it may follow),
// its controller's limits and its drive's start-up (PDO mapping, mode, homing). Pure: config in,
// core types out.
#include "axisnode/node/axis_node.hpp"
#include "canopen/cia402/node_startup.hpp"
#include "common/config/machine_config.hpp"

#include <cstdint>
#include <vector>

namespace mcnc::axisnode {

// The drive's start-up: its PDOs (with the TPDO2 objects the axis asks for), its mode, homing
// and quick-stop deceleration.
canopen::NodeStartupConfig drive_startup_of(const config::AxisConfig& axis);

// The roles of `axis` in `machine`, with the controller set up for `startup`'s heartbeat.
AxisNodeRoles roles_of(const config::MachineConfig& machine, const config::AxisConfig& axis,
                       const canopen::NodeStartupConfig& startup);

// The node ids of the other drives on `axis`'s bus (their frames are not this node's).
std::vector<std::uint8_t> other_nodes_on_bus(const config::MachineConfig& machine,
                                             const config::AxisConfig& axis);

}  // namespace mcnc::axisnode
