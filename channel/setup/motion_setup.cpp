#include "channel/setup/motion_setup.hpp"

#include <algorithm>

namespace mcnc::channel {

motion::MotionConfig motion_config_for(const config::MachineConfig& machine,
                                       const config::ChannelConfig& channel) {
  motion::MotionConfig c;
  const std::vector<std::string> axes = channel.program_axes();
  c.axis_count = std::min(axes.size(), interp::kMaxChannelAxes);
  for (std::size_t i = 0; i < c.axis_count; ++i) {
    const config::AxisConfig* a = machine.find_axis(axes[i]);
    // The machine file gives rates per minute (as programs do), dynamics per second.
    c.axes[i] = motion::AxisDynamics{a->max_feed / 60.0, a->acceleration, a->jerk};
    c.rapid_rate[i] = a->rapid_rate / 60.0;
    if (a->address == 'X' && a->diameter) {
      c.css_axis = static_cast<int>(i);  // G96 measures the radius on the diameter axis
    }
  }
  c.cycle_s = machine.cycle_s();
  c.lookahead_blocks = static_cast<std::size_t>(channel.motion.lookahead_blocks);
  c.path_tolerance = channel.motion.path_tolerance;
  c.jerk_limited = channel.motion.jerk_limited;
  c.rapid_interpolated = channel.motion.rapid_interpolated;
  return c;
}

}  // namespace mcnc::channel
