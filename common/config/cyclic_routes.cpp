#include "common/config/cyclic_routes.hpp"

#include <algorithm>

namespace mcnc::config {

namespace {

void add_once(std::vector<std::string>& names, std::string name) {
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    names.push_back(std::move(name));
  }
}

}  // namespace

std::string node_key(const AxisConfig& axis) {
  return axis.spindle.empty() ? axis.name : axis.spindle;  // a C axis names its spindle
}

std::vector<const AxisConfig*> fed_axes(const MachineConfig& machine,
                                        const ChannelConfig& channel) {
  std::vector<const AxisConfig*> fed;
  for (const std::string& name : channel.program_axes()) {
    fed.push_back(machine.find_axis(name));
  }
  for (const std::string& name : channel.spindles) {
    fed.push_back(machine.find_axis(name));
  }
  for (const SpindleSyncGroup& g : machine.spindle_sync) {
    if (g.channel == channel.id) {
      fed.push_back(&machine.axes[static_cast<std::size_t>(g.slave - 1)]);
    }
  }
  return fed;
}

std::vector<std::string> node_keys(const std::vector<const AxisConfig*>& axes) {
  std::vector<std::string> names;
  for (const AxisConfig* a : axes) {
    if (a != nullptr) {
      add_once(names, node_key(*a));
    }
  }
  return names;
}

std::vector<std::string> node_keys(const MachineConfig& machine) {
  std::vector<const AxisConfig*> axes;
  for (const AxisConfig& a : machine.axes) {
    axes.push_back(&a);
  }
  return node_keys(axes);
}

std::size_t channels_fed_by(const MachineConfig& machine, const std::string& node) {
  std::size_t count = 0;
  for (const ChannelConfig& c : machine.channels) {
    const std::vector<std::string> nodes = node_keys(fed_axes(machine, c));
    count += std::find(nodes.begin(), nodes.end(), node) != nodes.end() ? 1 : 0;
  }
  return count;
}

std::vector<std::string> other_channels(const MachineConfig& machine, const ChannelConfig& self) {
  std::vector<std::string> names;
  for (const ChannelConfig& c : machine.channels) {
    if (c.id != self.id) {
      names.push_back(c.name);
    }
  }
  return names;
}

std::vector<std::string> channel_names(const MachineConfig& machine) {
  std::vector<std::string> names;
  for (const ChannelConfig& c : machine.channels) {
    names.push_back(c.name);
  }
  return names;
}

std::string channel_name(const MachineConfig& machine, std::uint64_t id) {
  const ChannelConfig* channel = machine.channel_by_id(id);
  return channel != nullptr ? channel->name : "channel " + std::to_string(id);
}

std::string axis_name(const MachineConfig& machine, std::uint64_t id) {
  const AxisConfig* axis = machine.axis_by_id(id);
  return axis != nullptr ? axis->name : "axis " + std::to_string(id);
}

}  // namespace mcnc::config
