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
//    While the run lasts its launcher keeps a record of that footprint in the directory
//    (mcnc_run_domain<N>_<launcher pid>: the names), so that when it is killed (`kill -9`) the
//    next run of the same domain on the host removes what it left: the recorded files and the
//    domain's port files that no process uses.
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
  // First removes what killed runs of `domain` left (the records whose launcher is gone), then
  // notes what the directory holds.
  explicit RunShmFootprint(int domain, std::string dir = "/dev/shm/");
  // Notes the files that process `pid` (one of the run's) uses now; with `keep_record`, also
  // writes the record of the run's footprint so far.
  void note_process(pid_t pid, bool keep_record = true) noexcept;
  // Removes the Fast DDS files that appeared during the run, are the run's and are used by no
  // process any more (with `in_use`, the full paths in use; by default read from /proc), and
  // the run's record. Returns how many files were removed.
  std::size_t remove_left_over() noexcept;
  std::size_t remove_left_over(const std::set<std::string>& in_use) noexcept;

  [[nodiscard]] const std::set<std::string>& before() const noexcept { return before_; }
  // What a killed run left and the constructor removed (file names).
  [[nodiscard]] const std::set<std::string>& removed_at_start() const noexcept {
    return removed_at_start_;
  }

 private:
  [[nodiscard]] bool of_this_run(const std::string& name) const noexcept;
  [[nodiscard]] std::string record_prefix() const;
  [[nodiscard]] std::string record_path() const;
  void remove_killed_run() noexcept;
  void write_record() const noexcept;

  int domain_;
  std::string dir_;
  std::set<std::string> before_;
  std::set<std::string> used_by_run_;  // names
  std::set<std::string> removed_at_start_;
};

}  // namespace mcnc::process
