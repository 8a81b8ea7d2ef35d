#pragma once
// A program alarm: where and why. Raised before the offending block produces motion. The
// numbers are in program_alarms.hpp and docs/alarms.md.
#include <string>

namespace mcnc::interp {

struct ProgramAlarm {
  int number = 0;  // alarm number (see docs/alarms.md)
  std::string text;
  std::string program;  // program name (file name)
  int line = 0;
  int column = 0;  // 1-based, 0 when not known
};

}  // namespace mcnc::interp
