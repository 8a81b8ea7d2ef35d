#include "hmi_bridge/core/meeting_tracker.hpp"
#include "common/cycle/channel_bit.hpp"

#include <algorithm>

namespace mcnc::hmi {

std::optional<Meeting> MeetingTracker::arrive(std::uint32_t channel, std::int32_t p,
                                              std::uint64_t round, std::uint64_t participants,
                                              std::uint64_t cycle) {
  const std::uint64_t bit = mcnc::cycle::channel_bit(channel);
  if (bit == 0) {
    return std::nullopt;
  }
  const auto key = std::make_tuple(p, round, participants | bit);
  Gathering& g = open_[key];
  g.arrived |= bit;
  g.cycle = std::max(g.cycle, cycle);
  if ((g.arrived & std::get<2>(key)) != std::get<2>(key)) {
    return std::nullopt;
  }
  const Meeting m{p, std::get<2>(key), g.cycle};
  open_.erase(key);
  return m;
}

}  // namespace mcnc::hmi
