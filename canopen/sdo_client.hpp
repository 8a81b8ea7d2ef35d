#pragma once
// The SDO client (CiA 301 §7.2.4): reads and writes one object of one node at a time,
// expedited (up to 4 bytes in one frame) or segmented (7 bytes per segment, toggle bit
// alternating from 0), aborts on a toggle error, an unknown command or a timeout, and reports
// the server's abort code. Pure: frames and the time in, frames out; no allocation.
#include "canopen/object_access.hpp"
#include "common/can/can_frame.hpp"

#include <cstdint>

namespace mcnc::canopen {

inline constexpr std::uint32_t kSdoResponseBase = 0x580;  // server -> client
inline constexpr std::uint32_t kSdoRequestBase = 0x600;   // client -> server

class SdoClient {
 public:
  enum class State : std::uint8_t { idle, downloading, uploading, done, aborted };

  SdoClient(std::uint8_t node, std::uint64_t timeout_us) noexcept
      : node_(node), timeout_us_(timeout_us) {}

  // Start a transfer; `out` is the first request. False (nothing sent) while one is under way
  // or for a value longer than kSdoMaxValue.
  bool download(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data, std::size_t size,
                std::uint64_t now_us, can::CanFrame& out) noexcept;
  bool upload(std::uint16_t index, std::uint8_t sub, std::uint64_t now_us,
              can::CanFrame& out) noexcept;

  // A frame from the bus: true when `out` must be sent (the next request, or an abort).
  // Frames of other COB-IDs are not looked at; a response of the wrong length is counted as
  // malformed and dropped (the transfer then times out); an initiate response or abort for
  // another object than this transfer's is a late answer to an earlier request, counted as
  // stale and dropped.
  bool on_frame(const can::CanFrame& in, std::uint64_t now_us, can::CanFrame& out) noexcept;
  // Time passes: true with an abort in `out` when the server took longer than the timeout.
  bool on_time(std::uint64_t now_us, can::CanFrame& out) noexcept;

  [[nodiscard]] State state() const noexcept { return state_; }
  [[nodiscard]] bool busy() const noexcept {
    return state_ == State::downloading || state_ == State::uploading;
  }
  [[nodiscard]] std::uint32_t abort_code() const noexcept { return abort_code_; }
  [[nodiscard]] bool aborted_by_server() const noexcept { return by_server_; }
  [[nodiscard]] const SdoValue& value() const noexcept { return value_; }  // an upload's result
  [[nodiscard]] std::uint16_t index() const noexcept { return index_; }
  [[nodiscard]] std::uint8_t sub() const noexcept { return sub_; }
  [[nodiscard]] std::uint64_t malformed() const noexcept { return malformed_; }
  // Answers to another object than the request's (late answers to earlier requests), ignored.
  [[nodiscard]] std::uint64_t stale() const noexcept { return stale_; }

 private:
  bool fail(std::uint32_t code, can::CanFrame& out) noexcept;
  void next_download_segment(can::CanFrame& out) noexcept;
  [[nodiscard]] can::CanFrame request(std::uint8_t command) const noexcept;
  [[nodiscard]] can::CanFrame segment_request(std::uint8_t command) const noexcept;

  std::uint8_t node_;
  std::uint64_t timeout_us_;
  State state_ = State::idle;
  bool segmented_ = false;
  bool initiated_ = false;  // the initiate response came
  std::uint8_t toggle_ = 0;
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0;
  SdoValue value_{};
  std::size_t offset_ = 0;      // bytes sent (download) or received (upload)
  std::size_t expected_ = 0;    // upload: the size the server indicated (0: not indicated)
  std::size_t last_chunk_ = 0;  // download: bytes in the segment sent last
  std::uint64_t last_us_ = 0;
  std::uint32_t abort_code_ = 0;
  bool by_server_ = false;
  std::uint64_t malformed_ = 0;
  std::uint64_t stale_ = 0;
};

}  // namespace mcnc::canopen
