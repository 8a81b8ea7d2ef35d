#pragma once
// A classic CAN frame, laid out exactly like Linux `struct can_frame` (16 bytes), so the UDP
// transport can carry it unchanged and the SocketCAN transport can pass it to the kernel.
#include <array>
#include <cstdint>

namespace mcnc::can {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit identifier (COB-ID); flag bits as in Linux can_id
  std::uint8_t dlc = 0;  // 0..8
  std::uint8_t pad = 0;
  std::uint8_t res0 = 0;
  std::uint8_t res1 = 0;
  std::array<std::uint8_t, 8> data{};
};
static_assert(sizeof(CanFrame) == 16, "CanFrame must match struct can_frame");

inline constexpr std::uint32_t kEffFlag = 0x80000000U;  // extended frame
inline constexpr std::uint32_t kRtrFlag = 0x40000000U;  // remote request
inline constexpr std::uint32_t kErrFlag = 0x20000000U;  // error frame
inline constexpr std::uint32_t kSffMask = 0x000007FFU;

}  // namespace mcnc::can
