#include "tools/status/status_lines.hpp"

#include "canopen/cia402/cia402_state.hpp"
#include "common/config/cyclic_routes.hpp"

#include <algorithm>
#include <cstdio>

namespace mcnc::status {

const char* drive_state_name(std::uint8_t drive_state) noexcept {
  // The wire's DriveState is cia402::State in the same order (axisnode's to_wire).
  return drive_state <= static_cast<std::uint8_t>(cia402::State::fault)
             ? cia402::to_string(static_cast<cia402::State>(drive_state))
             : "unknown";
}

namespace {

std::string padded(const std::string& text, std::size_t width) {
  return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

std::string channel_line(const config::MachineConfig& machine, const ChannelView& c) {
  char head[96];
  std::snprintf(head, sizeof head, "%-8s block %u/%u  line %d", channel::to_string(c.state),
                c.block, c.block_total, c.line);
  std::string out = head;
  if (c.state == ChannelState::waiting && c.sync_p != 0) {
    out += "  waits at G04.1 P" + std::to_string(c.sync_p);
    std::string whom;
    for (std::uint32_t ch = 1; ch <= 64; ++ch) {
      if ((c.sync_waiting_for >> (ch - 1) & 1U) != 0) {
        whom += (whom.empty() ? "" : ", ") + config::channel_name(machine, ch);
      }
    }
    out += whom.empty() ? "" : " for " + whom;
  }
  if (c.call_caller != 0) {
    out += "  runs a call of " + config::channel_name(machine, c.call_caller);
  }
  if (c.program_end) {
    out += "  ended";
  }
  if (c.alarms > 0) {
    out += "  " + std::to_string(c.alarms) + (c.alarms == 1 ? " alarm" : " alarms");
  }
  return out;
}

std::string axis_line(const config::MachineConfig& machine, const config::AxisConfig& a,
                      const AxisView& v) {
  std::string owner = v.owner == 0 ? "released" : config::channel_name(machine, v.owner);
  if (v.released_by != 0) {
    owner += " (from " + config::channel_name(machine, v.released_by) + ")";
  }
  char body[160];
  if (a.type == config::AxisType::spindle) {
    std::snprintf(body, sizeof body, "%.1f rpm  %s", v.vel / 6.0,
                  v.mode_display == 8 ? "position (CSP)" : "speed (CSV)");
  } else {
    std::snprintf(body, sizeof body, "cmd %.4f  act %.4f  error %.4f", v.cmd, v.act,
                  v.following_error);
  }
  std::string out = padded(owner, 8) + "  " + body;
  if (v.coupled_to != 0) {
    out += "  follows " + config::axis_name(machine, v.coupled_to) +
           (a.type == config::AxisType::spindle
                ? (v.coupling_locked ? " (in phase)" : " (catching up)")
                : "");
  }
  out += v.alarm ? "  ALARM" : v.enabled ? "" : "  disabled";
  return out;
}

}  // namespace

std::vector<std::string> status_lines(const config::MachineConfig& machine,
                                      const StatusSnapshot& snapshot) {
  std::size_t width = 0;
  for (const config::ChannelConfig& c : machine.channels) {
    width = std::max(width, c.name.size());
  }
  for (const config::AxisConfig& a : machine.axes) {
    width = std::max(width, a.name.size());
  }
  std::vector<std::string> lines;
  for (const config::ChannelConfig& c : machine.channels) {
    const auto it = snapshot.channels.find(static_cast<std::uint32_t>(c.id));
    lines.push_back(padded(c.name, width) + "  " +
                    (it == snapshot.channels.end() ? std::string("no status")
                                                   : channel_line(machine, it->second)));
  }
  for (const config::AxisConfig& a : machine.axes) {
    const auto it = snapshot.axes.find(static_cast<std::uint32_t>(a.id));
    lines.push_back(padded(a.name, width) + "  " +
                    (it == snapshot.axes.end() ? std::string("no feedback")
                                               : axis_line(machine, a, it->second)));
  }
  for (const config::HostConfig& h : machine.hosts) {
    const auto it = snapshot.host_clocks.find(h.name);
    char text[128];
    if (it == snapshot.host_clocks.end()) {
      std::snprintf(text, sizeof text, "host %s  no clock announced", h.name.c_str());
    } else if (it->second.samples == 0) {
      std::snprintf(text, sizeof text, "host %s  clock: machine time (coordinator)",
                    h.name.c_str());
    } else {
      std::snprintf(text, sizeof text, "host %s  clock %+.1f us +- %.1f us (%u exchanges)",
                    h.name.c_str(), static_cast<double>(it->second.offset_ns) / 1000.0,
                    static_cast<double>(it->second.error_ns) / 1000.0, it->second.samples);
    }
    lines.emplace_back(text);
  }
  return lines;
}

std::vector<std::string> missing(const config::MachineConfig& machine,
                                 const StatusSnapshot& snapshot) {
  std::vector<std::string> out;
  for (const config::ChannelConfig& c : machine.channels) {
    if (!snapshot.channels.contains(static_cast<std::uint32_t>(c.id))) {
      out.push_back(c.name);
    }
  }
  for (const config::AxisConfig& a : machine.axes) {
    if (!snapshot.axes.contains(static_cast<std::uint32_t>(a.id))) {
      out.push_back(a.name);
    }
  }
  return out;
}

}  // namespace mcnc::status
