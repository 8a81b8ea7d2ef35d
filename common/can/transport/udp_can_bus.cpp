#include "common/can/transport/udp_can_bus.hpp"

#include "common/can/transport/fd_wait.hpp"

#include <arpa/inet.h>
#include <linux/filter.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mcnc::can {
namespace {

[[noreturn]] void fail(const std::string& uri, const char* step, int err) {
  throw std::runtime_error("CAN bus \"" + uri + "\": " + step + ": " + std::strerror(err));
}

template <typename T>
void set_option(int fd, int level, int name, const T& value, const std::string& uri,
                const char* step) {
  if (::setsockopt(fd, level, name, &value, sizeof(value)) != 0) {
    fail(uri, step, errno);
  }
}

// The socket filter (classic BPF) of a set of CanFilters, as CanFilterSet::passes() decides,
// and dropping our own frames. A UDP socket's filter sees the datagram from its UDP header:
// the source port at 0, the length at 4, the CanFrame at 8, whose id a word load reads in
// network order (hence ntohl on the constants). A datagram that is not frame-sized passes, so
// that receive() counts it as malformed.
struct SocketFilterProgram {
  std::array<sock_filter, 8 + 3 * kMaxFilters> code{};
  unsigned short length = 0;
};

SocketFilterProgram socket_filter(std::span<const CanFilter> filters,
                                  std::uint16_t own_port) noexcept {
  constexpr std::uint32_t kUdpHeader = 8;
  constexpr std::uint32_t kId = kUdpHeader;  // CanFrame::id is its first member
  SocketFilterProgram p;
  auto emit = [&p](sock_filter insn) { p.code[p.length++] = insn; };
  // Jumps are relative to the next instruction; `accept` and `drop` are the last two.
  const auto n = static_cast<unsigned short>(6 + 3 * filters.size());
  const auto to_drop = [&p, n] { return static_cast<std::uint8_t>(n - p.length - 1); };
  const auto to_accept = [&p, n] { return static_cast<std::uint8_t>(n + 1 - p.length - 1); };
  emit(BPF_STMT(BPF_LD | BPF_H | BPF_ABS, 0));
  emit(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, own_port, to_drop(), 0));
  emit(BPF_STMT(BPF_LD | BPF_H | BPF_ABS, 4));
  emit(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, kUdpHeader + sizeof(CanFrame), 0, to_accept()));
  emit(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, kId));
  emit(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, ntohl(kErrFlag), to_accept(),
                filters.empty() ? to_accept() : std::uint8_t{0}));
  for (const CanFilter& f : filters) {
    emit(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, kId));
    emit(BPF_STMT(BPF_ALU | BPF_AND | BPF_K, ntohl(f.mask)));
    emit(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, ntohl(f.id & f.mask), to_accept(), 0));
  }
  emit(BPF_STMT(BPF_RET | BPF_K, 0));            // drop
  emit(BPF_STMT(BPF_RET | BPF_K, 0xFFFFFFFFU));  // accept, whole
  return p;
}

in_addr loopback() {
  in_addr addr{};
  addr.s_addr = htonl(INADDR_LOOPBACK);
  return addr;
}

}  // namespace

UdpCanBus::UdpCanBus(const std::string& uri, in_addr group, std::uint16_t port) {
  // Closes whatever was opened when a later step throws (the destructor does not run then).
  struct Guard {
    UdpCanBus* bus;
    bool armed = true;
    ~Guard() {
      if (armed) {
        if (bus->recv_fd_ >= 0)
          ::close(bus->recv_fd_);
        if (bus->send_fd_ >= 0)
          ::close(bus->send_fd_);
      }
    }
  } guard{this};

  // Receiving socket: every endpoint binds the same group:port, hence SO_REUSEADDR/PORT.
  // Binding to the group address (not INADDR_ANY) keeps out unicast and other groups' traffic.
  recv_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (recv_fd_ < 0) {
    fail(uri, "socket", errno);
  }
  const int one = 1;
  const int zero = 0;
  set_option(recv_fd_, SOL_SOCKET, SO_REUSEADDR, one, uri, "SO_REUSEADDR");
  set_option(recv_fd_, SOL_SOCKET, SO_REUSEPORT, one, uri, "SO_REUSEPORT");
  sockaddr_in bind_addr{};
  bind_addr.sin_family = AF_INET;
  bind_addr.sin_addr = group;
  bind_addr.sin_port = htons(port);
  if (::bind(recv_fd_, reinterpret_cast<const sockaddr*>(&bind_addr), sizeof(bind_addr)) != 0) {
    fail(uri, "bind receive socket", errno);
  }
  ip_mreq membership{};
  membership.imr_multiaddr = group;
  membership.imr_interface = loopback();
  set_option(recv_fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, membership, uri,
             "join multicast group on 127.0.0.1");
  // Only the group joined by this socket, not every group some socket of the host joined.
  set_option(recv_fd_, IPPROTO_IP, IP_MULTICAST_ALL, zero, uri, "IP_MULTICAST_ALL");

  // Sending socket on its own ephemeral port: all endpoints share the receive port, so the
  // send socket's port is what tells our own datagrams apart when they loop back.
  send_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (send_fd_ < 0) {
    fail(uri, "socket", errno);
  }
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_addr = loopback();
  local.sin_port = 0;
  if (::bind(send_fd_, reinterpret_cast<const sockaddr*>(&local), sizeof(local)) != 0) {
    fail(uri, "bind send socket", errno);
  }
  socklen_t len = sizeof(own_source_);
  if (::getsockname(send_fd_, reinterpret_cast<sockaddr*>(&own_source_), &len) != 0) {
    fail(uri, "getsockname", errno);
  }
  const in_addr interface_addr = loopback();
  set_option(send_fd_, IPPROTO_IP, IP_MULTICAST_IF, interface_addr, uri, "IP_MULTICAST_IF");
  const unsigned char ttl = 0;   // never leaves the host
  const unsigned char loop = 1;  // other endpoints on this host must see it
  set_option(send_fd_, IPPROTO_IP, IP_MULTICAST_TTL, ttl, uri, "IP_MULTICAST_TTL");
  set_option(send_fd_, IPPROTO_IP, IP_MULTICAST_LOOP, loop, uri, "IP_MULTICAST_LOOP");

  destination_.sin_family = AF_INET;
  destination_.sin_addr = group;
  destination_.sin_port = htons(port);
  if (!attach_socket_filter()) {
    fail(uri, "SO_ATTACH_FILTER", errno);
  }
  guard.armed = false;
}

