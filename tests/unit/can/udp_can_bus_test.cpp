#include "common/can/can_bus.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <chrono>
#include <cstring>
#include <string>

namespace mcnc::can {
namespace {

using namespace std::chrono_literals;

// Each test gets its own group and port, derived from the pid, so parallel test processes do
// not hear each other.
struct Endpoint {
  std::string group;
  int port;
  [[nodiscard]] std::string uri() const { return "udp:" + group + ":" + std::to_string(port); }
};

Endpoint test_endpoint() {
  static int counter = 0;
  const int pid = static_cast<int>(::getpid());
  const int n = ++counter;
  Endpoint e;
  e.group = "239.255." + std::to_string((pid >> 8) & 0xFF) + "." + std::to_string(pid & 0xFF);
  e.port = 20000 + (pid * 7 + n) % 40000;
  return e;
}

CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  std::size_t i = 0;
  for (const std::uint8_t b : bytes) {
    f.data[i++] = b;
  }
  return f;
}

bool same(const CanFrame& a, const CanFrame& b) {
  return a.id == b.id && a.dlc == b.dlc && a.data == b.data;
}

// A plain UDP socket that sends raw datagrams to the group, like a misbehaving peer.
void send_raw(const Endpoint& e, const void* data, std::size_t size) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  in_addr lo{};
  lo.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &lo, sizeof(lo)), 0);
  const unsigned char ttl = 0;
  ASSERT_EQ(::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl)), 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(e.port));
  ASSERT_EQ(::inet_pton(AF_INET, e.group.c_str(), &to.sin_addr), 1);
  ASSERT_EQ(::sendto(fd, data, size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to)),
            static_cast<ssize_t>(size));
  ::close(fd);
}

TEST(UdpCanBus, ExchangesFramesBothWays) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(e.uri());
  const CanFrame ping = frame(0x201, {0x0F, 0x00, 0x10, 0x27, 0x00, 0x00});
  const CanFrame pong = frame(0x181, {0x37, 0x06, 0x10, 0x27, 0x00, 0x00});

  ASSERT_EQ(a->send(ping), BusResult::ok);
  CanFrame got;
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_TRUE(same(got, ping));

  ASSERT_EQ(b->send(pong), BusResult::ok);
  ASSERT_EQ(a->receive(got, 1s), BusResult::ok);
  EXPECT_TRUE(same(got, pong));

  // Frames with no data and with the full 8 bytes survive unchanged.
  const CanFrame sync = frame(0x080, {});
  const CanFrame emcy = frame(0x081, {1, 2, 3, 4, 5, 6, 7, 8});
  ASSERT_EQ(a->send(sync), BusResult::ok);
  ASSERT_EQ(a->send(emcy), BusResult::ok);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_TRUE(same(got, sync));
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_TRUE(same(got, emcy));
  EXPECT_EQ(a->malformed_count(), 0U);
  EXPECT_EQ(b->malformed_count(), 0U);
}

TEST(UdpCanBus, DoesNotReceiveItsOwnFrames) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(e.uri());
  auto c = open_can_bus(e.uri());
  for (std::uint8_t i = 1; i <= 3; ++i) {
    ASSERT_EQ(a->send(frame(0x700 + i, {i})), BusResult::ok);
  }
  CanFrame got;
  EXPECT_EQ(a->receive(got, 50ms), BusResult::timeout);
  for (std::uint8_t i = 1; i <= 3; ++i) {
    ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
    EXPECT_EQ(got.id, 0x700U + i);
    ASSERT_EQ(c->receive(got, 1s), BusResult::ok);  // a broadcast medium: everyone else hears it
    EXPECT_EQ(got.id, 0x700U + i);
  }
  // A frame from someone else queued behind our own is still delivered by a zero-wait poll.
  ASSERT_EQ(a->send(frame(0x1, {})), BusResult::ok);
  ASSERT_EQ(b->send(frame(0x2, {})), BusResult::ok);
  bool seen = false;
  for (int i = 0; i < 100 && !seen; ++i) {
    seen = a->receive(got, 0us) == BusResult::ok && got.id == 0x2;
    if (!seen) {
      ::usleep(1000);
    }
  }
  EXPECT_TRUE(seen);
}

TEST(UdpCanBus, GarbageIsCountedMalformedAndDropped) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  CanFrame got;

  const unsigned char shorty[5] = {1, 2, 3, 4, 5};
  send_raw(e, shorty, sizeof(shorty));
  EXPECT_EQ(a->receive(got, 1s), BusResult::malformed);
  EXPECT_EQ(a->malformed_count(), 1U);

  unsigned char longer[17] = {};
  send_raw(e, longer, sizeof(longer));
  EXPECT_EQ(a->receive(got, 1s), BusResult::malformed);
  EXPECT_EQ(a->malformed_count(), 2U);

  CanFrame bad_dlc = frame(0x201, {});
  bad_dlc.dlc = 9;
  send_raw(e, &bad_dlc, sizeof(bad_dlc));
  EXPECT_EQ(a->receive(got, 1s), BusResult::malformed);
  EXPECT_EQ(a->malformed_count(), 3U);

  send_raw(e, shorty, 0);  // empty datagram
  EXPECT_EQ(a->receive(got, 1s), BusResult::malformed);
  EXPECT_EQ(a->malformed_count(), 4U);

  // A valid frame from a plain socket (another process) is delivered afterwards.
  const CanFrame good = frame(0x77F, {0x05});
  send_raw(e, &good, sizeof(good));
  ASSERT_EQ(a->receive(got, 1s), BusResult::ok);
  EXPECT_TRUE(same(got, good));
}

