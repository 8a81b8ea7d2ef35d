#include "launch/machine_security.hpp"

#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/security/machine_permissions.hpp"
#include "launch/host_roudi.hpp"

#include <cstdio>

namespace mcnc::launch {

bool is_follower(const config::MachineConfig& machine, const std::string& host) {
  return !host.empty() && !machine.hosts.empty() && host != machine.hosts.front().name;
}

std::string launcher_identity(const config::MachineConfig& machine, const std::string& host) {
  return is_follower(machine, host) ? "launch-" + host : "launch";
}

std::vector<std::string> started_identities(const config::MachineConfig& machine,
                                            const std::string& host, bool with_hmi) {
  std::vector<std::string> names{launcher_identity(machine, host)};
  // host_of names the PLC and the HMI in lower case.
  const auto here = [&](const std::string& process) {
    if (host.empty()) {
      return true;
    }
    const config::HostConfig* runs_it = machine.host_of(process);
    return runs_it != nullptr && runs_it->name == host;
  };
  for (const config::AxisConfig& axis : machine.axes) {
    if (here(axis.name)) {
      names.push_back(axis.name);
    }
  }
  for (const config::ChannelConfig& channel : machine.channels) {
    if (here(channel.name)) {
      names.push_back(channel.name);
    }
  }
  if (machine.plc.present && here("plc")) {
    names.emplace_back("PLC");
  }
  if (with_hmi && here("hmi")) {
    names.emplace_back("hmi");
  }
  return names;
}

bool check_machine_security(const config::MachineConfig& machine, const std::string& host,
                            bool with_hmi) {
  if (machine.security_dir.empty()) {
    std::fprintf(stderr,
                 "warning: machine %s runs UNSECURED on DDS domain %d: its machine file names no "
                 "security_dir, so any participant on the network may command it "
                 "(docs/operations.md, \"Security\")\n",
                 machine.name.c_str(), process::resolve_domain(machine));
    return true;
  }
  const int domain = process::resolve_domain(machine);
  if (domain > security::kMaxSecuredDomain) {
    std::fprintf(stderr,
                 "error: a secured machine runs on DDS domains 0-%d (Cyclone DDS's access control "
                 "reads no higher one), not %d; nothing started\n",
                 security::kMaxSecuredDomain, domain);
    return false;
  }
  // Cyclone DDS 0.10 and Fast DDS 2.9 encode the handshake's Diffie-Hellman key differently:
  // between the two, half the handshakes fail (decision 73).
  const std::vector<std::string> processes = dds_process_names(machine, with_hmi);
  const dds::Middleware first = process::resolve_middleware(machine, processes.front());
  for (const std::string& process : processes) {
    const dds::Middleware middleware = process::resolve_middleware(machine, process);
    if (middleware != first) {
      std::fprintf(stderr,
                   "error: a secured machine runs every process on one DDS implementation, but %s "
                   "runs on %s and %s on %s (their DDS Security handshakes fail); nothing "
                   "started\n",
                   processes.front().c_str(), dds::middleware_name(first), process.c_str(),
                   dds::middleware_name(middleware));
      return false;
    }
  }
  for (const std::string& identity : started_identities(machine, host, with_hmi)) {
    if (const auto problem = process::security_problem(machine, identity)) {
      std::fprintf(stderr, "error: DDS Security identity %s: %s; nothing started\n",
                   identity.c_str(), problem->c_str());
      return false;
    }
  }
  return true;
}

}  // namespace mcnc::launch
