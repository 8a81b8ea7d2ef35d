#pragma once
// A channel's controller set-up from the machine file: its axes in program order (its own,
// those it may acquire with G141, then its spindle's C axis on the spindle's node), its
// spindles, and what the controller knows of each (slots, in-position widths, couplings, the
// G114.1 groups it leads).
#include "channel/control/channel_controller.hpp"
#include "common/config/machine_config.hpp"

#include <vector>

namespace mcnc::channel {

struct ControllerLayout {
  std::vector<const config::AxisConfig*> axes;      // program order
  std::vector<const config::AxisConfig*> spindles;  // the channel's spindles
  ChannelSetup setup;                               // shared_writes left to the caller
};

ControllerLayout controller_layout_for(const config::MachineConfig& machine,
                                       const config::ChannelConfig& channel);

}  // namespace mcnc::channel
