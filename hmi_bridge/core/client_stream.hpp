#pragma once
// What the HMI reads of a client's bytes before its web server sees them (docs/hmi.md,
// Security): the HTTP request head, then, on a WebSocket, each frame's header. A frame is
// judged by the length its header announces, before a byte of its payload is read. Pure.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace mcnc::hmi {

// The longest request head the HMI reads (civetweb's own limit, max_request_size).
inline constexpr std::size_t kMaxRequestHeadBytes = 16384;
// The largest WebSocket frame the HMI reads. Messages above kMaxMessageBytes are still read and
// answered with an error up to this size; a larger announcement ends the connection.
inline constexpr std::uint64_t kMaxFrameBytes = 65536;

// Where the request head in `received` ends (just after its blank line), or npos while it has
// not ended.
std::size_t request_head_end(std::string_view received) noexcept;

// The head asks for a WebSocket: an `Upgrade` header naming websocket (any case).
bool asks_websocket(std::string_view head) noexcept;

// Follows a client's WebSocket frames (RFC 6455, 5.2) across reads of any size.
class FrameScanner {
 public:
  // Reads `bytes`, the stream's next ones. Returns 0 while every frame header seen announces
  // at most `max_frame` bytes; else the first larger announcement (the scanner then stays
  // there: the connection is to end).
  std::uint64_t scan(std::string_view bytes, std::uint64_t max_frame = kMaxFrameBytes) noexcept;

 private:
  std::array<unsigned char, 14> header_{};  // the header being read: 2-14 bytes
  std::size_t header_size_ = 0;
  std::uint64_t payload_left_ = 0;  // of the frame whose header was read
  std::uint64_t refused_ = 0;
};

}  // namespace mcnc::hmi
