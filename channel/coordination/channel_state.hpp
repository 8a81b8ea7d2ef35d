#pragma once
// The channel state machine's states (reset / idle / running / hold / waiting / alarm), and what
// a channel knows of another channel from its status: what the coordination state machines of
// one channel read of the others.
#include <cstdint>

namespace mcnc::coordination {

enum class ChannelState : std::uint8_t { reset, idle, running, hold, waiting, alarm };
const char* to_string(ChannelState state) noexcept;

// What a channel knows of another channel (its status stamped N-1).
struct PartnerStatus {
  bool known = false;
  ChannelState state = ChannelState::reset;
  std::uint64_t call_id = 0;  // the G144 call it runs, 0: none
  std::uint32_t call_caller = 0;
};

}  // namespace mcnc::coordination
