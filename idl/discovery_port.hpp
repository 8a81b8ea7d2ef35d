#pragma once
// Where a Cyclone DDS participant with a fixed participant index listens for discovery
// (security::DiscoveryPeers, decision 137).

namespace mcnc::dds {

// The unicast discovery port of participant index `participant_index` on `domain`: the DDSI port
// mapping with Cyclone DDS's defaults, base 7400, domain gain 250, participant gain 2 and
// unicast discovery offset 10.
constexpr int unicast_discovery_port(int domain, int participant_index) noexcept {
  return 7400 + 250 * domain + 10 + 2 * participant_index;
}

}  // namespace mcnc::dds
