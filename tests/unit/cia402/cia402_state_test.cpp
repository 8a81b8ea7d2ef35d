#include "canopen/cia402/cia402_state.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace mcnc::cia402 {
namespace {

constexpr State kAllStates[] = {
    State::not_ready_to_switch_on, State::switch_on_disabled,
    State::ready_to_switch_on,     State::switched_on,
    State::operation_enabled,      State::quick_stop_active,
    State::fault_reaction_active,  State::fault,
};

TEST(Cia402Statusword, DecodesEachStateOfTheTable) {
  // Typical words real drives send, with "x" bits set both ways.
  const std::vector<std::pair<std::uint16_t, State>> cases = {
      {0x0000, State::not_ready_to_switch_on},
      {0x0020, State::not_ready_to_switch_on},
      {0x0040, State::switch_on_disabled},
      {0x0250, State::switch_on_disabled},
      {0x0270, State::switch_on_disabled},
      {0x0021, State::ready_to_switch_on},
      {0x0231, State::ready_to_switch_on},
      {0x0023, State::switched_on},
      {0x0233, State::switched_on},
      {0x0027, State::operation_enabled},
      {0x0637, State::operation_enabled},
      {0x0007, State::quick_stop_active},
      {0x0217, State::quick_stop_active},
      {0x000F, State::fault_reaction_active},
      {0x003F, State::fault_reaction_active},
      {0x0008, State::fault},
      {0x0218, State::fault},
      {0x0238, State::fault},
  };
  for (const auto& [word, state] : cases) {
    EXPECT_EQ(decode_statusword(word), state) << std::hex << word;
  }
}

TEST(Cia402Statusword, IgnoresBitsOutsideTheMask) {
  // Bits 4 and 7..15 never change the state.
  EXPECT_EQ(decode_statusword(0xFF90 | 0x0027), State::operation_enabled);
  EXPECT_EQ(decode_statusword(0xFF90 | 0x0008), State::fault);
}

TEST(Cia402Statusword, EncodeDecodeRoundTrip) {
  for (const State state : kAllStates) {
    EXPECT_EQ(decode_statusword(encode_statusword(state, false)), state) << to_string(state);
    EXPECT_EQ(decode_statusword(encode_statusword(state, true)), state) << to_string(state);
    EXPECT_EQ(encode_statusword(state, true) & 0x0400, 0x0400);
    EXPECT_EQ(encode_statusword(state, false) & 0x0400, 0);
  }
  EXPECT_EQ(encode_statusword(State::operation_enabled, false), 0x0237);
  EXPECT_EQ(encode_statusword(State::switch_on_disabled, false), 0x0250);
  EXPECT_EQ(encode_statusword(State::fault, false), 0x0218);
}

TEST(Cia402Controlword, EncodeAndDecode) {
  EXPECT_EQ(encode_controlword(Command::shutdown), 0x0006);
  EXPECT_EQ(encode_controlword(Command::switch_on), 0x0007);
  EXPECT_EQ(encode_controlword(Command::enable_operation), 0x000F);
  EXPECT_EQ(encode_controlword(Command::disable_voltage), 0x0000);
  EXPECT_EQ(encode_controlword(Command::quick_stop), 0x0002);
  EXPECT_EQ(encode_controlword(Command::disable_operation), 0x0007);
  EXPECT_EQ(encode_controlword(Command::fault_reset), 0x0080);
  EXPECT_EQ(encode_controlword(Command::none), 0x0000);

  EXPECT_EQ(decode_controlword(0x0006), Command::shutdown);
  EXPECT_EQ(decode_controlword(0x0007), Command::switch_on);
  EXPECT_EQ(decode_controlword(0x000F), Command::enable_operation);
  EXPECT_EQ(decode_controlword(0x0000), Command::disable_voltage);
  EXPECT_EQ(decode_controlword(0x0001), Command::disable_voltage);
  EXPECT_EQ(decode_controlword(0x0002), Command::quick_stop);
  EXPECT_EQ(decode_controlword(0x000B), Command::quick_stop);
  EXPECT_EQ(decode_controlword(0x000E), Command::shutdown);
  EXPECT_EQ(decode_controlword(0x0080), Command::fault_reset);
  EXPECT_EQ(decode_controlword(0x008F), Command::fault_reset);
}

DeviceStateMachine powered() {
  DeviceStateMachine device;
  device.power_on();
  return device;
}

TEST(Cia402Device, PowerOnGoesToSwitchOnDisabled) {
  DeviceStateMachine device;
  EXPECT_EQ(device.state(), State::not_ready_to_switch_on);
  device.apply(0x0006);  // ignored while initialising
  EXPECT_EQ(device.state(), State::not_ready_to_switch_on);
  device.power_on();
  EXPECT_EQ(device.state(), State::switch_on_disabled);
}

TEST(Cia402Device, EnableSequenceWithNextControlword) {
  DeviceStateMachine device = powered();
  std::vector<State> seen{device.state()};
  std::vector<std::uint16_t> sent;
  for (int i = 0; i < 10 && device.state() != State::operation_enabled; ++i) {
    const std::uint16_t cw = next_controlword(device.state(), Goal::enabled, false);
    sent.push_back(cw);
    device.apply(cw);
    seen.push_back(device.state());
  }
  EXPECT_EQ(sent, (std::vector<std::uint16_t>{0x0006, 0x0007, 0x000F}));
  EXPECT_EQ(seen, (std::vector<State>{State::switch_on_disabled, State::ready_to_switch_on,
                                      State::switched_on, State::operation_enabled}));
  // Staying enabled keeps sending enable operation.
  EXPECT_EQ(next_controlword(device.state(), Goal::enabled, false), 0x000F);
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::operation_enabled);
}

