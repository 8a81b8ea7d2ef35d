#pragma once
// Canonical commands: what the interpreter hands to the planner, one per executable block.
// Positions are physical (mm or degrees; diameter axes already converted to radius) and are
// absolute in the channel's axis order (the order of the channel's `axes` in the machine file).
#include <array>
#include <cstdint>
#include <string>

namespace mcnc::interp {

inline constexpr std::size_t kMaxChannelAxes = 8;
using AxisVector = std::array<double, kMaxChannelAxes>;

enum class CommandKind {
  rapid,        // G00: every axis to `target` at rapid rate
  linear,       // G01: straight line to `target` at `feed`
  dwell,        // G04: wait `dwell_s`
  program_end,  // M30 / M02
};

struct CanonicalCommand {
  CommandKind kind = CommandKind::rapid;
  AxisVector target{};    // absolute end point, all axes (unchanged axes keep their value)
  double feed = 0.0;      // units/min along the path (linear)
  double dwell_s = 0.0;   // dwell
  int end_code = 0;       // 30 or 2 (program_end)
  int line = 0;           // 1-based line in the program file
  std::size_t block = 0;  // 1-based index of the block among executable blocks
};

// A program alarm: where and why. Raised before the offending block produces motion.
struct ProgramAlarm {
  int number = 0;  // alarm number (see docs/alarms.md)
  std::string text;
  std::string program;  // program name (file name)
  int line = 0;
  int column = 0;  // 1-based, 0 when not known
};

}  // namespace mcnc::interp
