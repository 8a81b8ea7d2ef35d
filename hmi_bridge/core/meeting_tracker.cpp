#include "hmi_bridge/core/meeting_tracker.hpp"

#include <algorithm>

namespace mcnc::hmi {

std::optional<Meeting> MeetingTracker::arrive(std::uint32_t channel, std::int32_t p,
                                              std::uint64_t round, std::uint64_t participants,
                                              std::uint64_t cycle) {
  if (channel < 1 || channel > 64) {
    return std::nullopt;
  }
  const std::uint64_t bit = std::uint64_t{1} << (channel - 1);
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
