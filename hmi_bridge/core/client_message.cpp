#include "hmi_bridge/core/client_message.hpp"

#include "common/text/file_name.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace mcnc::hmi {

namespace {

using process::OperatorActionKind;
using Json = nlohmann::json;

struct Range {
  double min;
  double max;
};

// The value an action needs, and its range; actions without a value have none.
bool value_range(OperatorActionKind action, Range& range) noexcept {
  switch (action) {
    case OperatorActionKind::feed_override:
      range = {0.0, 200.0};
      return true;
    case OperatorActionKind::rapid_override:
      range = {0.0, 100.0};
      return true;
    case OperatorActionKind::spindle_override:
      range = {50.0, 120.0};
      return true;
    case OperatorActionKind::single_block:
      range = {0.0, 1.0};
      return true;
    case OperatorActionKind::alarm_ack:
      range = {1.0, 9.0e15};
      return true;
    default:
      return false;
  }
}

bool needs_text(OperatorActionKind action) noexcept {
  return action == OperatorActionKind::select_program || action == OperatorActionKind::mdi ||
         action == OperatorActionKind::alarm_ack;
}

bool printable(const std::string& text) noexcept {
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) {
      return false;
    }
  }
  return true;
}

MessageError error(std::int64_t id, std::string reason) {
  return MessageError{id, std::move(reason)};
}

ClientMessage read_command(const Json& j, const config::MachineConfig& machine) {
  const auto id_it = j.find("id");
  if (id_it == j.end() || !id_it->is_number_integer()) {
    return error(-1, "a command needs an integer \"id\"");
  }
  CommandMessage c;
  c.id = id_it->get<std::int64_t>();
  const auto action_it = j.find("action");
  if (action_it == j.end() || !action_it->is_string()) {
    return error(c.id, "a command needs an \"action\"");
  }
  c.action = process::action_named(action_it->get<std::string>());
  if (c.action == OperatorActionKind::none) {
    return error(c.id, "unknown action \"" + action_it->get<std::string>() + "\"");
  }
  const auto channel_it = j.find("channel");
  if (channel_it != j.end() && !channel_it->is_null()) {
    if (!channel_it->is_string()) {
      return error(c.id, "\"channel\" must be a channel's name");
    }
    const std::string name = channel_it->get<std::string>();
    for (std::size_t i = 0; i < machine.channels.size(); ++i) {
      if (machine.channels[i].name == name) {
        c.channel = static_cast<std::uint32_t>(i + 1);
      }
    }
    if (c.channel == 0) {
      return error(c.id, "no channel \"" + name.substr(0, 32) + "\" on this machine");
    }
  }
  const bool per_channel = c.action == OperatorActionKind::select_program ||
                           c.action == OperatorActionKind::mdi ||
                           c.action == OperatorActionKind::single_block;
  if (per_channel && c.channel == 0) {
    return error(c.id, std::string(process::to_string(c.action)) + " needs a \"channel\"");
  }
  Range range{};
  if (value_range(c.action, range)) {
    const auto value_it = j.find("value");
    if (value_it == j.end() || !value_it->is_number()) {
      return error(c.id, std::string(process::to_string(c.action)) + " needs a number \"value\"");
    }
    c.value = value_it->get<double>();
    if (!std::isfinite(c.value) || c.value < range.min || c.value > range.max) {
      char text[128];
      std::snprintf(text, sizeof text, "%s: value out of %g-%g", process::to_string(c.action),
                    range.min, range.max);
      return error(c.id, text);
    }
  }
  if (needs_text(c.action)) {
    const auto text_it = j.find("text");
    if (text_it == j.end() || !text_it->is_string() || text_it->get<std::string>().empty()) {
      return error(c.id, std::string(process::to_string(c.action)) + " needs a \"text\"");
    }
    c.text = text_it->get<std::string>();
    if (c.text.size() >= process::OperatorRequest::kTextSize || !printable(c.text)) {
      return error(c.id, "\"text\" must be printable ASCII, at most " +
                             std::to_string(process::OperatorRequest::kTextSize - 1) +
                             " characters");
    }
    if (c.action == OperatorActionKind::select_program && !text::is_plain_file_name(c.text)) {
      return error(c.id, "a program is named by its file name in the program store");
    }
  }
  return c;
}

}  // namespace

ClientMessage read_client_message(std::string_view text, const config::MachineConfig& machine) {
  if (text.size() > kMaxMessageBytes) {
    return error(-1, "message longer than " + std::to_string(kMaxMessageBytes) + " bytes");
  }
  const Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    return error(-1, "not a JSON object");
  }
  const auto type_it = j.find("type");
  if (type_it == j.end() || !type_it->is_string()) {
    return error(-1, "a message needs a \"type\"");
  }
  const std::string type = type_it->get<std::string>();
  if (type == "auth") {
    const auto token_it = j.find("token");
    if (token_it == j.end() || !token_it->is_string()) {
      return error(-1, "auth needs a \"token\"");
    }
    return AuthMessage{token_it->get<std::string>()};
  }
  if (type == "command") {
    return read_command(j, machine);
  }
  return error(-1, "unknown message type \"" + type.substr(0, 32) + "\"");
}

}  // namespace mcnc::hmi
