#pragma once
// The interpreter parameters of one channel of a machine file: its axes in program order (the
// program address letter, diameter programming) and its channel number.
#include "channel/interp/interp_config.hpp"
#include "common/config/machine_config.hpp"

namespace mcnc::channel {

interp::InterpreterConfig interpreter_config_for(const config::MachineConfig& machine,
                                                 const config::ChannelConfig& channel);

}  // namespace mcnc::channel
