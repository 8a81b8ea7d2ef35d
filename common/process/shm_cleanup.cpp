#include "common/process/shm_cleanup.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

namespace mcnc::process {

namespace fs = std::filesystem;

namespace {

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

// The port in "fastrtps_port<N>", "fastrtps_port<N>_el" or "sem.fastrtps_port<N>_mutex"; -1
// for any other name.
long port_of(const std::string& name) {
  std::string rest;
  if (starts_with(name, "fastrtps_port")) {
    rest = name.substr(13);
  } else if (starts_with(name, "sem.fastrtps_port")) {
    rest = name.substr(17);
  } else {
    return -1;
  }
  char* end = nullptr;
  const long port = std::strtol(rest.c_str(), &end, 10);
  if (end == rest.c_str()) {
    return -1;
  }
  return port;
}

// Fast DDS's well-known ports (RTPS 9.6.1.1): a domain takes 250 ports from 7400 + 250 * id.
constexpr long kPortBase = 7400;
constexpr long kDomainGain = 250;

// The /dev/shm path in a line of /proc/<pid>/maps, or "".
std::string mapped_path(const std::string& line) {
  const auto slash = line.find('/');
  if (slash == std::string::npos) {
    return {};
  }
  std::string path = line.substr(slash);
  const std::string deleted = " (deleted)";
  if (path.size() > deleted.size() &&
      path.compare(path.size() - deleted.size(), deleted.size(), deleted) == 0) {
    path.resize(path.size() - deleted.size());
  }
  return path;
}

void add_files_used_by(const std::string& proc_dir, const std::string& dir,
                       std::set<std::string>& out) {
  std::ifstream maps(proc_dir + "/maps");
  for (std::string line; std::getline(maps, line);) {
    const std::string path = mapped_path(line);
    if (starts_with(path, dir.c_str())) {
      out.insert(path);
    }
  }
  std::error_code ec;
  for (const auto& fd : fs::directory_iterator(proc_dir + "/fd", ec)) {
    std::error_code rl;
    const std::string target = fs::read_symlink(fd.path(), rl).string();
    if (!rl && starts_with(target, dir.c_str())) {
      out.insert(target);
    }
  }
}

}  // namespace

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

bool is_dds_shm_file(const std::string& name) noexcept {
  return starts_with(name, "fastrtps_") || starts_with(name, "sem.fastrtps_") ||
         starts_with(name, "fast_datasharing_");
}

std::set<std::string> dds_shm_files(const std::string& dir) noexcept {
  std::set<std::string> out;
  try {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename();
      if (is_dds_shm_file(name)) {
        out.insert(name);
      }
    }
  } catch (...) {
  }
  return out;
}

std::set<std::string> files_used_by(pid_t pid, const std::string& dir) noexcept {
  std::set<std::string> out;
  try {
    add_files_used_by("/proc/" + std::to_string(pid), dir, out);
  } catch (...) {
  }
  return out;
}

std::set<std::string> files_in_use(const std::string& dir) noexcept {
  std::set<std::string> out;
  try {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/proc", ec)) {
      const std::string name = entry.path().filename();
      if (!name.empty() && name.find_first_not_of("0123456789") == std::string::npos) {
        add_files_used_by(entry.path().string(), dir, out);
      }
    }
  } catch (...) {
  }
  return out;
}

RunShmFootprint::RunShmFootprint(int domain, std::string dir)
    : domain_(domain), dir_(std::move(dir)) {
  remove_killed_run();
  before_ = dds_shm_files(dir_);
}

std::string RunShmFootprint::record_prefix() const {
  return "mcnc_run_domain" + std::to_string(domain_) + "_";
}

std::string RunShmFootprint::record_path() const {
  return dir_ + record_prefix() + std::to_string(::getpid());
}

void RunShmFootprint::remove_killed_run() noexcept {
  try {
    // One record per launcher (several hosts of a machine may share a /dev/shm): each names
    // its launcher's pid. A launcher that still runs keeps its record and its files.
    const std::string prefix = record_prefix();
    std::vector<std::string> records;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir_, ec)) {
      const std::string name = entry.path().filename();
      if (starts_with(name, prefix.c_str()) &&
          name.find_first_not_of("0123456789", prefix.size()) == std::string::npos) {
        const long launcher = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
        if (launcher > 0 && ::kill(static_cast<pid_t>(launcher), 0) != 0 && errno == ESRCH) {
          records.push_back(name);
        }
      }
    }
    if (records.empty()) {
      return;  // the last runs of the domain ended cleanly (or still run)
    }
    for (const std::string& record_name : records) {
      std::ifstream record(dir_ + record_name);
      for (std::string name; record >> name;) {
        used_by_run_.insert(name);
      }
    }
    const std::set<std::string> in_use = files_in_use(dir_);
    for (const std::string& name : dds_shm_files(dir_)) {
      if (!of_this_run(name) || in_use.count(dir_ + name) > 0) {
        continue;
      }
      std::error_code rm;
      if (fs::remove(dir_ + name, rm)) {
        removed_at_start_.insert(name);
      }
    }
    used_by_run_.clear();
    for (const std::string& record_name : records) {
      std::error_code rm;
      fs::remove(dir_ + record_name, rm);
    }
  } catch (...) {
  }
}

void RunShmFootprint::write_record() const noexcept {
  try {
    const std::string path = record_path();
    {
      std::ofstream record(path + ".new");
      for (const std::string& name : used_by_run_) {
        record << name << "\n";
      }
    }
    std::error_code ec;
    fs::rename(path + ".new", path, ec);  // whole or not at all
  } catch (...) {
  }
}

void RunShmFootprint::note_process(pid_t pid, bool keep_record) noexcept {
  try {
    for (const std::string& path : files_used_by(pid, dir_)) {
      used_by_run_.insert(path.substr(dir_.size()));
    }
  } catch (...) {
  }
  if (keep_record) {
    write_record();
  }
}

bool RunShmFootprint::of_this_run(const std::string& name) const noexcept {
  const long port = port_of(name);
  if (port >= 0) {
    const long first = kPortBase + kDomainGain * domain_;
    return port >= first && port < first + kDomainGain;
  }
  if (used_by_run_.count(name) > 0) {
    return true;
  }
  // A segment's lock file and semaphore go with the segment.
  for (const char* suffix : {"_el", "_mutex"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
      std::string segment = name.substr(0, name.size() - s.size());
      if (starts_with(segment, "sem.")) {
        segment = segment.substr(4);
      }
      return used_by_run_.count(segment) > 0;
    }
  }
  return false;
}

std::size_t RunShmFootprint::remove_left_over() noexcept {
  return remove_left_over(files_in_use(dir_));
}

std::size_t RunShmFootprint::remove_left_over(const std::set<std::string>& in_use) noexcept {
  std::size_t removed = 0;
  try {
    for (const std::string& name : dds_shm_files(dir_)) {
      if (before_.count(name) > 0 || !of_this_run(name) || in_use.count(dir_ + name) > 0) {
        continue;
      }
      std::error_code rm;
      if (fs::remove(dir_ + name, rm)) {
        ++removed;
      }
    }
    std::error_code rm;
    fs::remove(record_path(), rm);
  } catch (...) {
  }
  return removed;
}

}  // namespace mcnc::process
