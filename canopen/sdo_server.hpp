#pragma once
// The SDO server (CiA 301 §7.2.4) of a device: answers each request of its client with one
// response from the device's object dictionary, expedited or segmented, and aborts with the
// dictionary's abort code, on a toggle error or an out-of-sequence request. Pure.
#include "canopen/object_access.hpp"
#include "common/can/can_frame.hpp"

#include <cstdint>

namespace mcnc::canopen {

class SdoServer {
 public:
  SdoServer(std::uint8_t node, ObjectAccess& objects) noexcept : node_(node), objects_(objects) {}

  // A frame from the bus: true when `out` is the response to send. Other COB-IDs are not
  // looked at; a request of the wrong length is counted and dropped; a client abort ends the
  // transfer without an answer.
  bool on_frame(const can::CanFrame& in, can::CanFrame& out) noexcept;

  [[nodiscard]] std::uint64_t malformed() const noexcept { return malformed_; }
  [[nodiscard]] std::uint64_t aborts_sent() const noexcept { return aborts_; }

 private:
  enum class State : std::uint8_t { idle, downloading, uploading };
  bool abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code,
             can::CanFrame& out) noexcept;
  [[nodiscard]] can::CanFrame response(std::uint8_t command) const noexcept;

  std::uint8_t node_;
  ObjectAccess& objects_;
  State state_ = State::idle;
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0;
  std::uint8_t toggle_ = 0;
  SdoValue value_{};
  std::size_t offset_ = 0;
  std::size_t expected_ = 0;  // download: the size the client indicated (0: not indicated)
  std::uint64_t malformed_ = 0;
  std::uint64_t aborts_ = 0;
};

}  // namespace mcnc::canopen
