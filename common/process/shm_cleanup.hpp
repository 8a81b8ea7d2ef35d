#pragma once
// Fast DDS leaves shared-memory files in /dev/shm when a process is killed (fastrtps_<segment>,
// fastrtps_port<N>, their _el lock files, sem.fastrtps_port<N>_mutex and
// fast_datasharing_<participant>_<endpoint>). Several machines may run on one host at once (on
// different DDS domains), so a launcher removes only what its own run left:
//  - remove_stale_dds_shm_files(): a segment whose <segment>_el lock file can be locked has a
//    dead owner (a live one holds an exclusive flock for as long as the segment lives);
//  - RunShmFootprint: the files that appeared during the run and are the run's (a port of its
//    domain, or a file one of its processes mapped) and that no process still maps or holds
//    open.
#include <sys/types.h>

#include <cstddef>
#include <set>
#include <string>

namespace mcnc::process {

// Returns how many segments were removed.
std::size_t remove_stale_dds_shm_files() noexcept;

// Whether `name` (a file name in /dev/shm) is one that Fast DDS makes.
bool is_dds_shm_file(const std::string& name) noexcept;

// The Fast DDS files in `dir` (names).
std::set<std::string> dds_shm_files(const std::string& dir = "/dev/shm/") noexcept;

// The full paths of the files below `dir` that process `pid` maps or holds open.
std::set<std::string> files_used_by(pid_t pid, const std::string& dir = "/dev/shm/") noexcept;

// The full paths of the files below `dir` that any process of the host maps or holds open.
std::set<std::string> files_in_use(const std::string& dir = "/dev/shm/") noexcept;

// A run's shared-memory footprint: what the directory held before it, its DDS domain, and the
// files its processes were seen to use.
class RunShmFootprint {
 public:
  explicit RunShmFootprint(int domain, std::string dir = "/dev/shm/");
  // Notes the files that process `pid` (one of the run's) uses now.
  void note_process(pid_t pid) noexcept;
  // Removes the Fast DDS files that appeared during the run, are the run's and are used by no
  // process any more (with `in_use`, the full paths in use; by default read from /proc).
  // Returns how many were removed.
  std::size_t remove_left_over() noexcept;
  std::size_t remove_left_over(const std::set<std::string>& in_use) noexcept;

  [[nodiscard]] const std::set<std::string>& before() const noexcept { return before_; }

 private:
  [[nodiscard]] bool of_this_run(const std::string& name) const noexcept;

  int domain_;
  std::string dir_;
  std::set<std::string> before_;
  std::set<std::string> used_by_run_;  // names
};

}  // namespace mcnc::process
