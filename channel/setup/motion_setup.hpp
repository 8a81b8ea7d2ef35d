#pragma once
// The look-ahead planner's parameters for one channel of a machine file: its axes' limits in
// program order and the channel's `motion` settings.
#include "channel/motion/motion_planner.hpp"
#include "common/config/machine_config.hpp"

namespace mcnc::channel {

motion::MotionConfig motion_config_for(const config::MachineConfig& machine,
                                       const config::ChannelConfig& channel);

}  // namespace mcnc::channel
