#pragma once
// A secured machine's fixed discovery ports kept from other programs' outgoing sockets
// (decision 150).
#include "common/config/machine_config.hpp"
#include "launch/ephemeral_ports.hpp"

#include <optional>

namespace mcnc::launch {

// The ports a secured machine's processes listen on by their participant index (decision
// 137): each one's unicast discovery port and the data port above it. nullopt when they are the
// system's choice (an unsecured machine, or one whose processes have no index).
[[nodiscard]] std::optional<PortRange> fixed_ports(const config::MachineConfig& machine,
                                                   int domain);

// Before anything starts: when some of those ports lie in the host's ephemeral range
// (net.ipv4.ip_local_port_range) and are not reserved, reserves them
// (net.ipv4.ip_local_reserved_ports, which the launcher only ever adds to) and says so; false,
// after printing why on stderr, when it cannot.
bool reserve_fixed_ports(const config::MachineConfig& machine);

}  // namespace mcnc::launch