TEST(Cia402Device, EnableFromFaultWithFaultReset) {
  DeviceStateMachine device = powered();
  device.on_fault();
  EXPECT_EQ(device.state(), State::fault_reaction_active);
  EXPECT_EQ(next_controlword(device.state(), Goal::enabled, true), 0x0000);
  device.apply(0x0080);  // no effect during the reaction
  EXPECT_EQ(device.state(), State::fault_reaction_active);
  device.on_fault_reaction_done();
  EXPECT_EQ(device.state(), State::fault);

  // Reset not allowed: the master keeps the drive disabled.
  EXPECT_EQ(next_controlword(device.state(), Goal::enabled, false), 0x0000);
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::fault);

  std::vector<std::uint16_t> sent;
  for (int i = 0; i < 10 && device.state() != State::operation_enabled; ++i) {
    const std::uint16_t cw = next_controlword(device.state(), Goal::enabled, true);
    sent.push_back(cw);
    device.apply(cw);
  }
  EXPECT_EQ(sent, (std::vector<std::uint16_t>{0x0080, 0x0006, 0x0007, 0x000F}));
  EXPECT_EQ(device.state(), State::operation_enabled);
}

TEST(Cia402Device, FaultResetNeedsARisingEdge) {
  DeviceStateMachine device = powered();
  device.apply(0x0080);  // bit 7 already high before the fault
  device.on_fault();
  device.on_fault_reaction_done();
  device.apply(0x0080);
  EXPECT_EQ(device.state(), State::fault);  // level, not edge
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::fault);
  device.apply(0x0080);
  EXPECT_EQ(device.state(), State::switch_on_disabled);  // 15
}

TEST(Cia402Device, OnFaultFromEveryState) {
  for (const State target : {State::switch_on_disabled, State::ready_to_switch_on,
                             State::switched_on, State::operation_enabled}) {
    DeviceStateMachine device = powered();
    while (device.state() != target) {
      device.apply(next_controlword(device.state(), Goal::enabled, false));
    }
    device.on_fault();
    EXPECT_EQ(device.state(), State::fault_reaction_active) << to_string(target);
    device.on_fault();
    device.on_fault_reaction_done();
    EXPECT_EQ(device.state(), State::fault);
    device.on_fault();
    EXPECT_EQ(device.state(), State::fault);
  }
}

DeviceStateMachine enabled() {
  DeviceStateMachine device = powered();
  device.apply(0x0006);
  device.apply(0x0007);
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::operation_enabled);
  return device;
}

TEST(Cia402Device, QuickStopStaysActiveWithOptionCode6) {
  DeviceStateMachine device = enabled();
  EXPECT_EQ(next_controlword(device.state(), Goal::quick_stop, false), 0x0002);
  device.apply(0x0002);
  EXPECT_EQ(device.state(), State::quick_stop_active);  // 11
  for (const std::uint16_t cw : {0x0002, 0x0006, 0x0007, 0x0002}) {
    device.apply(cw);
    EXPECT_EQ(device.state(), State::quick_stop_active) << cw;
  }
  EXPECT_EQ(next_controlword(device.state(), Goal::quick_stop, false), 0x0002);
  EXPECT_EQ(next_controlword(device.state(), Goal::enabled, false), 0x000F);
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::operation_enabled);  // 16

  device.apply(0x0002);
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::switch_on_disabled);  // 12
}

TEST(Cia402Device, QuickStopGoalOutsideOperationDisablesVoltage) {
  for (const State state : {State::switch_on_disabled, State::ready_to_switch_on,
                            State::switched_on, State::fault, State::not_ready_to_switch_on}) {
    EXPECT_EQ(next_controlword(state, Goal::quick_stop, true), 0x0000) << to_string(state);
  }
  DeviceStateMachine ready = powered();
  ready.apply(0x0006);
  ready.apply(0x0002);
  EXPECT_EQ(ready.state(), State::switch_on_disabled);  // 7
  DeviceStateMachine on = powered();
  on.apply(0x0006);
  on.apply(0x0007);
  on.apply(0x0002);
  EXPECT_EQ(on.state(), State::switch_on_disabled);  // 10
}

TEST(Cia402Device, RemainingTransitions) {
  DeviceStateMachine device = enabled();
  device.apply(0x0007);
  EXPECT_EQ(device.state(), State::switched_on);  // 5
  device.apply(0x0006);
  EXPECT_EQ(device.state(), State::ready_to_switch_on);  // 6
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::switch_on_disabled);  // 7

  device = enabled();
  device.apply(0x0006);
  EXPECT_EQ(device.state(), State::ready_to_switch_on);  // 8
  device = enabled();
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::switch_on_disabled);  // 9
  device = powered();
  device.apply(0x0006);
  device.apply(0x0007);
  device.apply(0x0000);
  EXPECT_EQ(device.state(), State::switch_on_disabled);  // 10

  // "Switch on + enable operation" from ready to switch on: 3 then 4, one per evaluation.
  device = powered();
  device.apply(0x0006);
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::switched_on);
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::operation_enabled);

  // Enable operation is not a way out of switch on disabled.
  device = powered();
  device.apply(0x000F);
  EXPECT_EQ(device.state(), State::switch_on_disabled);
}

TEST(Cia402Master, DisabledGoalAlwaysDisablesVoltage) {
  for (const State state : kAllStates) {
    EXPECT_EQ(next_controlword(state, Goal::disabled, true), 0x0000) << to_string(state);
  }
}

TEST(Cia402, ToStringNamesEveryState) {
  for (const State state : kAllStates) {
    EXPECT_NE(std::string(to_string(state)), "unknown");
  }
  EXPECT_STREQ(to_string(State::quick_stop_active), "quick_stop_active");
}

}  // namespace
}  // namespace mcnc::cia402
