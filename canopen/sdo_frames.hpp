#pragma once
// The bytes every SDO frame shares (CiA 301): byte 0 the command specifier, bytes 1-2 the
// index (little endian), byte 3 the sub-index, bytes 4-7 data, a size or an abort code.
#include "common/can/can_frame.hpp"

#include <cstdint>

namespace mcnc::canopen::sdo {

inline constexpr std::uint8_t kAbort = 0x80;

// Command specifiers (byte 0, bits 7-5) of the client's requests...
inline constexpr std::uint8_t kDownloadSegment = 0;
inline constexpr std::uint8_t kDownloadInitiate = 1;
inline constexpr std::uint8_t kUploadInitiate = 2;
inline constexpr std::uint8_t kUploadSegment = 3;
// ... and of the server's responses.
inline constexpr std::uint8_t kUploadSegmentResponse = 0;
inline constexpr std::uint8_t kDownloadSegmentResponse = 1;
inline constexpr std::uint8_t kUploadInitiateResponse = 2;
inline constexpr std::uint8_t kDownloadInitiateResponse = 3;
inline constexpr std::uint8_t kAbortSpecifier = 4;

inline std::uint8_t specifier(const can::CanFrame& f) noexcept {
  return f.data[0] >> 5;
}
inline std::uint16_t index_of(const can::CanFrame& f) noexcept {
  return static_cast<std::uint16_t>(f.data[1] | (f.data[2] << 8));
}
inline std::uint32_t u32_at4(const can::CanFrame& f) noexcept {
  return static_cast<std::uint32_t>(f.data[4]) | (static_cast<std::uint32_t>(f.data[5]) << 8) |
         (static_cast<std::uint32_t>(f.data[6]) << 16) |
         (static_cast<std::uint32_t>(f.data[7]) << 24);
}
inline can::CanFrame frame(std::uint32_t id, std::uint8_t command, std::uint16_t index,
                           std::uint8_t sub) noexcept {
  can::CanFrame f;
  f.id = id;
  f.dlc = 8;
  f.data[0] = command;
  f.data[1] = static_cast<std::uint8_t>(index & 0xFF);
  f.data[2] = static_cast<std::uint8_t>(index >> 8);
  f.data[3] = sub;
  return f;
}
inline void put_u32_at4(can::CanFrame& f, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) {
    f.data[static_cast<std::size_t>(4 + i)] = static_cast<std::uint8_t>(v >> (8 * i));
  }
}

}  // namespace mcnc::canopen::sdo
