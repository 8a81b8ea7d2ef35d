#pragma once
// Which of a secured machine's fixed ports another program's outgoing socket may take
// (decision 150): Linux gives a socket that binds no port one of its ephemeral range
// (net.ipv4.ip_local_port_range), except those reserved (net.ipv4.ip_local_reserved_ports).
// Pure: the two settings' texts in, the ports to reserve out.
#include <optional>
#include <string>
#include <vector>

namespace mcnc::launch {

struct PortRange {
  int first = 0;
  int last = 0;  // inclusive
  bool operator==(const PortRange&) const = default;
};

// net.ipv4.ip_local_port_range as the kernel shows it ("32768\t60999\n"); nullopt when it is
// not two ports, the first not above the second.
[[nodiscard]] std::optional<PortRange> parse_port_range(const std::string& text);
// net.ipv4.ip_local_reserved_ports as the kernel shows it ("" or "7410-7430,8000\n"); nullopt
// when malformed.
[[nodiscard]] std::optional<std::vector<PortRange>> parse_port_list(const std::string& text);
// The ports of `wanted` in `ephemeral` and not in `reserved`, as ranges in order.
[[nodiscard]] std::vector<PortRange> exposed_ports(PortRange wanted, PortRange ephemeral,
                                                   const std::vector<PortRange>& reserved);
// "a-b,c" (the form the kernel reads back).
[[nodiscard]] std::string port_list(const std::vector<PortRange>& ranges);

}  // namespace mcnc::launch
