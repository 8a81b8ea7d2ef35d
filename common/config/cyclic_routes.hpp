#pragma once
// Who uses which cyclic samples (ARCHITECTURE.md §7: a cyclic sample goes only to the readers that
// use it), from the machine file. Every process takes the keys of its cyclic writers and readers
// (each key a topic of its own, idl/topics.hpp) from here, so a writer and its readers agree on
// them by construction and the delivery of a cycle grows with the machine, not with its square.
#include "common/config/machine_config.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace mcnc::config {

// The key of an axis's setpoints and feedback: the name of the node that drives it (a C axis
// travels on its spindle's node).
[[nodiscard]] std::string node_key(const AxisConfig& axis);

// The axes whose feedback a channel reads, in its slot order: the axes it programs, its spindles,
// then the slaves of the G114.1 groups whose master it commands.
[[nodiscard]] std::vector<const AxisConfig*> fed_axes(const MachineConfig& machine,
                                                      const ChannelConfig& channel);

// The keys of `axes` (their nodes), each once.
[[nodiscard]] std::vector<std::string> node_keys(const std::vector<const AxisConfig*>& axes);
// The keys of every node of the machine (what an observer reads).
[[nodiscard]] std::vector<std::string> node_keys(const MachineConfig& machine);

// How many channels read the feedback of the node `node` (a node's name), for its discovery.
[[nodiscard]] std::size_t channels_fed_by(const MachineConfig& machine, const std::string& node);

// The names of the channels other than `self` (whose status a channel reads; all but itself).
[[nodiscard]] std::vector<std::string> other_channels(const MachineConfig& machine,
                                                      const ChannelConfig& self);

// The names of every channel (whose status the PLC reads).
[[nodiscard]] std::vector<std::string> channel_names(const MachineConfig& machine);

// The name of the channel or axis a wire id names (decision 1), for a person to read: "channel
// 7" or "axis 12" when the id is not in the machine file.
[[nodiscard]] std::string channel_name(const MachineConfig& machine, std::uint64_t id);
[[nodiscard]] std::string axis_name(const MachineConfig& machine, std::uint64_t id);

}  // namespace mcnc::config
