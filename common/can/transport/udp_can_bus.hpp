#pragma once
// CAN over UDP multicast on loopback ("udp:GROUP:PORT"): one raw 16-byte CanFrame per
// datagram, a broadcast medium shared by every endpoint of the same group and port on this
// host. For multi-process tests on hosts without kernel CAN. Its receive filters run in the
// kernel, as a socket filter, like a CAN controller's acceptance filter: a frame that no filter
// passes, or one of our own looped back, never wakes the receiver.
#include "common/can/can_bus.hpp"

#include <netinet/in.h>
#include <cstdint>

namespace mcnc::can {

class UdpCanBus final : public CanBus {
 public:
  // group: IPv4 multicast address (network byte order); port: host byte order. Throws
  // std::runtime_error (with `uri` and the failing step) when a socket cannot be set up.
  UdpCanBus(const std::string& uri, in_addr group, std::uint16_t port);
  ~UdpCanBus() override;
  UdpCanBus(const UdpCanBus&) = delete;
  UdpCanBus& operator=(const UdpCanBus&) = delete;

  BusResult send(const CanFrame& frame) noexcept override;
  BusResult receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept override;
  [[nodiscard]] unsigned long malformed_count() const noexcept override;
  bool set_filters(std::span<const CanFilter> filters) noexcept override;
  [[nodiscard]] int native_handle() const noexcept override;

 private:
  // The socket filter of filters_ (and of our own frames). False when the kernel refused it.
  bool attach_socket_filter() noexcept;

  int recv_fd_ = -1;
  int send_fd_ = -1;
  sockaddr_in destination_{};
  sockaddr_in own_source_{};  // the send socket's address: datagrams from it are our own
  unsigned long malformed_ = 0;
  CanFilterSet filters_;  // also applied in receive(), should the kernel refuse the socket filter
};

}  // namespace mcnc::can
