#pragma once
// A CAN bus endpoint. Transports (UDP multicast on loopback, SocketCAN) implement it; the
// CANopen code above it is identical on both. Calls never throw and never allocate.
#include "common/can/can_frame.hpp"

#include <chrono>
#include <memory>
#include <string>

namespace mcnc::can {

enum class BusResult { ok, timeout, malformed, error };

class CanBus {
 public:
  virtual ~CanBus() = default;
  // Sends one frame. Frames sent by this endpoint are not received back by it.
  virtual BusResult send(const CanFrame& frame) noexcept = 0;
  // Waits up to `timeout` for one frame (zero: poll). `malformed`: a datagram that is not a
  // valid frame arrived and was dropped (counted in malformed_count()).
  virtual BusResult receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept = 0;
  [[nodiscard]] virtual unsigned long malformed_count() const noexcept = 0;
  // A file descriptor that becomes readable when a frame may be waiting (for poll()).
  [[nodiscard]] virtual int native_handle() const noexcept = 0;
};

// Opens a bus by URI: "udp:GROUP:PORT" or "socketcan:IFNAME". Throws std::runtime_error with
// the URI and the reason when it cannot be opened (start-up error).
std::unique_ptr<CanBus> open_can_bus(const std::string& uri);

}  // namespace mcnc::can
