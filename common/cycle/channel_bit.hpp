#pragma once
// Channel sets on the wire are 64-bit masks, bit c-1 for channel c (1-64): ChannelStatus,
// CoordinationEvent, AxisFeedback's refused and full channels. The one place that says so.
#include <cstdint>

namespace mcnc::cycle {

// The bit of channel `channel`; 0 for a number outside 1-64, which no mask can hold.
[[nodiscard]] constexpr std::uint64_t channel_bit(std::uint32_t channel) noexcept {
  return channel >= 1 && channel <= 64 ? std::uint64_t{1} << (channel - 1) : 0;
}

}  // namespace mcnc::cycle
