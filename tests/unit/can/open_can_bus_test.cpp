#include "common/can/can_bus.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <stdexcept>
#include <string>

namespace mcnc::can {
namespace {

// The error message of open_can_bus(uri), or "" when it opened.
std::string open_error(const std::string& uri) {
  try {
    open_can_bus(uri);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

TEST(OpenCanBus, RejectsBadUris) {
  const struct {
    const char* uri;
    const char* reason;
  } cases[] = {
      {"", "unknown transport"},
      {"can0", "unknown transport"},
      {"tcp:127.0.0.1:4000", "unknown transport"},
      {"UDP:239.255.0.1:4000", "unknown transport"},
      {"udp:", "missing port"},
      {"udp:239.255.0.1", "missing port"},
      {"udp:239.255.0.1:", "port"},
      {"udp:239.255.0.1:0", "port"},
      {"udp:239.255.0.1:65536", "port"},
      {"udp:239.255.0.1:42x", "port"},
      {"udp:239.255.0.1:-5", "port"},
      {"udp:127.0.0.1:42000", "not a multicast group"},
      {"udp:239.255.0:42000", "not an IPv4 address"},
      {"udp:localhost:42000", "not an IPv4 address"},
      {"socketcan:", "missing interface name"},
      {"socketcan:abcdefghijklmnopq", "interface name longer"},
  };
  for (const auto& c : cases) {
    const std::string message = open_error(c.uri);
    ASSERT_FALSE(message.empty()) << c.uri;
    EXPECT_NE(message.find('"' + std::string(c.uri) + '"'), std::string::npos) << message;
    EXPECT_NE(message.find(c.reason), std::string::npos) << message;
  }
}

TEST(OpenCanBus, OpensUdp) {
  auto bus = open_can_bus("udp:239.255.77.1:" + std::to_string(20000 + ::getpid() % 40000));
  ASSERT_NE(bus, nullptr);
  EXPECT_GE(bus->native_handle(), 0);
  EXPECT_EQ(bus->malformed_count(), 0U);
}

TEST(OpenCanBus, SocketCanMissingInterfaceThrows) {
  // On this host the kernel has no AF_CAN at all; on a host with SocketCAN the interface is
  // missing. Either way: a start-up error naming the URI, never a crash.
  const std::string message = open_error("socketcan:nosuchcan9");
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("socketcan:nosuchcan9"), std::string::npos) << message;
}

TEST(OpenCanBus, SocketCanVcanOpensOrExplainsWhy) {
  std::unique_ptr<CanBus> bus;
  try {
    bus = open_can_bus("socketcan:vcan0");
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("socketcan:vcan0"), std::string::npos) << e.what();
    return;
  }
  // A host with vcan0: the bus works and times out on an idle receive.
  ASSERT_NE(bus, nullptr);
  CanFrame frame;
  const BusResult result = bus->receive(frame, std::chrono::microseconds(0));
  EXPECT_TRUE(result == BusResult::timeout || result == BusResult::ok);
  EXPECT_GE(bus->native_handle(), 0);
}

}  // namespace
}  // namespace mcnc::can
