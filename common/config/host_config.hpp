#pragma once
// The `hosts:` section of a machine file: the controller hosts (NCUs) a machine spans and which
// of its processes each runs (docs/configuration.md "Hosts"). A machine without it runs on one
// host.
#include <string>
#include <vector>

namespace mcnc::config {

// The shortest cycle a machine whose channels command axes on other hosts may have, unless the
// machine file names its link's own (machine.link_cycle_us): the link axes' setpoints cross the
// network once a cycle, and the SINUMERIK NCU link runs its position cycle at 2-4 ms.
inline constexpr int kDefaultLinkCycleUs = 2000;

struct HostConfig {
  std::string name;
  // Where its peers reach it on the controllers' network (an IPv4 address or a host name);
  // empty: found by DDS discovery alone.
  std::string address;
  // What it runs, by name: channels, axis nodes (axes and spindles), buses (a bus is wired to
  // one host, with its drives or their simulator), `plc` and `hmi`.
  std::vector<std::string> runs;
};

}  // namespace mcnc::config
