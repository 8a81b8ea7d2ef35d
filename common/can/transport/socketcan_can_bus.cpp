#include "common/can/transport/socketcan_can_bus.hpp"

#include "common/can/transport/fd_wait.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <array>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace mcnc::can {
namespace {

static_assert(sizeof(CanFrame) == sizeof(can_frame));
static_assert(sizeof(can_frame::data) == std::tuple_size_v<decltype(CanFrame::data)>);

}  // namespace

SocketCanBus::SocketCanBus(const std::string& uri, const std::string& interface_name) {
  const auto fail = [&](const std::string& reason) {
    if (fd_ >= 0) {
      ::close(fd_);
      fd_ = -1;
    }
    throw std::runtime_error("CAN bus \"" + uri + "\": " + reason);
  };

  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) {
    const int err = errno;
    std::string reason = std::string("cannot open a CAN_RAW socket: ") + std::strerror(err);
    if (err == EAFNOSUPPORT) {
      reason += " (this kernel has no SocketCAN; use a udp:GROUP:PORT bus instead)";
    }
    fail(reason);
  }
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ) {
    fail("bad interface name \"" + interface_name + "\"");
  }
  const unsigned int index = ::if_nametoindex(interface_name.c_str());
  if (index == 0) {
    fail("no network interface \"" + interface_name + "\": " + std::strerror(errno));
  }
  const can_err_mask_t error_mask = CAN_ERR_MASK;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &error_mask, sizeof(error_mask)) != 0) {
    fail(std::string("CAN_RAW_ERR_FILTER: ") + std::strerror(errno));
  }
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    fail("bind to \"" + interface_name + "\": " + std::strerror(errno));
  }
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

BusResult SocketCanBus::send(const CanFrame& frame) noexcept {
  if (frame.dlc > 8) {
    return BusResult::malformed;
  }
  can_frame out{};
  out.can_id = frame.id;
  out.len = frame.dlc;
  std::memcpy(out.data, frame.data.data(), sizeof(out.data));
  const ssize_t written = ::write(fd_, &out, sizeof(out));
  return written == static_cast<ssize_t>(sizeof(out)) ? BusResult::ok : BusResult::error;
}

BusResult SocketCanBus::receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept {
  if (const BusResult ready = wait_readable(fd_, timeout); ready != BusResult::ok) {
    return ready;
  }
  can_frame in{};
  const ssize_t got = ::recv(fd_, &in, sizeof(in), MSG_DONTWAIT);
  if (got < 0) {
    return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? BusResult::timeout
                                                                       : BusResult::error;
  }
  if (got != static_cast<ssize_t>(sizeof(in)) || in.len > CAN_MAX_DLEN) {
    ++malformed_;
    return BusResult::malformed;
  }
  frame = CanFrame{};
  frame.id = in.can_id;
  frame.dlc = in.len;
  std::memcpy(frame.data.data(), in.data, sizeof(in.data));
  if ((in.can_id & CAN_ERR_FLAG) != 0) {
    return (in.can_id & CAN_ERR_BUSOFF) != 0 ? BusResult::bus_off : BusResult::error;
  }
  return BusResult::ok;
}

bool SocketCanBus::set_filters(std::span<const CanFilter> filters) noexcept {
  if (filters.size() > kMaxFilters) {
    return false;
  }
  std::array<can_filter, kMaxFilters> kernel{};
  for (std::size_t i = 0; i < filters.size(); ++i) {
    kernel[i].can_id = filters[i].id;
    kernel[i].can_mask = filters[i].mask;
  }
  // An empty set: the default filter that lets every frame in.
  if (filters.empty()) {
    kernel[0].can_id = 0;
    kernel[0].can_mask = 0;
  }
  const std::size_t count = filters.empty() ? 1 : filters.size();
  return ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, kernel.data(),
                      static_cast<socklen_t>(count * sizeof(can_filter))) == 0;
}

unsigned long SocketCanBus::malformed_count() const noexcept {
  return malformed_;
}

int SocketCanBus::native_handle() const noexcept {
  return fd_;
}

}  // namespace mcnc::can
