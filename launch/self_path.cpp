#include "launch/self_path.hpp"

#include <filesystem>

namespace mcnc::launch {
std::string executable_dir() {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
}
}  // namespace mcnc::launch
