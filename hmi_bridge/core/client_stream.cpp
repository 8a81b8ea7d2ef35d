#include "hmi_bridge/core/client_stream.hpp"

#include <algorithm>
#include <cctype>

namespace mcnc::hmi {

namespace {

char lower(char c) noexcept {
  return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}

bool contains_nocase(std::string_view text, std::string_view word) noexcept {
  const auto it = std::search(text.begin(), text.end(), word.begin(), word.end(),
                              [](char a, char b) { return lower(a) == lower(b); });
  return it != text.end();
}

// The bytes a header with these first two bytes has: the length's extension and the mask.
std::size_t header_bytes(unsigned char second) noexcept {
  const unsigned len7 = second & 0x7FU;
  const std::size_t extension = len7 == 126 ? 2 : len7 == 127 ? 8 : 0;
  return 2 + extension + ((second & 0x80U) != 0 ? 4 : 0);
}

std::uint64_t announced_length(const std::array<unsigned char, 14>& h) noexcept {
  const unsigned len7 = h[1] & 0x7FU;
  if (len7 < 126) {
    return len7;
  }
  const std::size_t n = len7 == 126 ? 2 : 8;
  std::uint64_t length = 0;
  for (std::size_t i = 0; i < n; ++i) {
    length = (length << 8) | h[2 + i];
  }
  return length;
}

}  // namespace

std::size_t request_head_end(std::string_view received) noexcept {
  const std::size_t at = received.find("\r\n\r\n");
  return at == std::string_view::npos ? std::string_view::npos : at + 4;
}

bool asks_websocket(std::string_view head) noexcept {
  std::size_t start = head.find("\r\n");
  while (start != std::string_view::npos && start + 2 < head.size()) {
    const std::size_t end = head.find("\r\n", start + 2);
    const std::string_view line =
        head.substr(start + 2, end == std::string_view::npos ? end : end - start - 2);
    const std::size_t colon = line.find(':');
    if (colon == 7 && contains_nocase(line.substr(0, 7), "upgrade") &&
        contains_nocase(line.substr(colon + 1), "websocket")) {
      return true;
    }
    start = end;
  }
  return false;
}

std::uint64_t FrameScanner::scan(std::string_view bytes, std::uint64_t max_frame) noexcept {
  std::size_t at = 0;
  while (refused_ == 0 && at < bytes.size()) {
    if (payload_left_ > 0) {
      const std::uint64_t skip = std::min<std::uint64_t>(payload_left_, bytes.size() - at);
      payload_left_ -= skip;
      at += static_cast<std::size_t>(skip);
      continue;
    }
    header_[header_size_++] = static_cast<unsigned char>(bytes[at++]);
    if (header_size_ < 2 || header_size_ < header_bytes(header_[1])) {
      continue;
    }
    const std::uint64_t length = announced_length(header_);
    header_size_ = 0;
    if (length > max_frame) {
      refused_ = length;
    } else {
      payload_left_ = length;
    }
  }
  return refused_;
}

}  // namespace mcnc::hmi
