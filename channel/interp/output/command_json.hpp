#pragma once
// The JSON form of canonical commands and alarms, one object per line (`mcnc interp`; schema in
// docs/canonical-commands.md). Appends to `out` so a caller can batch its writes.
#include "channel/interp/command.hpp"
#include "channel/interp/interp_config.hpp"

#include <string>
#include <vector>

namespace mcnc::interp::output {

// `main_file`: blocks of other files (subprograms from the program directory) carry "file".
void append_json(std::string& out, const Command& c, const std::vector<AxisConfig>& axes,
                 const std::string& main_file);
void append_json(std::string& out, const ProgramAlarm& a);

}  // namespace mcnc::interp::output
