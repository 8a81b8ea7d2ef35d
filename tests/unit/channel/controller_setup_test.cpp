// A channel's axes in program order and its controller's set-up, as the twin turret's machine
// file gives them.
#include "channel/setup/controller_setup.hpp"
#include "channel/setup/interpreter_setup.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

config::MachineConfig twin_turret() {
  return config::load_machine_file(std::string(MCNC_SOURCE_DIR) +
                                   "/launch/machines/twin_turret.yaml");
}

TEST(ControllerSetup, AnAxisTheChannelMayAcquireIsASlotAfterItsOwnAndTheSpindlesCAxisComesLast) {
  const config::MachineConfig m = twin_turret();
  const ControllerLayout ch2 = controller_layout_for(m, *m.find_channel("CH2"));
  ASSERT_GE(ch2.axes.size(), 3U);
  EXPECT_EQ(ch2.axes[0]->name, "X2");
  EXPECT_EQ(ch2.axes[1]->name, "Z2");
  EXPECT_EQ(ch2.axes[2]->name, "A1");
  EXPECT_FALSE(ch2.setup.slots[1].exchange_slot);
  EXPECT_TRUE(ch2.setup.slots[2].exchange_slot);
  EXPECT_EQ(ch2.setup.slots[2].home, static_cast<std::uint32_t>(m.find_channel("CH1")->id));
  EXPECT_EQ(ch2.setup.axis_count, ch2.axes.size());
  EXPECT_EQ(ch2.setup.in_position.size(), ch2.axes.size());
  ASSERT_EQ(ch2.spindles.size(), 1U);
  EXPECT_EQ(ch2.spindles[0]->name, "S2");
  EXPECT_TRUE(ch2.setup.spindle_may_follow) << "S2 is the slave of G114.1 group 1";
  EXPECT_TRUE(ch2.setup.spindle_groups.empty());

  const ControllerLayout ch1 = controller_layout_for(m, *m.find_channel("CH1"));
  EXPECT_EQ(ch1.axes.back()->name, "C1") << "S1's C axis, on the spindle's node";
  EXPECT_EQ(ch1.setup.spindle_c_slot, ch1.axes.size() - 1);
  EXPECT_FALSE(ch1.setup.spindle_may_follow);
  // CH1 leads group 1: its slave's feedback comes after CH1's axes and spindles.
  ASSERT_EQ(ch1.setup.spindle_groups.size(), 1U);
  EXPECT_EQ(ch1.setup.spindle_groups[0].group, 1);
  EXPECT_EQ(ch1.setup.spindle_groups[0].slave_view, ch1.axes.size() + 1);
  EXPECT_EQ(ch1.setup.machine_axes.size(), m.axes.size());
}

// G04 I and G04 PS: a PLC input's port names its bit of the PLC status, the channel's
// speed_arrival gives params 1057/1059; a port on an output, twice, or out of range is refused.
std::string with_plc(const std::string& signals, const std::string& channel_extra = "") {
  return "machine: {name: m, cycle_us: 1000}\n"
         "buses: [{name: b, uri: \"socketcan:can0\", sync_producer: X1}]\n"
         "axes:\n"
         "  - {name: X1, address: X, bus: b, node_id: 1}\n"
         "  - {name: S1, type: spindle, bus: b, node_id: 2}\n"
         "channels: [{name: CH1, axes: [X1], spindles: [S1]" +
         channel_extra +
         "}]\n"
         "plc:\n"
         "  signals:\n" +
         signals;
}

