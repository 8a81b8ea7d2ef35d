#pragma once
// The channel's axis vector, which every stage of a channel shares: physical positions (mm or
// degrees, diameter axes already converted to radius) in the order of the channel's `axes` in
// the machine file.
#include <array>
#include <cstddef>

namespace mcnc::interp {

inline constexpr std::size_t kMaxChannelAxes = 8;
using AxisVector = std::array<double, kMaxChannelAxes>;

}  // namespace mcnc::interp
