#include "common/operator/operator_admission.hpp"

#include "common/config/machine_config.hpp"

#include <algorithm>

namespace mcnc::process {

std::optional<OperatorRefusal> refusal_numbered(int number) noexcept {
  if (number < 0 || number > static_cast<int>(OperatorRefusal::text_too_long)) {
    return std::nullopt;
  }
  return static_cast<OperatorRefusal>(number);
}

const char* code_of(OperatorRefusal refusal) noexcept {
  switch (refusal) {
    case OperatorRefusal::none:
      return "taken";
    case OperatorRefusal::inbox_full:
      return "inbox_full";
    case OperatorRefusal::stale:
      return "stale";
    case OperatorRefusal::too_far_ahead:
      return "too_far_ahead";
    case OperatorRefusal::earlier_run:
      return "earlier_run";
    case OperatorRefusal::unknown_origin:
      return "unknown_origin";
    case OperatorRefusal::unknown_action:
      return "unknown_action";
    case OperatorRefusal::text_too_long:
      return "text_too_long";
  }
  return "unknown";
}

const char* reason_of(OperatorRefusal refusal) noexcept {
  switch (refusal) {
    case OperatorRefusal::none:
      return "taken";
    case OperatorRefusal::inbox_full:
      return "the process holds as many commands as it keeps";
    case OperatorRefusal::stale:
      return "its cycle passed too long ago";
    case OperatorRefusal::too_far_ahead:
      return "its cycle lies too far beyond the machine's";
    case OperatorRefusal::earlier_run:
      return "it belongs to a run that is over";
    case OperatorRefusal::unknown_origin:
      return "its origin is not one that commands (launch, hmi, cli)";
    case OperatorRefusal::unknown_action:
      return "an action this build does not know";
    case OperatorRefusal::text_too_long:
      return "its text is longer than a command holds";
  }
  return "unknown";
}

AdmissionLimits AdmissionLimits::for_cycle_us(std::uint32_t cycle_us) noexcept {
  const int us = cycle_us == 0 ? 1 : static_cast<int>(cycle_us);
  AdmissionLimits limits;
  limits.late_cycles = config::cycles_of(1000, us);
  limits.ahead_cycles = 3600 * limits.late_cycles;
  return limits;
}

bool OperatorScope::covers(std::uint32_t command_channel, int action) const noexcept {
  const bool its_channel = channel == 0 || command_channel == 0 || command_channel == channel;
  return its_channel && (!reset_only || action == static_cast<int>(OperatorActionKind::reset));
}

bool commanding_origin(std::string_view origin) noexcept {
  return origin == "launch" || origin == "hmi" || origin == "cli";
}

OperatorRefusal admit(const ArrivingCommand& command, const AdmissionState& now,
                      const AdmissionLimits& limits) noexcept {
  if (command.action <= static_cast<int>(OperatorActionKind::none) ||
      command.action > static_cast<int>(OperatorActionKind::alarm_ack)) {
    return OperatorRefusal::unknown_action;
  }
  if (command.text_size >= OperatorRequest::kTextSize) {
    return OperatorRefusal::text_too_long;  // the NUL must fit too
  }
  if (!commanding_origin(command.origin)) {
    return OperatorRefusal::unknown_origin;
  }
  if (command.generation != 0 && command.generation < now.generation) {
    return OperatorRefusal::earlier_run;
  }
  if (command.cycle != 0 && command.cycle < now.cycle &&
      now.cycle - command.cycle > limits.late_cycles) {
    return OperatorRefusal::stale;
  }
  if (command.cycle > now.cycle && command.cycle - now.cycle > limits.ahead_cycles) {
    return OperatorRefusal::too_far_ahead;
  }
  const std::size_t later_room =
      OperatorInbox::kSlots - std::min(limits.reserved_slots, OperatorInbox::kSlots);
  if (now.queued >= OperatorInbox::kSlots ||
      (due_after_next(command.cycle, now.cycle) && now.queued_later >= later_room)) {
    return OperatorRefusal::inbox_full;
  }
  return OperatorRefusal::none;
}

}  // namespace mcnc::process
