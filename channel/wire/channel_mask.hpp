#pragma once
// Channel sets on the wire: a 64-bit mask, bit c-1 for channel c (ChannelStatus,
// CoordinationEvent).
#include "channel/coordination/sync_barrier.hpp"
#include "common/cycle/channel_bit.hpp"

#include <cstdint>

namespace mcnc::channel {

inline std::uint64_t to_mask(const coordination::ChannelSet& set) noexcept {
  std::uint64_t mask = 0;
  for (std::uint32_t c = 1; c <= coordination::kMaxChannels; ++c) {
    if (set.test(c)) {
      mask |= cycle::channel_bit(c);
    }
  }
  return mask;
}

inline coordination::ChannelSet from_mask(std::uint64_t mask) noexcept {
  coordination::ChannelSet set;
  for (std::uint32_t c = 1; c <= coordination::kMaxChannels; ++c) {
    set.set(c, (mask & cycle::channel_bit(c)) != 0);
  }
  return set;
}

}  // namespace mcnc::channel
