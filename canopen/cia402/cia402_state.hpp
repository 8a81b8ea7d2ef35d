#pragma once
// CiA 402 power state machine: the statusword/controlword encoding (device side and master side).
#include <cstdint>

namespace mcnc::cia402 {

enum class State : std::uint8_t {
  not_ready_to_switch_on,
  switch_on_disabled,
  ready_to_switch_on,
  switched_on,
  operation_enabled,
  quick_stop_active,
  fault_reaction_active,
  fault,
};

const char* to_string(State state) noexcept;

// Statusword bits 0,1,2,3,5,6 per CiA 402 table; other bits ignored.
State decode_statusword(std::uint16_t statusword) noexcept;
// The statusword a device in `state` reports (bit 4 voltage enabled set when powered,
// bit 9 remote set; target reached bit 10 passed in).
std::uint16_t encode_statusword(State state, bool target_reached) noexcept;

// Controlword commands (CiA 402 device control commands).
enum class Command : std::uint8_t {
  none,               // keep the current controlword meaning (sends "disable voltage" = 0)
  shutdown,           // 0b0110
  switch_on,          // 0b0111
  enable_operation,   // 0b1111
  disable_voltage,    // 0b0000
  quick_stop,         // 0b0010
  disable_operation,  // 0b0111
  fault_reset,        // bit 7 rising edge
};
std::uint16_t encode_controlword(Command command) noexcept;
// The command a controlword means (device side); fault_reset when bit 7 set.
Command decode_controlword(std::uint16_t controlword) noexcept;

// Device side: the transition a drive makes on a controlword (one step per call, like a real
// drive that evaluates the controlword once per cycle). fault_reaction_active -> fault happens
// through on_fault_reaction_done(); a fault is injected with on_fault(). Quick stop option
// code 6: the drive ramps down and stays in quick_stop_active until enable_operation (back to
// operation_enabled) or disable_voltage (to switch_on_disabled).
class DeviceStateMachine {
 public:
  [[nodiscard]] State state() const noexcept { return state_; }
  void power_on() noexcept;  // not_ready_to_switch_on -> switch_on_disabled
  void apply(std::uint16_t controlword) noexcept;
  void on_fault() noexcept;                // any state -> fault_reaction_active
  void on_fault_reaction_done() noexcept;  // -> fault

 private:
  State state_ = State::not_ready_to_switch_on;
  std::uint16_t last_controlword_ = 0;
};

// Master side: given the drive's reported state and what the node wants, the next controlword.
// Goal enabled: shutdown -> switch on -> enable operation (resetting a fault first when asked).
// Goal quick_stop: quick stop from operation enabled (and from quick stop active, to stay there);
// disable voltage elsewhere.
// Goal enabled from quick_stop_active sends enable operation (transition 16). Stateless: from
// fault it sends fault reset (0x0080) when allow_fault_reset, else disable voltage (0x0000).
// Every other result has bit 7 clear, so the first 0x0080 is a rising edge; to retry a reset
// that did not clear the fault, pass allow_fault_reset = false for one cycle, then true again.
// not_ready_to_switch_on and fault_reaction_active get disable voltage (nothing to command).
enum class Goal : std::uint8_t { disabled, enabled, quick_stop };
std::uint16_t next_controlword(State reported, Goal goal, bool allow_fault_reset) noexcept;

}  // namespace mcnc::cia402
