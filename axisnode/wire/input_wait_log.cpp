#include "axisnode/wire/input_wait_log.hpp"

#include "common/config/cyclic_routes.hpp"
#include "common/process/lockstep_wait_log.hpp"

#include <spdlog/fmt/fmt.h>

namespace mcnc::axisnode {

std::string input_wait_text(const AxisNode::InputWait& wait, std::uint64_t cycle,
                            const config::MachineConfig& machine) {
  using From = AxisNode::InputWait::From;
  switch (wait.from) {
    case From::leader:
      return fmt::format("cycle {} still waits for {}'s feedback of cycle {}, the axis it follows",
                         cycle, config::axis_name(machine, wait.id), cycle - 1);
    case From::master:
      return process::lockstep_wait_text(cycle, config::axis_name(machine, wait.id) + "'s feedback",
                                         wait.gate);
    case From::coupling_channel:
      return process::lockstep_wait_text(
          cycle, config::channel_name(machine, wait.id) + "'s status", wait.gate);
    case From::channel:
      break;
  }
  return process::lockstep_wait_text(cycle, config::channel_name(machine, wait.id) + "'s setpoints",
                                     wait.gate);
}

}  // namespace mcnc::axisnode
