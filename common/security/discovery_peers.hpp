#pragma once
// Which participants of a secured machine discover each other (decision 137). DDS Security
// authenticates every pair of participants that discover each other, and on Cyclone DDS 0.10 a
// participant does its handshakes one after the other: a machine whose every participant
// discovers every other does a handshake per pair, most of them between processes that share
// no topic (two axis nodes of different channels). So a secured machine discovers without
// multicast: each process has a fixed participant index (its unicast discovery port follows
// from it and the domain) and announces itself to the processes it talks to alone, at
// 127.0.0.1 on one host, at the address of each one's host across hosts (decision 151).
// Pure: the machine file in, the indices and addresses out.
#include "common/config/machine_config.hpp"
#include "common/security/identity_files.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::security {

// Cyclone DDS 0.10 takes participant indices below 120 (its Discovery/ParticipantIndex); a
// larger machine keeps multicast discovery.
inline constexpr std::size_t kMaxIndexedParticipants = 120;

// The participants of `machine` that have an index, in index order: the channels, the axis
// nodes, the PLC when there is one, the HMI, the launcher and each host's launcher (as
// machine_identities names them). Empty for a machine of more than kMaxIndexedParticipants,
// or of several hosts one of which has no `address`.
[[nodiscard]] std::vector<std::string> indexed_participants(const config::MachineConfig& machine);

// `identity`'s index and peers: the launchers, the HMI and the PLC talk to every process and
// every process to them; the channels to each other (status, coordination); a channel to the
// axis nodes it may own, whose feedback it reads or whose coupling it commands; an axis node
// to the nodes it may follow or whose spindle it is synchronised to. The viewer peers with
// every process. `across_hosts`: the machine runs across the hosts of its `hosts:` section,
// and each peer is reached at its host's address; else all at 127.0.0.1. nullopt when
// indexed_participants is empty or names no such identity.
[[nodiscard]] std::optional<DiscoveryPeers> discovery_peers(const config::MachineConfig& machine,
                                                            const std::string& identity,
                                                            bool across_hosts = false);

// How many pairs of indexed participants discover each other: the handshakes of a start
// (against n(n-1)/2 when every participant discovers every other).
[[nodiscard]] std::size_t discovering_pairs(const config::MachineConfig& machine);

}  // namespace mcnc::security