TEST(ControllerSetup, PlcInputPortsAndSpeedArrivalReachTheChannel) {
  const config::MachineConfig m = config::parse_machine_yaml(
      with_plc("    - {name: lamp, type: output}\n"
               "    - {name: door, type: input, port: 7}\n"
               "    - {name: part, type: input, follows: lamp, port: 2}\n",
               ", speed_arrival: {tolerance: 5, timeout: 3}"));
  const ControllerLayout ch = controller_layout_for(m, *m.find_channel("CH1"));
  ASSERT_EQ(ch.setup.input_ports.size(), 8U);
  EXPECT_EQ(ch.setup.input_ports[7], 1);  // door is signal 1
  EXPECT_EQ(ch.setup.input_ports[2], 2);
  EXPECT_EQ(ch.setup.input_ports[3], -1);
  EXPECT_DOUBLE_EQ(ch.setup.speed_arrival_rpm, 5.0);
  EXPECT_DOUBLE_EQ(ch.setup.speed_arrival_timeout_s, 3.0);
  const interp::InterpreterConfig ic = interpreter_config_for(m, *m.find_channel("CH1"));
  EXPECT_EQ(ic.input_ports, (std::vector<int>{7, 2}));

  EXPECT_THROW(config::parse_machine_yaml(with_plc("    - {name: l, type: output, port: 1}\n")),
               config::ConfigError);
  EXPECT_THROW(config::parse_machine_yaml(with_plc("    - {name: a, type: input, port: 1}\n"
                                                   "    - {name: b, type: input, port: 1}\n")),
               config::ConfigError);
  EXPECT_THROW(config::parse_machine_yaml(with_plc("    - {name: a, type: input, port: 100}\n")),
               config::ConfigError);
  EXPECT_THROW(config::parse_machine_yaml(
                   with_plc("    - {name: a, type: input}\n", ", speed_arrival: {tolerance: -1}")),
               config::ConfigError);
}

}  // namespace
}  // namespace mcnc::channel

namespace mcnc::channel {
namespace {

// polygon_lathe.yaml: CH1's polygon axis T1 and its master S1 are its spindles, their feedback
// right after its axes; 3000 rpm at most.
TEST(ControllerSetup, ThePolygonAxisAndItsMasterAreTheChannelsSpindles) {
  const config::MachineConfig m = config::load_machine_file(std::string(MCNC_SOURCE_DIR) +
                                                            "/launch/machines/polygon_lathe.yaml");
  const ControllerLayout ch1 = controller_layout_for(m, *m.find_channel("CH1"));
  ASSERT_EQ(ch1.spindles.size(), 2U);
  EXPECT_EQ(ch1.setup.polygon.master, static_cast<std::uint32_t>(m.find_axis("S1")->id));
  EXPECT_EQ(ch1.setup.polygon.master_view, ch1.axes.size());
  EXPECT_EQ(ch1.setup.polygon.slave_view, ch1.axes.size() + 1);
  EXPECT_DOUBLE_EQ(ch1.setup.polygon.max_speed, 3000.0 * 6.0);
  // A machine without: G51.2 has no polygon axis.
  const config::MachineConfig twin =
      config::load_machine_file(std::string(MCNC_SOURCE_DIR) + "/launch/machines/twin_turret.yaml");
  EXPECT_EQ(controller_layout_for(twin, *twin.find_channel("CH1")).setup.polygon.master, 0U);
}

// polygon_servo_lathe.yaml: CH1's polygon axis is its third axis, C1, whose slot the program
// does not move while it follows; S1's feedback comes after the axes.
TEST(ControllerSetup, AServoPolygonAxisIsOneOfTheChannelsAxisSlots) {
  const config::MachineConfig m = config::load_machine_file(
      std::string(MCNC_SOURCE_DIR) + "/launch/machines/polygon_servo_lathe.yaml");
  const ControllerLayout ch1 = controller_layout_for(m, *m.find_channel("CH1"));
  ASSERT_EQ(ch1.axes.size(), 3U);
  EXPECT_EQ(ch1.setup.polygon.master_view, 3U);
  EXPECT_TRUE(ch1.setup.polygon.slave_axis);
  EXPECT_EQ(ch1.setup.polygon.slave_view, 2U);
  EXPECT_FALSE(ch1.setup.polygon.no_wait);
  ASSERT_EQ(ch1.setup.slots.size(), 3U);
  EXPECT_FALSE(ch1.setup.slots[0].polygon);
  EXPECT_TRUE(ch1.setup.slots[2].polygon);
}

}  // namespace
}  // namespace mcnc::channel
