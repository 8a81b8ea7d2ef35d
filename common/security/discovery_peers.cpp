#include "common/security/discovery_peers.hpp"

#include "common/config/cyclic_routes.hpp"
#include "common/security/machine_permissions.hpp"

#include <algorithm>

namespace mcnc::security {

namespace {

// Who discovers whom among indexed_participants, as a symmetric matrix by index.
class TalkGraph {
 public:
  explicit TalkGraph(const config::MachineConfig& machine)
      : names_(indexed_participants(machine)), links_(names_.size() * names_.size(), false) {
    std::vector<std::string> hubs{"launch", "hmi", "PLC"};
    for (const config::HostConfig& host : machine.hosts) {
      hubs.push_back("launch-" + host.name);  // a host's launcher watches its processes
    }
    for (const std::string& hub : hubs) {
      for (const std::string& other : names_) {
        link(hub, other);
      }
    }
    for (const config::ChannelConfig& a : machine.channels) {
      for (const config::ChannelConfig& b : machine.channels) {
        link(a.name, b.name);
      }
    }
    for (const config::AxisConfig& axis : machine.axes) {
      link(axis.channel, axis.name);  // its home channel
      link_axes(machine, axis.id, axis.sync_master);
      if (axis.sync_slave) {
        // G51.4: it may follow any axis of its type that follows none (AxisNodeRoles::leaders).
        for (const config::AxisConfig& leader : machine.axes) {
          if (leader.type == axis.type && !leader.sync_slave) {
            link(axis.name, leader.name);
          }
        }
      }
    }
    for (const config::ChannelConfig& channel : machine.channels) {
      for (const std::string& axis : channel.exchange_axes) {
        link(channel.name, axis);
      }
      for (const config::AxisConfig* axis : config::fed_axes(machine, channel)) {
        if (axis != nullptr) {
          link(channel.name, axis->name);
          link(channel.name, config::node_key(*axis));
        }
      }
      link_coupling(machine, channel, channel.polygon_master, channel.polygon_slave);
      link_coupling(machine, channel, channel.cam_master, channel.cam_slave);
      // G81.4: the work axis follows the tool spindle, and the axial axis as a leader.
      link_coupling(machine, channel, channel.egb_tool, channel.egb_work);
      link_axes(machine, channel.egb_work, channel.egb_axial);
    }
    for (const config::SpindleSyncGroup& group : machine.spindle_sync) {
      const config::ChannelConfig* channel = machine.channel_by_id(group.channel);
      if (channel != nullptr) {
        link_coupling(machine, *channel, group.master, group.slave);
      }
    }
  }

  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] int index_of(const std::string& name) const {
    const auto it = std::find(names_.begin(), names_.end(), name);
    return it == names_.end() ? -1 : static_cast<int>(it - names_.begin());
  }
  [[nodiscard]] bool linked(std::size_t a, std::size_t b) const {
    return links_[a * names_.size() + b];
  }

 private:
  void link(const std::string& a, const std::string& b) {
    const int i = index_of(a);
    const int j = index_of(b);
    if (i < 0 || j < 0 || i == j) {
      return;
    }
    const auto n = names_.size();
    links_[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)] = true;
    links_[static_cast<std::size_t>(j) * n + static_cast<std::size_t>(i)] = true;
  }
  // Axes by their ids (0: none).
  void link_axes(const config::MachineConfig& machine, int a, int b) {
    const config::AxisConfig* first = machine.axis_by_id(static_cast<std::uint64_t>(a));
    const config::AxisConfig* second = machine.axis_by_id(static_cast<std::uint64_t>(b));
    if (first != nullptr && second != nullptr) {
      link(first->name, second->name);
    }
  }
  // A coupling the channel commands: its master and its slave, and both with the channel.
  void link_coupling(const config::MachineConfig& machine, const config::ChannelConfig& channel,
                     int master, int slave) {
    link_axes(machine, master, slave);
    for (const int id : {master, slave}) {
      if (const config::AxisConfig* axis = machine.axis_by_id(static_cast<std::uint64_t>(id))) {
        link(channel.name, axis->name);
      }
    }
  }

  std::vector<std::string> names_;
  std::vector<bool> links_;
};

// The address of the host that runs the participant `name` (an identity's name).
std::string host_address(const config::MachineConfig& machine, const std::string& name) {
  const config::HostConfig* host = nullptr;
  if (name == "launch") {
    host = &machine.hosts.front();  // the first host's launcher runs the machine
  } else if (name.rfind("launch-", 0) == 0) {
    for (const config::HostConfig& h : machine.hosts) {
      host = "launch-" + h.name == name ? &h : host;
    }
  } else {
    host = machine.host_of(name == "PLC" ? "plc" : name);  // host_of names the PLC in lower case
  }
  return host == nullptr ? std::string() : host->address;
}

}  // namespace

std::vector<std::string> indexed_participants(const config::MachineConfig& machine) {
  for (const config::HostConfig& host : machine.hosts) {
    if (host.address.empty()) {
      return {};  // no index says where a process of that host listens
    }
  }
  std::vector<std::string> names;
  for (const Identity& identity : machine_identities(machine)) {
    if (identity.role != Role::viewer) {
      names.push_back(identity.name);
    }
  }
  if (names.size() > kMaxIndexedParticipants) {
    return {};
  }
  return names;
}

std::optional<DiscoveryPeers> discovery_peers(const config::MachineConfig& machine,
                                              const std::string& identity, bool across_hosts) {
  const TalkGraph graph(machine);
  const std::size_t n = graph.names().size();
  if (n == 0) {
    return std::nullopt;
  }
  DiscoveryPeers peers;
  if (identity != kViewerIdentity) {
    peers.participant_index = graph.index_of(identity);
    if (peers.participant_index < 0) {
      return std::nullopt;
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (peers.participant_index < 0 ||
        graph.linked(static_cast<std::size_t>(peers.participant_index), j)) {
      peers.peers.push_back(static_cast<int>(j));
      if (across_hosts && !machine.hosts.empty()) {
        peers.peer_addresses.push_back(host_address(machine, graph.names()[j]));
      }
    }
  }
  return peers;
}

std::size_t discovering_pairs(const config::MachineConfig& machine) {
  const TalkGraph graph(machine);
  const std::size_t n = graph.names().size();
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      pairs += graph.linked(i, j) ? 1 : 0;
    }
  }
  return pairs;
}

}  // namespace mcnc::security
