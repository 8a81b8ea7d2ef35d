#pragma once
// One spdlog logger per process, named after the process (CH1, X1, drivesim-can0, launch).
#include <string>

namespace mcnc::log {

// Level from `level` ("trace".."off"); empty: MCNC_LOG_LEVEL, else "info". Logs go to stderr.
void setup(const std::string& process_name, const std::string& level = {});

}  // namespace mcnc::log
