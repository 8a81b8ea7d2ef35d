#include "canopen/cia402/cia402_state.hpp"

namespace mcnc::cia402 {
namespace {

// Statusword bits (CiA 402, object 0x6041).
constexpr std::uint16_t kSwReadyToSwitchOn = 1U << 0;
constexpr std::uint16_t kSwSwitchedOn = 1U << 1;
constexpr std::uint16_t kSwOperationEnabled = 1U << 2;
constexpr std::uint16_t kSwFault = 1U << 3;
constexpr std::uint16_t kSwVoltageEnabled = 1U << 4;
constexpr std::uint16_t kSwQuickStop = 1U << 5;  // active low: 0 = quick stop active
constexpr std::uint16_t kSwSwitchOnDisabled = 1U << 6;
constexpr std::uint16_t kSwRemote = 1U << 9;
constexpr std::uint16_t kSwTargetReached = 1U << 10;

// States whose table entry leaves bit 5 as "x" are matched with this mask, the others with
// the full one.
constexpr std::uint16_t kMaskWithoutQuickStop = 0x004F;
constexpr std::uint16_t kMaskWithQuickStop = 0x006F;

// Controlword bits (object 0x6040).
constexpr std::uint16_t kCwSwitchOn = 1U << 0;
constexpr std::uint16_t kCwEnableVoltage = 1U << 1;
constexpr std::uint16_t kCwQuickStop = 1U << 2;  // active low
constexpr std::uint16_t kCwEnableOperation = 1U << 3;
constexpr std::uint16_t kCwFaultReset = 1U << 7;

}  // namespace

const char* to_string(State state) noexcept {
  switch (state) {
    case State::not_ready_to_switch_on:
      return "not_ready_to_switch_on";
    case State::switch_on_disabled:
      return "switch_on_disabled";
    case State::ready_to_switch_on:
      return "ready_to_switch_on";
    case State::switched_on:
      return "switched_on";
    case State::operation_enabled:
      return "operation_enabled";
    case State::quick_stop_active:
      return "quick_stop_active";
    case State::fault_reaction_active:
      return "fault_reaction_active";
    case State::fault:
      return "fault";
  }
  return "unknown";
}

State decode_statusword(std::uint16_t statusword) noexcept {
  switch (statusword & kMaskWithoutQuickStop) {
    case 0x0000:
      return State::not_ready_to_switch_on;
    case 0x0040:
      return State::switch_on_disabled;
    case 0x000F:
      return State::fault_reaction_active;
    case 0x0008:
      return State::fault;
    default:
      break;
  }
  switch (statusword & kMaskWithQuickStop) {
    case 0x0021:
      return State::ready_to_switch_on;
    case 0x0023:
      return State::switched_on;
    case 0x0027:
      return State::operation_enabled;
    case 0x0007:
      return State::quick_stop_active;
    default:
      break;
  }
  // A combination the table does not define: the drive is not usable, like one still
  // initialising. The master then waits instead of commanding a transition.
  return State::not_ready_to_switch_on;
}

std::uint16_t encode_statusword(State state, bool target_reached) noexcept {
  // The simulated power stage has its DC link from power on: voltage enabled in every state
  // but the initialisation one.
  constexpr std::uint16_t kPowered = kSwVoltageEnabled | kSwRemote;
  std::uint16_t word = 0;
  switch (state) {
    case State::not_ready_to_switch_on:
      word = 0;
      break;
    case State::switch_on_disabled:
      word = kPowered | kSwSwitchOnDisabled;
      break;
    case State::ready_to_switch_on:
      word = kPowered | kSwQuickStop | kSwReadyToSwitchOn;
      break;
    case State::switched_on:
      word = kPowered | kSwQuickStop | kSwReadyToSwitchOn | kSwSwitchedOn;
      break;
    case State::operation_enabled:
      word = kPowered | kSwQuickStop | kSwReadyToSwitchOn | kSwSwitchedOn | kSwOperationEnabled;
      break;
    case State::quick_stop_active:
      word = kPowered | kSwReadyToSwitchOn | kSwSwitchedOn | kSwOperationEnabled;
      break;
    case State::fault_reaction_active:
      word = kPowered | kSwReadyToSwitchOn | kSwSwitchedOn | kSwOperationEnabled | kSwFault;
      break;
    case State::fault:
      word = kPowered | kSwFault;
      break;
  }
  if (target_reached) {
    word |= kSwTargetReached;
  }
  return word;
}

std::uint16_t encode_controlword(Command command) noexcept {
  switch (command) {
    case Command::none:
    case Command::disable_voltage:
      return 0x0000;
    case Command::shutdown:
      return 0x0006;
    case Command::switch_on:
    case Command::disable_operation:
      return 0x0007;
    case Command::enable_operation:
      return 0x000F;
    case Command::quick_stop:
      return 0x0002;
    case Command::fault_reset:
      return 0x0080;
  }
  return 0x0000;
}

Command decode_controlword(std::uint16_t controlword) noexcept {
  if ((controlword & kCwFaultReset) != 0) {
    return Command::fault_reset;
  }
  if ((controlword & kCwEnableVoltage) == 0) {
    return Command::disable_voltage;
  }
  if ((controlword & kCwQuickStop) == 0) {
    return Command::quick_stop;
  }
  if ((controlword & kCwSwitchOn) == 0) {
    return Command::shutdown;
  }
  if ((controlword & kCwEnableOperation) == 0) {
    // Same code as disable_operation; the current state decides which one it is.
    return Command::switch_on;
  }
  return Command::enable_operation;
}

void DeviceStateMachine::power_on() noexcept {
  if (state_ == State::not_ready_to_switch_on) {
    state_ = State::switch_on_disabled;  // transitions 0 and 1: self-test done
  }
}

void DeviceStateMachine::apply(std::uint16_t controlword) noexcept {
  const bool reset_edge =
      (controlword & kCwFaultReset) != 0 && (last_controlword_ & kCwFaultReset) == 0;
  last_controlword_ = controlword;
  const Command command = decode_controlword(controlword);

  switch (state_) {
    case State::not_ready_to_switch_on:
    case State::fault_reaction_active:
      // Internal transitions only (power_on, on_fault_reaction_done).
      break;
    case State::switch_on_disabled:
      if (command == Command::shutdown) {
        state_ = State::ready_to_switch_on;  // 2
      }
      break;
    case State::ready_to_switch_on:
      if (command == Command::switch_on || command == Command::enable_operation) {
        state_ = State::switched_on;  // 3 (with 0x0F, 4 follows on the next evaluation)
      } else if (command == Command::disable_voltage || command == Command::quick_stop) {
        state_ = State::switch_on_disabled;  // 7
      }
      break;
    case State::switched_on:
      if (command == Command::enable_operation) {
        state_ = State::operation_enabled;  // 4
      } else if (command == Command::shutdown) {
        state_ = State::ready_to_switch_on;  // 6
      } else if (command == Command::disable_voltage || command == Command::quick_stop) {
        state_ = State::switch_on_disabled;  // 10
      }
      break;
    case State::operation_enabled:
      if (command == Command::switch_on) {
        state_ = State::switched_on;  // 5 (disable operation)
      } else if (command == Command::shutdown) {
        state_ = State::ready_to_switch_on;  // 8
      } else if (command == Command::disable_voltage) {
        state_ = State::switch_on_disabled;  // 9
      } else if (command == Command::quick_stop) {
        state_ = State::quick_stop_active;  // 11
      }
      break;
    case State::quick_stop_active:
      // Quick stop option code 6: stay here after the ramp until told otherwise.
      if (command == Command::disable_voltage) {
        state_ = State::switch_on_disabled;  // 12
      } else if (command == Command::enable_operation) {
        state_ = State::operation_enabled;  // 16
      }
      break;
    case State::fault:
      if (reset_edge) {
        state_ = State::switch_on_disabled;  // 15
      }
      break;
  }
}

void DeviceStateMachine::on_fault() noexcept {
  // A further fault while already in fault keeps the drive there; the reaction is over.
  if (state_ != State::fault) {
    state_ = State::fault_reaction_active;  // 13
  }
}

void DeviceStateMachine::on_fault_reaction_done() noexcept {
  if (state_ == State::fault_reaction_active) {
    state_ = State::fault;  // 14
  }
}

std::uint16_t next_controlword(State reported, Goal goal, bool allow_fault_reset) noexcept {
  switch (goal) {
    case Goal::disabled:
      return encode_controlword(Command::disable_voltage);
    case Goal::quick_stop:
      if (reported == State::operation_enabled || reported == State::quick_stop_active) {
        return encode_controlword(Command::quick_stop);
      }
      return encode_controlword(Command::disable_voltage);
    case Goal::enabled:
      break;
  }
  switch (reported) {
    case State::switch_on_disabled:
      return encode_controlword(Command::shutdown);
    case State::ready_to_switch_on:
      return encode_controlword(Command::switch_on);
    case State::switched_on:
    case State::operation_enabled:
    case State::quick_stop_active:  // transition 16 back to operation enabled
      return encode_controlword(Command::enable_operation);
    case State::fault:
      return encode_controlword(allow_fault_reset ? Command::fault_reset
                                                  : Command::disable_voltage);
    case State::not_ready_to_switch_on:
    case State::fault_reaction_active:
      break;
  }
  return encode_controlword(Command::disable_voltage);
}

}  // namespace mcnc::cia402
