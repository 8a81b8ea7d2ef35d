#pragma once
#include <string>

namespace mcnc::launch {
// The folder of the running executable (where the other mcnc-* executables are installed).
std::string executable_dir();
}  // namespace mcnc::launch