TEST(UdpCanBus, GroupsOnTheSamePortAreSeparate) {
  const Endpoint e = test_endpoint();
  Endpoint other = e;
  other.group = "239.254.1.2";
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(other.uri());
  auto c = open_can_bus(other.uri());
  ASSERT_EQ(a->send(frame(0x80, {})), BusResult::ok);
  CanFrame got;
  EXPECT_EQ(b->receive(got, 50ms), BusResult::timeout);
  ASSERT_EQ(c->send(frame(0x81, {})), BusResult::ok);
  EXPECT_EQ(a->receive(got, 50ms), BusResult::timeout);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, 0x81U);
}

TEST(UdpCanBus, TimeoutAndNativeHandle) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(e.uri());
  CanFrame got;
  EXPECT_EQ(a->receive(got, 0us), BusResult::timeout);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(a->receive(got, 30ms), BusResult::timeout);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 29ms);

  ASSERT_GE(a->native_handle(), 0);
  ASSERT_EQ(b->send(frame(0x123, {9})), BusResult::ok);
  pollfd pfd{a->native_handle(), POLLIN, 0};
  EXPECT_EQ(::poll(&pfd, 1, 1000), 1);
  ASSERT_EQ(a->receive(got, 0us), BusResult::ok);
  EXPECT_EQ(got.id, 0x123U);
}

}  // namespace
}  // namespace mcnc::can

namespace mcnc::can {
namespace {

TEST(UdpCanBus, ReceivesOnlyWhatItsFiltersLetThrough) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(e.uri());
  const std::array<CanFilter, 2> filters{CanFilter{0x181}, CanFilter{0x080}};
  ASSERT_TRUE(b->set_filters(filters));
  for (const std::uint32_t id : {0x182U, 0x181U, 0x201U, 0x080U}) {
    ASSERT_EQ(a->send(frame(id, {1})), BusResult::ok);
  }
  CanFrame got;
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, 0x181U);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, 0x080U);
  EXPECT_EQ(b->receive(got, 50ms), BusResult::timeout);
  // Back to everything.
  ASSERT_TRUE(b->set_filters({}));
  ASSERT_EQ(a->send(frame(0x182, {1})), BusResult::ok);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, 0x182U);
  const std::vector<CanFilter> too_many(kMaxFilters + 1);
  EXPECT_FALSE(b->set_filters(too_many));
}

// The filters run in the kernel, like a controller's acceptance filter: a frame no filter
// passes, and our own looped back, never make the socket readable (no wake-up); error frames and
// datagrams that are not frames still do (the latter to be counted as malformed).
TEST(UdpCanBus, FilteredAndOwnFramesNeverWakeTheReceiver) {
  const Endpoint e = test_endpoint();
  auto a = open_can_bus(e.uri());
  auto b = open_can_bus(e.uri());
  const std::array<CanFilter, 2> filters{CanFilter{0x181}, CanFilter{0x700, 0x780}};
  ASSERT_TRUE(b->set_filters(filters));
  const auto readable = [&b](std::chrono::milliseconds wait) {
    pollfd p{b->native_handle(), POLLIN, 0};
    return ::poll(&p, 1, static_cast<int>(wait.count())) == 1;
  };
  for (const std::uint32_t id : {0x182U, 0x201U, 0x080U, 0x681U}) {
    ASSERT_EQ(a->send(frame(id, {1})), BusResult::ok);
  }
  ASSERT_EQ(b->send(frame(0x181, {2})), BusResult::ok);  // b's own, looped back
  EXPECT_FALSE(readable(100ms)) << "a frame no filter passes reached the socket";

  // What passes: an id a filter names, one under a filter's mask, an error frame, a runt.
  ASSERT_EQ(a->send(frame(0x181, {3})), BusResult::ok);
  ASSERT_TRUE(readable(1000ms));
  CanFrame got;
  ASSERT_EQ(b->receive(got, 0ms), BusResult::ok);
  EXPECT_EQ(got.id, 0x181U);
  EXPECT_EQ(got.data[0], 3);
  ASSERT_EQ(a->send(frame(0x705, {5})), BusResult::ok);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, 0x705U);
  ASSERT_EQ(a->send(frame(kErrFlag | 0x40, {0, 0, 0, 0, 0, 0, 0, 0})), BusResult::ok);
  ASSERT_EQ(b->receive(got, 1s), BusResult::ok);
  EXPECT_EQ(got.id, kErrFlag | 0x40);
  const unsigned char runt[3] = {1, 2, 3};
  send_raw(e, runt, sizeof(runt));
  EXPECT_EQ(b->receive(got, 1s), BusResult::malformed);
  EXPECT_EQ(b->malformed_count(), 1U);
  EXPECT_FALSE(readable(50ms));
}

}  // namespace
}  // namespace mcnc::can
