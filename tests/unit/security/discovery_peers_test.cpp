#include "common/security/discovery_peers.hpp"

#include "axisnode/setup/axis_node_setup.hpp"
#include "common/config/cyclic_routes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

using namespace mcnc;
using ::testing::Contains;
using ::testing::Not;

namespace {

const std::string kSourceDir = MCNC_SOURCE_DIR;

config::MachineConfig machine_file(const std::string& name) {
  return config::load_machine_file(kSourceDir + "/launch/machines/" + name);
}

// The names `identity` announces itself to.
std::set<std::string> peers_of(const config::MachineConfig& machine, const std::string& identity) {
  const std::vector<std::string> names = security::indexed_participants(machine);
  const auto peers = security::discovery_peers(machine, identity);
  if (!peers) {
    throw std::runtime_error("no discovery peers for " + identity);
  }
  std::set<std::string> out;
  for (const int index : peers->peers) {
    out.insert(names.at(static_cast<std::size_t>(index)));
  }
  return out;
}

// The scale bench's machine (bench/bench_machine.py): `n` channels of X and Z, four axes a bus.
config::MachineConfig scale_machine(int n) {
  std::string yaml = "machine:\n  name: scale\n  cycle_us: 2000\nbuses:\n";
  for (int b = 0; b < (2 * n + 3) / 4; ++b) {
    yaml += "  - name: can" + std::to_string(b) + "\n    uri: udp:239.255.213." +
            std::to_string(b + 1) + ":" + std::to_string(24213 + 300 * b) +
            "\n    bitrate: 1000000\n    sync_producer: X" + std::to_string(2 * b + 1) +
            "\n";  // the bus's first axis
  }
  yaml += "channels:\n";
  for (int c = 1; c <= n; ++c) {
    yaml += "  - name: CH" + std::to_string(c) + "\n    axes: [X" + std::to_string(c) + ", Z" +
            std::to_string(c) + "]\n";
  }
  yaml += "axes:\n";
  int i = 0;
  for (int c = 1; c <= n; ++c) {
    for (const char* address : {"X", "Z"}) {
      yaml += "  - name: " + std::string(address) + std::to_string(c) +
              "\n    address: " + address + "\n    type: linear\n    bus: can" +
              std::to_string(i / 4) + "\n    node_id: " + std::to_string(i % 4 + 1) +
              "\n    counts_per_unit: 10000\n    rapid_rate: 8000\n    max_feed: 5000\n"
              "    acceleration: 1500\n    drive:\n      max_velocity: 200\n";
      ++i;
    }
  }
  const std::string path =
      ::testing::TempDir() + "/discovery_peers_scale_" + std::to_string(n) + ".yaml";
  std::ofstream(path) << yaml;
  return config::load_machine_file(path);
}

}  // namespace

TEST(DiscoveryPeers, EveryIndexedParticipantHasItsOwnIndexBelowCycloneDdsLimit) {
  const config::MachineConfig machine = machine_file("twin_turret.yaml");
  const std::vector<std::string> names = security::indexed_participants(machine);
  ASSERT_FALSE(names.empty());
  EXPECT_LE(names.size(), security::kMaxIndexedParticipants);
  std::set<int> indices;
  for (const std::string& name : names) {
    const auto peers = security::discovery_peers(machine, name);
    ASSERT_TRUE(peers) << name;
    EXPECT_TRUE(indices.insert(peers->participant_index).second) << name;
    EXPECT_THAT(peers->peers, Not(Contains(peers->participant_index))) << name;
  }
  EXPECT_THAT(names, Contains("launch"));
  EXPECT_THAT(names, Contains("hmi"));
}

TEST(DiscoveryPeers, TheViewerHasNoIndexAndAnnouncesItselfToEveryProcess) {
  const config::MachineConfig machine = machine_file("twin_turret.yaml");
  const auto viewer = security::discovery_peers(machine, security::kViewerIdentity);
  ASSERT_TRUE(viewer);
  EXPECT_EQ(viewer->participant_index, -1);
  EXPECT_EQ(viewer->peers.size(), security::indexed_participants(machine).size());
}

TEST(DiscoveryPeers, TheLauncherMeetsEveryProcessAndTwoAxisNodesOfTwoChannelsNeverMeet) {
  const config::MachineConfig machine = scale_machine(4);
  const std::vector<std::string> names = security::indexed_participants(machine);
  std::set<std::string> others(names.begin(), names.end());
  others.erase("launch");
  EXPECT_EQ(peers_of(machine, "launch"), others);
  // X1 reads its channel's setpoints; nothing of X2's, nor of Z1's (no topic between two
  // axis nodes that do not follow each other).
  EXPECT_EQ(peers_of(machine, "X1"), (std::set<std::string>{"launch", "hmi", "CH1"}));
  EXPECT_EQ(peers_of(machine, "CH1"),
            (std::set<std::string>{"launch", "hmi", "CH2", "CH3", "CH4", "X1", "Z1"}));
}

