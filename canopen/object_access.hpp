#pragma once
// What an SDO server reads and writes: a device's object dictionary, by index and sub-index.
// A result of 0 is success, anything else the SDO abort code the server answers with.
#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::canopen {

// Values up to this size travel over SDO here (the longest are device-name strings).
inline constexpr std::size_t kSdoMaxValue = 64;

struct SdoValue {
  std::array<std::uint8_t, kSdoMaxValue> bytes{};
  std::size_t size = 0;
};

class ObjectAccess {
 public:
  virtual ~ObjectAccess() = default;
  virtual std::uint32_t read(std::uint16_t index, std::uint8_t sub, SdoValue& out) noexcept = 0;
  virtual std::uint32_t write(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                              std::size_t size) noexcept = 0;
};

}  // namespace mcnc::canopen
