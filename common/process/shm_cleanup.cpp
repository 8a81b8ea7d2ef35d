#include "common/process/shm_cleanup.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace mcnc::process {

namespace fs = std::filesystem;

std::size_t remove_stale_dds_shm_files() noexcept {
  try {
    const std::string dir = "/dev/shm/";
    std::vector<std::string> lock_files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename();
      if (name.rfind("fastrtps_", 0) == 0 && name.size() > 3 &&
          name.compare(name.size() - 3, 3, "_el") == 0) {
        lock_files.push_back(name);
      }
    }
    std::size_t removed = 0;
    for (const auto& lock_name : lock_files) {
      const std::string path = dir + lock_name;
      const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) {
        continue;
      }
      // Held exclusively by a live owner: leave it. Ours while we remove, so nobody re-opens it.
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        const std::string segment = lock_name.substr(0, lock_name.size() - 3);
        std::error_code rm;
        fs::remove(dir + segment, rm);
        fs::remove(dir + "sem." + segment + "_mutex", rm);
        fs::remove(path, rm);
        ++removed;
      }
      ::close(fd);
    }
    return removed;
  } catch (...) {
    return 0;
  }
}

}  // namespace mcnc::process