TEST(DiscoveryPeers, TheScaleMachineAtSixteenChannelsDiscoversAFifthOfItsPairs) {
  const config::MachineConfig machine = scale_machine(16);
  // 16 channels, 32 axis nodes, the HMI and the launcher: 50 participants, 1 225 pairs when
  // every one discovers every other. Here: the launcher and the HMI with every other (48 + 48
  // + 1), the channels among themselves (120), each axis node with its channel (32).
  ASSERT_EQ(security::indexed_participants(machine).size(), 50U);
  EXPECT_EQ(security::discovering_pairs(machine), 97U + 120U + 32U);
}

TEST(DiscoveryPeers, AMachineOfSeveralHostsOneOfWhichHasNoAddressKeepsMulticastDiscovery) {
  config::MachineConfig machine = machine_file("cell_3ncu.yaml");
  ASSERT_EQ(machine.hosts.size(), 3U);
  machine.hosts[0].address = "10.77.0.1";
  machine.hosts[1].address = "10.77.0.2";
  EXPECT_TRUE(security::indexed_participants(machine).empty());
  EXPECT_FALSE(security::discovery_peers(machine, "launch", true));
}

// Across hosts each peer is reached at the address of the host that runs it (decision 151);
// run on one host, at 127.0.0.1 (no addresses).
TEST(DiscoveryPeers, AcrossHostsEachPeerIsReachedAtItsHostsAddress) {
  config::MachineConfig machine = machine_file("cell_3ncu.yaml");
  ASSERT_EQ(machine.hosts.size(),
            3U);  // ncu1: CH1 X1 Z1 A1 S1 plc hmi, ncu2: CH2 ..., ncu3: CH3 X3
  for (std::size_t h = 0; h < 3; ++h) {
    machine.hosts[h].address = "10.77.0." + std::to_string(h + 1);
  }
  const std::vector<std::string> names = security::indexed_participants(machine);
  EXPECT_THAT(names, Contains("launch-ncu2"));
  const auto peers = security::discovery_peers(machine, "X3", true);
  ASSERT_TRUE(peers);
  ASSERT_EQ(peers->peer_addresses.size(), peers->peers.size());
  std::map<std::string, std::string> where;
  for (std::size_t k = 0; k < peers->peers.size(); ++k) {
    where[names.at(static_cast<std::size_t>(peers->peers[k]))] = peers->peer_addresses[k];
  }
  // Its channel, the launchers (the machine's on ncu1, its host's), the PLC and the HMI.
  EXPECT_EQ(where.at("CH3"), "10.77.0.3");
  EXPECT_EQ(where.at("launch"), "10.77.0.1");
  EXPECT_EQ(where.at("launch-ncu3"), "10.77.0.3");
  EXPECT_EQ(where.at("launch-ncu2"), "10.77.0.2");
  EXPECT_EQ(where.at("PLC"), "10.77.0.1");
  EXPECT_EQ(where.at("hmi"), "10.77.0.1");
  EXPECT_EQ(where.count("X1"), 0U);
  EXPECT_TRUE(security::discovery_peers(machine, "X3", false)->peer_addresses.empty());
  const auto viewer = security::discovery_peers(machine, security::kViewerIdentity, true);
  ASSERT_TRUE(viewer);
  EXPECT_EQ(viewer->peer_addresses.size(), names.size());
}

// Every reader a process makes of another process's topic has that process among its peers:
// what the axis node's roles say it reads (setpoints and events of its candidates, its
// leaders', its master's and its sync channel's samples) and the feedback a channel reads.
TEST(DiscoveryPeers, EveryExampleMachineDiscoversWhatItsProcessesRead) {
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir + "/launch/machines")) {
    const config::MachineConfig machine = config::load_machine_file(entry.path().string());
    if (!machine.hosts.empty()) {
      continue;
    }
    SCOPED_TRACE(entry.path().filename().string());
    for (const config::AxisConfig& axis : machine.axes) {
      const std::set<std::string> peers = peers_of(machine, axis.name);
      const axisnode::AxisNodeRoles roles =
          axisnode::roles_of(machine, axis, axisnode::drive_startup_of(axis));
      for (const std::uint32_t channel : roles.candidates) {
        EXPECT_THAT(peers, Contains(machine.channel_by_id(channel)->name)) << axis.name;
      }
      for (const std::uint32_t leader : roles.leaders) {
        EXPECT_THAT(peers, Contains(machine.axis_by_id(leader)->name)) << axis.name;
      }
      for (const std::uint32_t master : {roles.sync_master, roles.power_on_master}) {
        if (master != 0) {
          EXPECT_THAT(peers, Contains(machine.axis_by_id(master)->name)) << axis.name;
        }
      }
      if (roles.sync_channel != 0) {
        EXPECT_THAT(peers, Contains(machine.channel_by_id(roles.sync_channel)->name)) << axis.name;
      }
    }
    for (const config::ChannelConfig& channel : machine.channels) {
      const std::set<std::string> peers = peers_of(machine, channel.name);
      for (const std::string& node : config::node_keys(config::fed_axes(machine, channel))) {
        EXPECT_THAT(peers, Contains(node)) << channel.name;
      }
      for (const std::string& other : config::other_channels(machine, channel)) {
        EXPECT_THAT(peers, Contains(other)) << channel.name;
      }
      EXPECT_THAT(peers, Contains("launch"));
      if (machine.plc.present) {
        EXPECT_THAT(peers, Contains("PLC"));
      }
    }
  }
}
