#pragma once
// CAN over a Linux SocketCAN raw socket ("socketcan:IFNAME"), the transport of real hardware.
// Error frames are enabled and reported by receive() as BusResult::error (the frame is
// returned with kErrFlag set). Own frames are not received back (CAN_RAW_RECV_OWN_MSGS off).
#include "common/can/can_bus.hpp"

#include <string>

namespace mcnc::can {

class SocketCanBus final : public CanBus {
 public:
  // Throws std::runtime_error naming `uri` and the reason, e.g. a kernel without AF_CAN
  // (EAFNOSUPPORT) or an interface that does not exist.
  SocketCanBus(const std::string& uri, const std::string& interface_name);
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  BusResult send(const CanFrame& frame) noexcept override;
  BusResult receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept override;
  [[nodiscard]] unsigned long malformed_count() const noexcept override;
  bool set_filters(std::span<const CanFilter> filters) noexcept override;
  [[nodiscard]] int native_handle() const noexcept override;

 private:
  int fd_ = -1;
  unsigned long malformed_ = 0;
};

}  // namespace mcnc::can