UdpCanBus::~UdpCanBus() {
  ::close(recv_fd_);
  ::close(send_fd_);
}

BusResult UdpCanBus::send(const CanFrame& frame) noexcept {
  const ssize_t sent =
      ::sendto(send_fd_, &frame, sizeof(frame), 0, reinterpret_cast<const sockaddr*>(&destination_),
               sizeof(destination_));
  return sent == static_cast<ssize_t>(sizeof(frame)) ? BusResult::ok : BusResult::error;
}

BusResult UdpCanBus::receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept {
  using Clock = std::chrono::steady_clock;
  // Capped so that now + timeout cannot overflow the clock's representation.
  constexpr std::chrono::microseconds kLongest = std::chrono::hours(24 * 365);
  const Clock::time_point deadline = Clock::now() + std::min(timeout, kLongest);
  // One byte more than a frame, so an oversized datagram shows up as a wrong size.
  unsigned char buffer[sizeof(CanFrame) + 1];
  for (;;) {
    if (const BusResult ready = wait_readable(recv_fd_, deadline - Clock::now());
        ready != BusResult::ok) {
      return ready;  // a signal (e.g. SIGTERM) ends the wait as a timeout
    }
    sockaddr_in source{};
    socklen_t source_len = sizeof(source);
    const ssize_t got = ::recvfrom(recv_fd_, buffer, sizeof(buffer), MSG_DONTWAIT | MSG_TRUNC,
                                   reinterpret_cast<sockaddr*>(&source), &source_len);
    if (got < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
        continue;  // the next ppoll sees the remaining time (zero once it has passed)
      }
      return BusResult::error;
    }
    if (source.sin_port == own_source_.sin_port &&
        source.sin_addr.s_addr == own_source_.sin_addr.s_addr) {
      continue;  // our own frame looped back; another may be queued behind it
    }
    if (got != static_cast<ssize_t>(sizeof(CanFrame))) {
      ++malformed_;
      return BusResult::malformed;
    }
    CanFrame received;
    std::memcpy(&received, buffer, sizeof(received));
    if (received.dlc > 8) {
      ++malformed_;
      return BusResult::malformed;
    }
    if (!filters_.passes(received)) {
      continue;  // not for this endpoint
    }
    frame = received;
    return BusResult::ok;
  }
}

bool UdpCanBus::set_filters(std::span<const CanFilter> filters) noexcept {
  if (!filters_.assign(filters)) {
    return false;
  }
  // Should the kernel refuse, receive() still filters: the frames pass or not alike.
  (void)attach_socket_filter();
  return true;
}

bool UdpCanBus::attach_socket_filter() noexcept {
  std::array<CanFilter, kMaxFilters> filters{};
  const std::size_t n = filters_.copy_to(filters);
  SocketFilterProgram program =
      socket_filter(std::span(filters.data(), n), ntohs(own_source_.sin_port));
  const sock_fprog fprog{program.length, program.code.data()};
  return ::setsockopt(recv_fd_, SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof(fprog)) == 0;
}

unsigned long UdpCanBus::malformed_count() const noexcept {
  return malformed_;
}

int UdpCanBus::native_handle() const noexcept {
  return recv_fd_;
}

}  // namespace mcnc::can
