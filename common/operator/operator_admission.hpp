#pragma once
// Whether a process takes an operator command as it arrives (docs/operations.md "Operator
// commands"). A command is taken, and then waits in the process's OperatorInbox for its cycle,
// or refused with a reason that goes back to its sender; nothing is dropped unanswered. Pure:
// the caller says what the process knows now.
#include "common/operator/operator_inbox.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace mcnc::process {

// In the wire's order (idl/mcnc.idl OperatorRefusal): the numbers never change.
enum class OperatorRefusal : std::uint8_t {
  none,  // taken
  inbox_full,
  stale,
  too_far_ahead,
  earlier_run,
  unknown_origin,
  unknown_action,
  text_too_long
};

// The refusal numbered `number` on the wire; nullopt for a number this build does not know.
std::optional<OperatorRefusal> refusal_numbered(int number) noexcept;
// A short code for programs ("inbox_full"), and a sentence for people.
const char* code_of(OperatorRefusal refusal) noexcept;
const char* reason_of(OperatorRefusal refusal) noexcept;

// How far from the process's cycle a stamp may lie, and the inbox slots kept for commands due
// at the next cycle (unstamped, or stamped for it or a cycle already passed; due_after_next), so
// that commands stamped for later, however many, never keep out the operator's next one.
struct AdmissionLimits {
  std::uint64_t late_cycles = 1000;
  std::uint64_t ahead_cycles = 3'600'000;
  std::size_t reserved_slots = 8;
  // One second late and one hour ahead, in cycles of `cycle_us`.
  static AdmissionLimits for_cycle_us(std::uint32_t cycle_us) noexcept;
};

// The command as it came off the wire, before it is an OperatorRequest.
struct ArrivingCommand {
  std::uint64_t generation = 0;  // 0: whichever run goes on
  std::uint64_t cycle = 0;       // 0: the next cycle
  int action = 0;                // the wire's OperatorAction
  std::string_view origin;
  std::size_t text_size = 0;
};

// What the process knows as the command arrives.
struct AdmissionState {
  std::uint64_t cycle = 0;       // the last cycle it ran (0 before the run)
  std::uint64_t generation = 0;  // the run it runs
  std::size_t queued = 0;        // commands waiting in its inbox
  std::size_t queued_later = 0;  // of them, those due only after the next cycle
};

// Which commands a process serves: those of its channel (0: of any channel, as an axis node,
// whose owner changes) and, when `reset_only`, RESET alone.
struct OperatorScope {
  std::uint32_t channel = 0;
  bool reset_only = false;
  [[nodiscard]] bool covers(std::uint32_t command_channel, int action) const noexcept;
  // The channel with this id obeys every action; an axis node only RESET (of its owner).
  static OperatorScope of_channel(std::uint32_t id) noexcept { return {id, false}; }
  static OperatorScope of_axis_node() noexcept { return {0, true}; }
};

// The origins that command a machine, as OperatorCommand.origin names them: the launcher's
// script, the HMI and a command-line tool. Under DDS Security the permissions, not this name, say
// who may write a command.
bool commanding_origin(std::string_view origin) noexcept;

// none when the process takes the command; else the first reason found, looking at the command
// itself (action, text, origin), then its run, its stamp, and last the room left for it.
OperatorRefusal admit(const ArrivingCommand& command, const AdmissionState& now,
                      const AdmissionLimits& limits) noexcept;

}  // namespace mcnc::process
