#pragma once
// What each identity of a machine may write, from its machine file (decision 70), and the
// governance and permissions documents that say so to DDS Security's builtin access control.
// Text only: signing and files are pki.hpp's and the `mcnc certs` command's.
#include "common/config/machine_config.hpp"

#include <string>
#include <vector>

namespace mcnc::security {

// The highest DDS domain a secured machine may run on: Cyclone DDS 0.10's access control reads
// no domain id above 230 in a governance or permissions document (the machine file allows 232).
inline constexpr int kMaxSecuredDomain = 230;

enum class Role { channel, axis_node, plc, hmi, launcher, viewer };

struct Identity {
  std::string name;  // the name its process gives its participant (CH1, X1, PLC, hmi, launch)
  Role role = Role::viewer;
  std::vector<std::string> publishes;  // DDS topic names, exact
};

// Every identity of the machine: each channel, each axis node, the PLC when there is one, the
// HMI, the launcher (one per host when the machine has hosts) and the viewer.
[[nodiscard]] std::vector<Identity> machine_identities(const config::MachineConfig& machine);

// The identity a participant of the machine presents, by the name it gives itself; nullptr for
// a name no identity has.
[[nodiscard]] const Identity* find_identity(const std::vector<Identity>& identities,
                                            const std::string& name);

// The identity's X.509 subject is one relative name, its common name "<identity>.<machine>", so
// that both implementations' comparisons (Cyclone DDS by attribute, Fast DDS in RFC 2253 order)
// agree; subject_name is "CN=" and it, as the permissions write it.
[[nodiscard]] std::string common_name(const std::string& machine, const std::string& identity);
[[nodiscard]] std::string subject_name(const std::string& machine, const std::string& identity);

// How the samples of the machine's topics are protected on the network (decision 71).
// access_control: authenticated participants and the permissions only; sign: each submessage
// also signed (GMAC); encrypt: also encrypted (AES-GCM), for a link between hosts that others
// can read.
enum class Protection { access_control, sign, encrypt };
[[nodiscard]] const char* protection_name(Protection protection) noexcept;

// Validity of the grants, as the documents write it: "YYYY-MM-DDTHH:MM:SS" (UTC).
struct Validity {
  std::string not_before;
  std::string not_after;
};

[[nodiscard]] std::string governance_xml(Protection protection);
[[nodiscard]] std::string permissions_xml(const std::string& machine,
                                          const std::vector<Identity>& identities,
                                          const Validity& validity);

}  // namespace mcnc::security
