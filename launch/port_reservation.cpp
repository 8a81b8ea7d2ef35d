#include "launch/port_reservation.hpp"

#include "common/process/process_node.hpp"
#include "common/security/discovery_peers.hpp"
#include "idl/discovery_port.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace mcnc::launch {

namespace {

constexpr const char* kRangeSetting = "/proc/sys/net/ipv4/ip_local_port_range";
constexpr const char* kReservedSetting = "/proc/sys/net/ipv4/ip_local_reserved_ports";
// Launchers of machines on other domains may reserve at the same moment: one at a time.
constexpr const char* kReservationLock = "/run/mcnc-reserved-ports.lock";

std::string read_setting(const char* path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string();
}

// Empty when written; else why not.
std::string add_reserved(const std::vector<PortRange>& ports) {
  const int lock = ::open(kReservationLock, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock >= 0) {
    (void)::flock(lock, LOCK_EX);
  }
  std::string why;
  const auto reserved = parse_port_list(read_setting(kReservedSetting));
  if (!reserved) {
    why = std::string("cannot read ") + kReservedSetting;
  } else {
    std::vector<PortRange> all = *reserved;
    all.insert(all.end(), ports.begin(), ports.end());
    const std::string text = port_list(all) + "\n";
    const int fd = ::open(kReservedSetting, O_WRONLY | O_CLOEXEC);
    if (fd < 0 || ::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
      why = std::string("cannot write ") + kReservedSetting + ": " + std::strerror(errno);
    }
    if (fd >= 0) {
      ::close(fd);
    }
  }
  if (lock >= 0) {
    ::close(lock);
  }
  return why;
}

}  // namespace

std::optional<PortRange> fixed_ports(const config::MachineConfig& machine, int domain) {
  // Fast DDS ignores the peers and the index (decision 137).
  if (machine.security_dir.empty() ||
      process::resolve_middleware(machine, "launch") != dds::Middleware::cyclonedds) {
    return std::nullopt;
  }
  const std::size_t indexed = security::indexed_participants(machine).size();
  if (indexed == 0) {
    return std::nullopt;
  }
  // Cyclone DDS's data port of an index is one above its discovery port.
  return PortRange{dds::unicast_discovery_port(domain, 0),
                   dds::unicast_discovery_port(domain, static_cast<int>(indexed) - 1) + 1};
}

bool reserve_fixed_ports(const config::MachineConfig& machine) {
  const int domain = process::resolve_domain(machine);
  const auto ports = fixed_ports(machine, domain);
  if (!ports) {
    return true;
  }
  const auto ephemeral = parse_port_range(read_setting(kRangeSetting));
  const auto reserved = parse_port_list(read_setting(kReservedSetting));
  if (!ephemeral || !reserved) {
    spdlog::warn(
        "cannot read {} or {}: not checked whether the machine's ports {} lie among "
        "the host's ephemeral ports",
        kRangeSetting, kReservedSetting, port_list({*ports}));
    return true;
  }
  const std::vector<PortRange> exposed = exposed_ports(*ports, *ephemeral, *reserved);
  if (exposed.empty()) {
    return true;
  }
  if (const std::string why = add_reserved(exposed); !why.empty()) {
    std::fprintf(stderr,
                 "error: machine.domain %d (or MCNC_DOMAIN): the secured machine's processes "
                 "listen on the fixed ports %s, and %s of them lie in this host's ephemeral "
                 "port range %s (net.ipv4.ip_local_port_range), where another program's "
                 "outgoing socket may take one; the launcher could not reserve them (%s). "
                 "Reserve them (sysctl -w net.ipv4.ip_local_reserved_ports=%s), or run the "
                 "machine on a domain whose ports lie below the range (0-101 with Linux's "
                 "default); nothing started\n",
                 domain, port_list({*ports}).c_str(), port_list(exposed).c_str(),
                 port_list({*ephemeral}).c_str(), why.c_str(),
                 port_list([&] {
                   std::vector<PortRange> all = *reserved;
                   all.insert(all.end(), exposed.begin(), exposed.end());
                   return all;
                 }())
                     .c_str());
    return false;
  }
  spdlog::info(
      "reserved the ports {} of this secured machine, which lie in the host's "
      "ephemeral range, in net.ipv4.ip_local_reserved_ports",
      port_list(exposed));
  return true;
}

}  // namespace mcnc::launch
