#pragma once
// The log line of a lockstep cycle that waits long for its inputs (decision 7: such waits never
// give up, and say what they wait for): whose sample or events are missing, by name.
#include "axisnode/node/axis_node.hpp"
#include "common/config/machine_config.hpp"

#include <cstdint>
#include <string>

namespace mcnc::axisnode {

std::string input_wait_text(const AxisNode::InputWait& wait, std::uint64_t cycle,
                            const config::MachineConfig& machine);

}  // namespace mcnc::axisnode
