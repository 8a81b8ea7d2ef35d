#include "channel/coordination/channel_state.hpp"

namespace mcnc::coordination {

const char* to_string(ChannelState state) noexcept {
  switch (state) {
    case ChannelState::reset:
      return "reset";
    case ChannelState::idle:
      return "idle";
    case ChannelState::running:
      return "running";
    case ChannelState::hold:
      return "hold";
    case ChannelState::waiting:
      return "waiting";
    case ChannelState::alarm:
      return "alarm";
  }
  return "reset";
}

}  // namespace mcnc::coordination
