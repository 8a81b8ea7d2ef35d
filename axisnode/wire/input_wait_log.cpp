#include "axisnode/wire/input_wait_log.hpp"

#include "common/process/lockstep_wait_log.hpp"

#include <spdlog/fmt/fmt.h>

namespace mcnc::axisnode {

namespace {

// Ids are 1-based positions in the machine file (decision 1).
template <class List>
std::string name_of(const List& list, std::uint32_t id) {
  return id >= 1 && id <= list.size() ? list[id - 1].name : fmt::format("#{}", id);
}

}  // namespace

std::string input_wait_text(const AxisNode::InputWait& wait, std::uint64_t cycle,
                            const config::MachineConfig& machine) {
  using From = AxisNode::InputWait::From;
  switch (wait.from) {
    case From::leader:
      return fmt::format("cycle {} still waits for {}'s feedback of cycle {}, the axis it follows",
                         cycle, name_of(machine.axes, wait.id), cycle - 1);
    case From::master:
      return process::lockstep_wait_text(cycle, name_of(machine.axes, wait.id) + "'s feedback",
                                         wait.gate);
    case From::coupling_channel:
      return process::lockstep_wait_text(cycle, name_of(machine.channels, wait.id) + "'s status",
                                         wait.gate);
    case From::channel:
      break;
  }
  return process::lockstep_wait_text(cycle, name_of(machine.channels, wait.id) + "'s setpoints",
                                     wait.gate);
}

}  // namespace mcnc::axisnode
