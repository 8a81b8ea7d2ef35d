#include "iceoryx_tmp.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>
#include <vector>

namespace mcnc::test {

namespace {

bool iceoryx_owns(const std::string& name, const struct stat& st) {
  return S_ISSOCK(st.st_mode) || name.rfind("iox-", 0) == 0 || name.rfind("roudi", 0) == 0 ||
         name.rfind("iceoryx_", 0) == 0;
}

std::string failed(const std::string& what) {
  return what + ": " + std::strerror(errno);
}

}  // namespace

std::string cover_iceoryx_files(const std::string& tmp) {
  // Opened before the cover: the covered folder stays reachable through the descriptor.
  const int covered = ::open(tmp.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (covered < 0) {
    return failed("open " + tmp);
  }
  std::vector<std::pair<std::string, mode_t>> kept;
  DIR* dir = ::fdopendir(::dup(covered));
  if (dir == nullptr) {
    const std::string why = failed("read " + tmp);
    ::close(covered);
    return why;
  }
  while (const dirent* e = ::readdir(dir)) {
    const std::string name = e->d_name;
    struct stat st {};
    if (name == "." || name == ".." ||
        ::fstatat(covered, e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0 || iceoryx_owns(name, st)) {
      continue;
    }
    if (S_ISDIR(st.st_mode) || S_ISREG(st.st_mode)) {
      kept.emplace_back(name, st.st_mode);
    }
  }
  ::closedir(dir);
  if (::mount("tmpfs", tmp.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777") != 0) {
    const std::string why = failed("tmpfs on " + tmp);
    ::close(covered);
    return why;
  }
  std::string why;
  for (const auto& [name, mode] : kept) {
    const std::string at = tmp + "/" + name;
    const bool made = S_ISDIR(mode) ? ::mkdir(at.c_str(), 0700) == 0
                                    : ::close(::open(at.c_str(), O_CREAT | O_WRONLY, 0600)) == 0;
    if (!made) {
      why = failed("make " + at);
      break;
    }
    // A bind mount's source must be one of this namespace's mounts: through the descriptor.
    const std::string from = "/proc/self/fd/" + std::to_string(covered) + "/" + name;
    if (::mount(from.c_str(), at.c_str(), nullptr, MS_BIND | MS_REC, nullptr) != 0) {
      if (errno != ENOENT) {
        why = failed("bind " + at);
        break;
      }
      ::remove(at.c_str());  // gone from the covered folder since it was listed
    }
  }
  ::close(covered);
  return why;
}

}  // namespace mcnc::test
