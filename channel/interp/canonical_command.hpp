#pragma once
// What every stage of a channel shares: the channel's axis vector (physical positions, mm or
// degrees, diameter axes already converted to radius, in the order of the channel's `axes` in
// the machine file) and a program alarm. The canonical commands are in command.hpp.
#include <array>
#include <cstdint>
#include <string>

namespace mcnc::interp {

inline constexpr std::size_t kMaxChannelAxes = 8;
using AxisVector = std::array<double, kMaxChannelAxes>;

// A program alarm: where and why. Raised before the offending block produces motion.
struct ProgramAlarm {
  int number = 0;  // alarm number (see docs/alarms.md)
  std::string text;
  std::string program;  // program name (file name)
  int line = 0;
  int column = 0;  // 1-based, 0 when not known
};

}  // namespace mcnc::interp
