#pragma once
// The JSON messages mcnc-hmi sends its browsers (docs/hmi.md, "Server to client"), built from
// the machine file and what the status topics said. Pure.
#include "common/config/machine_config.hpp"
#include "hmi_bridge/core/access_policy.hpp"
#include "hmi_bridge/core/alarm_log.hpp"
#include "hmi_bridge/core/meeting_tracker.hpp"
#include "tools/status/status_lines.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::hmi {

// The machine's layout: channels with their axes and spindles, every axis with its address.
std::string machine_message(const config::MachineConfig& machine);
std::string role_message(Role role);
// Every channel and axis as last heard (null fields for one not heard yet).
std::string state_message(const config::MachineConfig& machine,
                          const status::StatusSnapshot& snapshot);
std::string program_message(std::string_view channel, std::string_view name,
                            const std::vector<std::string>& lines);
std::string alarms_message(const config::MachineConfig& machine, const AlarmLog& log);
std::string alarm_message(const config::MachineConfig& machine, const AlarmEntry& entry);
// A G04.1 meeting: its mark, its channels and when (machine time), for the timeline.
std::string meeting_message(const config::MachineConfig& machine, const Meeting& meeting);
// A refused command's reply also names the refusal's code (OperatorRefusal's, or "unanswered")
// and the process that refused it, when there are such.
std::string reply_message(std::int64_t id, bool ok, std::string_view reason,
                          std::string_view refusal = {}, std::string_view process = {});
std::string error_message(std::string_view reason);

}  // namespace mcnc::hmi
