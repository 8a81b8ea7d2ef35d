#pragma once
// Where `mcnc certs` puts a machine's DDS Security files, and which of them a process presents
// (docs/operations.md, "Security"). One CA signs the identities, the governance and the
// permissions (decision 69); every identity shares the one permissions document, whose grant for
// its subject name says what it may write.
#include <optional>
#include <string>
#include <vector>

namespace mcnc::security {

// A participant's discovery peers on a secured machine (discovery_peers.hpp).
struct DiscoveryPeers {
  // Its own participant index; -1 for an onlooker (the viewer), whose ports are the system's
  // choice: it announces itself, and the processes answer it.
  int participant_index = -1;
  // The participant indices of the processes it announces itself to. A process it does not
  // name may still find it by announcing itself to it; so the relation is symmetric here.
  std::vector<int> peers;
  // Where each of `peers` listens: the address of the host that runs it, on a machine run
  // across its hosts; empty when every process runs on this host (127.0.0.1).
  std::vector<std::string> peer_addresses;
};

// The files a participant of the identity `name` is configured with (absolute when `dir` is).
struct IdentityFiles {
  std::string identity;        // the identity's name (a process of the machine, or "viewer")
  std::string ca_certificate;  // the identity CA: whose identities this one meets
  std::string permissions_ca;  // whose signature on the documents holds: the same CA here
  std::string certificate;     // the identity's own, signed by the CA
  std::string private_key;     // its key, unencrypted, readable by its owner only
  std::string governance;      // signed (S/MIME)
  std::string permissions;     // signed (S/MIME)
  // Not a file: whom it announces itself to instead of multicast (decision 137); none:
  // multicast discovery, as an unsecured participant.
  std::optional<DiscoveryPeers> discovery;
};

IdentityFiles identity_files(const std::string& dir, const std::string& identity);

// The files the CA keeps besides its certificate: its private key (move it off the machine
// once the identities are made) and the unsigned documents it signed, for reading.
std::string ca_key_file(const std::string& dir);
std::string governance_source_file(const std::string& dir);
std::string permissions_source_file(const std::string& dir);

// The identity of the machine's read-only onlookers (`mcnc status`, a user's DDS tool): it may
// write nothing.
inline constexpr const char* kViewerIdentity = "viewer";

}  // namespace mcnc::security
