#pragma once
// The log line of a lockstep cycle that waits long for an input (decision 7: such waits never
// give up, and say what they wait for): "cycle N still waits for <whose> of cycle N-1 (latest
// in: M)", or for the events that input's sample announces.
#include "common/cycle/lockstep_gate.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace mcnc::process {

// `whose`: the input as the operator knows it ("CH2's setpoints", "S1's feedback").
std::string lockstep_wait_text(std::uint64_t cycle, std::string_view whose,
                               const cycle::LockstepGate::Wait& wait);

}  // namespace mcnc::process
