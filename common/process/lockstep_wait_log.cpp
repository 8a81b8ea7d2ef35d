#include "common/process/lockstep_wait_log.hpp"

#include <spdlog/fmt/fmt.h>

namespace mcnc::process {

std::string lockstep_wait_text(std::uint64_t cycle, std::string_view whose,
                               const cycle::LockstepGate::Wait& wait) {
  if (!wait.sample_missing) {
    return fmt::format("cycle {} still waits for the events {} announce: up to {}, {} in", cycle,
                       whose, wait.events_announced, wait.events_received);
  }
  if (!wait.any_sample) {
    return fmt::format("cycle {} still waits for {} of cycle {} (none in yet)", cycle, whose,
                       cycle - 1);
  }
  return fmt::format("cycle {} still waits for {} of cycle {} (latest in: {})", cycle, whose,
                     cycle - 1, wait.latest_cycle);
}

}  // namespace mcnc::process
