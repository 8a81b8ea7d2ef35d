#pragma once
// Fast DDS leaves shared-memory files in /dev/shm when a process is killed (fastrtps_<segment>,
// fastrtps_port<N>, their _el lock files and sem.fastrtps_port<N>_mutex). A live owner holds an
// exclusive flock on <segment>_el for as long as the segment lives; a segment whose lock file
// can be locked has a dead owner. This removes exactly those, so it is safe while other DDS
// processes run.
#include <cstddef>

namespace mcnc::process {

// Returns how many segments were removed.
std::size_t remove_stale_dds_shm_files() noexcept;

}  // namespace mcnc::process
