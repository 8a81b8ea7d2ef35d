#pragma once
// What a browser may send over the HMI's WebSocket (docs/hmi.md), read and checked before
// anything acts on it: a malformed or out-of-range message is an error with its reason, never a
// command. Pure.
#include "common/config/machine_config.hpp"
#include "common/operator/operator_inbox.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

namespace mcnc::hmi {

inline constexpr std::size_t kMaxMessageBytes = 4096;

struct AuthMessage {
  std::string token;
};

struct CommandMessage {
  std::int64_t id = 0;  // the client's, echoed in the reply
  process::OperatorActionKind action = process::OperatorActionKind::none;
  std::uint32_t channel = 0;  // channel id; 0: the whole machine
  double value = 0.0;
  std::string text;  // select_program: a file name; mdi: one block; alarm_ack: the alarm's src
};

struct MessageError {
  std::int64_t id = -1;  // the command's id when it could be read, -1 otherwise
  std::string reason;
};

using ClientMessage = std::variant<AuthMessage, CommandMessage, MessageError>;

// Reads one text message. Channel names are the machine's; values must be finite and within
// the action's range (overrides, single block 0/1); texts printable ASCII and shorter than an
// operator command's text; a program name a plain file name.
ClientMessage read_client_message(std::string_view text, const config::MachineConfig& machine);

}  // namespace mcnc::hmi
