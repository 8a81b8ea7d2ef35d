#pragma once
// A CAN bus endpoint. Transports (UDP multicast on loopback, SocketCAN) implement it; the
// CANopen code above it is identical on both. Calls never throw and never allocate.
#include "common/can/can_frame.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace mcnc::can {

// bus_off: the controller went bus off (an error frame said so); the bus carries nothing of ours.
enum class BusResult { ok, timeout, malformed, error, bus_off };

// A receive filter as Linux CAN_RAW_FILTER: a frame passes when (id & mask) == (filter id &
// mask). Error frames pass regardless.
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = kSffMask;
};
inline constexpr std::size_t kMaxFilters = 32;

// A set of filters; empty lets everything pass.
class CanFilterSet {
 public:
  bool assign(std::span<const CanFilter> filters) noexcept {
    if (filters.size() > filters_.size()) {
      return false;
    }
    count_ = 0;
    for (const CanFilter& f : filters) {
      filters_[count_++] = f;
    }
    return true;
  }
  [[nodiscard]] bool passes(const CanFrame& frame) const noexcept {
    if (count_ == 0 || (frame.id & kErrFlag) != 0) {
      return true;
    }
    for (std::size_t i = 0; i < count_; ++i) {
      if ((frame.id & filters_[i].mask) == (filters_[i].id & filters_[i].mask)) {
        return true;
      }
    }
    return false;
  }
  // Copies the filters to `out` (room for kMaxFilters); returns how many.
  std::size_t copy_to(std::span<CanFilter, kMaxFilters> out) const noexcept {
    std::copy_n(filters_.begin(), count_, out.begin());
    return count_;
  }

 private:
  std::array<CanFilter, kMaxFilters> filters_{};
  std::size_t count_ = 0;
};

class CanBus {
 public:
  virtual ~CanBus() = default;
  // Sends one frame. Frames sent by this endpoint are not received back by it.
  virtual BusResult send(const CanFrame& frame) noexcept = 0;
  // Waits up to `timeout` for one frame (zero: poll). `malformed`: a datagram that is not a
  // valid frame arrived and was dropped (counted in malformed_count()).
  virtual BusResult receive(CanFrame& frame, std::chrono::microseconds timeout) noexcept = 0;
  [[nodiscard]] virtual unsigned long malformed_count() const noexcept = 0;
  // Receive only frames that pass one of `filters` (at most kMaxFilters; empty: everything),
  // in the kernel where the transport has one (CAN_RAW_FILTER). False when refused.
  virtual bool set_filters(std::span<const CanFilter> filters) noexcept = 0;
  // A file descriptor that becomes readable when a frame may be waiting (for poll()).
  [[nodiscard]] virtual int native_handle() const noexcept = 0;
};

// Opens a bus by URI: "udp:GROUP:PORT" or "socketcan:IFNAME". Throws std::runtime_error with
// the URI and the reason when it cannot be opened (start-up error).
std::unique_ptr<CanBus> open_can_bus(const std::string& uri);

}  // namespace mcnc::can
