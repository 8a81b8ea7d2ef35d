#include "common/can/can_bus.hpp"
#include "common/can/transport/socketcan_can_bus.hpp"
#include "common/can/transport/udp_can_bus.hpp"

#include <arpa/inet.h>
#include <net/if.h>
#include <charconv>
#include <stdexcept>
#include <string_view>

namespace mcnc::can {
namespace {

[[noreturn]] void bad_uri(const std::string& uri, const std::string& reason) {
  throw std::runtime_error("CAN bus \"" + uri + "\": " + reason +
                           " (expected udp:GROUP:PORT or socketcan:IFNAME)");
}

std::unique_ptr<CanBus> open_udp(const std::string& uri, std::string_view rest) {
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos) {
    bad_uri(uri, "missing port");
  }
  const std::string group_text(rest.substr(0, colon));
  const std::string_view port_text = rest.substr(colon + 1);

  in_addr group{};
  if (::inet_pton(AF_INET, group_text.c_str(), &group) != 1) {
    bad_uri(uri, "\"" + group_text + "\" is not an IPv4 address");
  }
  if (!IN_MULTICAST(ntohl(group.s_addr))) {
    bad_uri(uri, group_text + " is not a multicast group (224.0.0.0/4)");
  }
  unsigned int port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || ec != std::errc{} || end != port_text.data() + port_text.size() ||
      port == 0 || port > 65535) {
    bad_uri(uri, "port \"" + std::string(port_text) + "\" is not a number in 1..65535");
  }
  return std::make_unique<UdpCanBus>(uri, group, static_cast<std::uint16_t>(port));
}

std::unique_ptr<CanBus> open_socketcan(const std::string& uri, std::string_view name) {
  if (name.empty()) {
    bad_uri(uri, "missing interface name");
  }
  if (name.size() >= IFNAMSIZ) {
    bad_uri(uri, "interface name longer than " + std::to_string(IFNAMSIZ - 1) + " characters");
  }
  return std::make_unique<SocketCanBus>(uri, std::string(name));
}

}  // namespace

std::unique_ptr<CanBus> open_can_bus(const std::string& uri) {
  const std::string_view view(uri);
  constexpr std::string_view kUdp = "udp:";
  constexpr std::string_view kSocketCan = "socketcan:";
  if (view.starts_with(kUdp)) {
    return open_udp(uri, view.substr(kUdp.size()));
  }
  if (view.starts_with(kSocketCan)) {
    return open_socketcan(uri, view.substr(kSocketCan.size()));
  }
  bad_uri(uri, "unknown transport");
}

}  // namespace mcnc::can
