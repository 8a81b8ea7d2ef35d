#include "hmi_bridge/core/hmi_messages.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace mcnc::hmi {

namespace {

using Json = nlohmann::json;

Json channel_name(const config::MachineConfig& machine, std::uint64_t id) {
  const config::ChannelConfig* channel = machine.channel_by_id(id);
  return channel != nullptr ? Json(channel->name) : Json(nullptr);
}

Json axis_name(const config::MachineConfig& machine, std::uint64_t id) {
  const config::AxisConfig* axis = machine.axis_by_id(id);
  return axis != nullptr ? Json(axis->name) : Json(nullptr);
}

// The channels of a mask, bit c-1 for channel c.
Json channel_names(const config::MachineConfig& machine, std::uint64_t mask) {
  Json names = Json::array();
  for (std::size_t c = 1; c <= machine.channels.size() && c <= 64; ++c) {
    if ((mask >> (c - 1)) & 1U) {
      names.push_back(machine.channels[c - 1].name);
    }
  }
  return names;
}

const char* type_name(config::AxisType type) {
  switch (type) {
    case config::AxisType::linear:
      return "linear";
    case config::AxisType::rotary:
      return "rotary";
    case config::AxisType::spindle:
      return "spindle";
  }
  return "linear";
}

// What a channel waits for, null when it does not.
Json wait_of(const config::MachineConfig& machine, const status::ChannelView& v) {
  // The PLC's FIN is waited for while running (the path may still move); the others stop it.
  if (v.waiting_m >= 0 || v.waiting_t >= 0) {
    char code[16];
    if (v.waiting_m >= 0) {
      std::snprintf(code, sizeof code, "M%02d", static_cast<int>(v.waiting_m));
    } else {
      std::snprintf(code, sizeof code, "T%04d", static_cast<int>(v.waiting_t));
    }
    return {{"kind", "fin"}, {"code", code}};
  }
  if (v.state != channel::ChannelState::waiting) {
    return nullptr;
  }
  if (v.call_waiting_for != 0) {
    return {{"kind", "call"}, {"target", channel_name(machine, v.call_waiting_for)}};
  }
  if (v.sync_waiting_for != 0) {
    return {{"kind", "mark"},
            {"p", v.sync_p},
            {"participants", channel_names(machine, v.sync_channels)},
            {"waiting_for", channel_names(machine, v.sync_waiting_for)}};
  }
  if (v.waiting_exchange != 0) {
    return {{"kind", "exchange"},
            {"g", v.waiting_exchange},
            {"axis", v.waiting_axis != 0 ? axis_name(machine, v.waiting_axis) : Json(nullptr)}};
  }
  return {{"kind", "other"}};
}

// A G code ten times its number as a control writes it: 10 "G01", 0 "G00", 541 "G54.1".
std::string g_code(std::uint16_t g10) {
  char text[16];
  if (g10 % 10 == 0) {
    std::snprintf(text, sizeof text, "G%02u", static_cast<unsigned>(g10 / 10));
  } else {
    std::snprintf(text, sizeof text, "G%02u.%u", static_cast<unsigned>(g10 / 10),
                  static_cast<unsigned>(g10 % 10));
  }
  return text;
}

// The modal G codes of the executing block, in the order of the control's modal screen.
Json modal_of(const status::ChannelView& v) {
  Json list = Json::array();
  for (std::size_t k = 0; k < v.modal_g.size(); ++k) {
    if (k == 0 || v.modal_g[k] != 0) {  // group 01's G00 is a code; elsewhere 0 is none
      list.push_back(g_code(v.modal_g[k]));
    }
  }
  return list;
}

Json channel_state(const config::MachineConfig& machine, const config::ChannelConfig& ch,
                   const status::ChannelView* v) {
  Json j = {{"name", ch.name}};
  if (v == nullptr) {
    j["state"] = nullptr;
    return j;
  }
  j["state"] = channel::to_string(v->state);
  j["cycle"] = v->cycle;
  j["program"] = v->program;
  j["line"] = v->line;
  j["block"] = v->block;
  j["block_total"] = v->block_total;
  j["alarms"] = v->alarms;
  j["ended"] = v->program_end;
  j["end_code"] = v->end_code;
  j["wait"] = wait_of(machine, *v);
  j["call"] =
      v->call_caller != 0 ? Json{{"caller", channel_name(machine, v->call_caller)}} : Json(nullptr);
  j["feed_override"] = v->feed_override;
  j["rapid_override"] = v->rapid_override;
  j["spindle_override"] = v->spindle_override;
  j["single_block"] = v->single_block;
  j["spindle_rpm"] = v->spindle_rpm;
  j["modal"] = modal_of(*v);
  j["feed"] = v->modal_feed;
  return j;
}

Json axis_state(const config::MachineConfig& machine, const config::AxisConfig& axis,
                const status::AxisView* v) {
  Json j = {{"name", axis.name}};
  if (v == nullptr) {
    j["drive"] = nullptr;
    return j;
  }
  j["owner"] = channel_name(machine, v->owner);
  j["cmd"] = v->cmd;
  j["act"] = v->act;
  j["vel"] = v->vel;
  j["following_error"] = v->following_error;
  j["drive"] = status::drive_state_name(v->drive_state);
  j["enabled"] = v->enabled;
  j["alarm"] = v->alarm;
  j["coupled_to"] = axis_name(machine, v->coupled_to);
  j["locked"] = v->coupling_locked;
  j["load"] = v->load_known ? Json(v->load) : Json(nullptr);
  return j;
}

Json alarm_json(const config::MachineConfig& machine, const AlarmEntry& e) {
  return {{"seq", e.seq},
          {"src", e.src},
          {"number", e.number},
          {"text", e.text},
          {"channel", e.channel > 0 ? channel_name(machine, static_cast<std::uint64_t>(e.channel))
                                    : Json(nullptr)},
          {"axis", e.axis},
          {"line", e.line},
          {"program", e.program},
          {"column", e.column},
          {"cycle", e.cycle},
          {"acknowledged", e.acknowledged}};
}

// Texts from programs and drives may hold bytes that are not UTF-8: replaced, never thrown on.
std::string dump(const Json& j) {
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace

std::string machine_message(const config::MachineConfig& machine) {
  Json channels = Json::array();
  for (const config::ChannelConfig& ch : machine.channels) {
    channels.push_back({{"name", ch.name},
                        {"axes", ch.axes},
                        {"spindles", ch.spindles},
                        {"exchange_axes", ch.exchange_axes}});
  }
  Json axes = Json::array();
  for (const config::AxisConfig& a : machine.axes) {
    axes.push_back({{"name", a.name},
                    {"address", a.type == config::AxisType::spindle ? std::string("S")
                                                                    : std::string(1, a.address)},
                    {"type", type_name(a.type)},
                    {"diameter", a.diameter},
                    {"home", a.channel}});
  }
  return dump({{"type", "machine"},
               {"name", machine.name},
               {"cycle_us", machine.cycle_us},
               {"channels", channels},
               {"axes", axes}});
}

std::string role_message(Role role) {
  return dump({{"type", "role"}, {"role", to_string(role)}});
}

std::string state_message(const config::MachineConfig& machine,
                          const status::StatusSnapshot& snapshot) {
  std::uint64_t cycle = 0;
  Json channels = Json::array();
  for (const config::ChannelConfig& ch : machine.channels) {
    const auto it = snapshot.channels.find(static_cast<std::uint32_t>(ch.id));
    const status::ChannelView* v = it == snapshot.channels.end() ? nullptr : &it->second;
    cycle = v != nullptr ? std::max(cycle, v->cycle) : cycle;
    channels.push_back(channel_state(machine, ch, v));
  }
  Json axes = Json::array();
  for (const config::AxisConfig& a : machine.axes) {
    const auto it = snapshot.axes.find(static_cast<std::uint32_t>(a.id));
    axes.push_back(axis_state(machine, a, it == snapshot.axes.end() ? nullptr : &it->second));
  }
  static constexpr const char* kPhases[] = {"starting", "running", "stopped", "estop"};
  const Json run = {{"phase", kPhases[static_cast<std::size_t>(snapshot.run.phase)]},
                    {"reason", snapshot.run.reason}};
  return dump({{"type", "state"},
               {"cycle", cycle},
               {"time_s", static_cast<double>(cycle) * machine.cycle_s()},
               {"run", run},
               {"channels", channels},
               {"axes", axes}});
}

std::string program_message(std::string_view channel, std::string_view name,
                            const std::vector<std::string>& lines) {
  return dump({{"type", "program"}, {"channel", channel}, {"name", name}, {"lines", lines}});
}

std::string alarms_message(const config::MachineConfig& machine, const AlarmLog& log) {
  Json list = Json::array();
  for (const AlarmEntry& e : log.entries()) {
    list.push_back(alarm_json(machine, e));
  }
  return dump({{"type", "alarms"}, {"list", list}});
}

std::string alarm_message(const config::MachineConfig& machine, const AlarmEntry& entry) {
  Json j = alarm_json(machine, entry);
  j["type"] = "alarm";
  return dump(j);
}

std::string meeting_message(const config::MachineConfig& machine, const Meeting& meeting) {
  return dump({{"type", "meeting"},
               {"p", meeting.p},
               {"channels", channel_names(machine, meeting.channels)},
               {"cycle", meeting.cycle},
               {"time_s", static_cast<double>(meeting.cycle) * machine.cycle_s()}});
}

std::string reply_message(std::int64_t id, bool ok, std::string_view reason,
                          std::string_view refusal, std::string_view process) {
  Json reply = {{"type", "reply"}, {"id", id}, {"ok", ok}, {"reason", reason}};
  if (!refusal.empty()) {
    reply["refusal"] = refusal;
  }
  if (!process.empty()) {
    reply["process"] = process;
  }
  return dump(reply);
}

std::string error_message(std::string_view reason) {
  return dump({{"type", "error"}, {"reason", reason}});
}

}  // namespace mcnc::hmi
