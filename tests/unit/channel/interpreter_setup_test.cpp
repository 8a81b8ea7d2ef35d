// A channel's interpreter parameters from the machine file: its spindle count, its power-on
// feed mode (param 2201.3, `feed_mode` of the channel) and its dialect.
#include "channel/setup/interpreter_setup.hpp"
#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::channel {
namespace {

config::MachineConfig machine(const std::string& lathe_feed_mode) {
  return config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 4000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
channels:
  - {name: LATHE, axes: [X1, Z1], spindles: [S1])" +
                                    lathe_feed_mode + R"(}
  - {name: LOADER, axes: [X2]}
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: S1, type: spindle, bus: b, node_id: 3}
  - {name: X2, address: X, bus: b, node_id: 4}
)");
}

TEST(InterpreterSetup, PowerOnFeedModeIsTheChannels) {
  const config::MachineConfig g99 = machine(", feed_mode: per_rev");
  EXPECT_EQ(interpreter_config_for(g99, g99.channels[0]).power_on_feed_mode,
            interp::FeedMode::per_rev);
  EXPECT_EQ(interpreter_config_for(g99, g99.channels[1]).power_on_feed_mode,
            interp::FeedMode::per_min);
  const config::MachineConfig g98 = machine("");
  EXPECT_EQ(interpreter_config_for(g98, g98.channels[0]).power_on_feed_mode,
            interp::FeedMode::per_min);
}

TEST(InterpreterSetup, SpindlesAreCounted) {
  const config::MachineConfig m = machine("");
  EXPECT_EQ(interpreter_config_for(m, m.channels[0]).spindles, 1);
  EXPECT_EQ(interpreter_config_for(m, m.channels[1]).spindles, 0);  // known: none
}

// `dialect: fanuc-mill` makes the channel a mill (system B's spelling, FANUC macro ranges) on
// the axes the machine file gives it; the other channels stay Dafeng lathes.
TEST(InterpreterSetup, DialectIsTheChannels) {
  const config::MachineConfig m = machine(", dialect: fanuc-mill");
  const interp::InterpreterConfig mill = interpreter_config_for(m, m.channels[0]);
  EXPECT_EQ(mill.dialect, interp::Dialect::fanuc_mill);
  EXPECT_EQ(mill.system, interp::GCodeSystem::b);
  EXPECT_EQ(mill.macro.local_last, 33);
  ASSERT_EQ(mill.axes.size(), 2u);  // the channel's X1 and Z1, not the dialect's X Y Z
  EXPECT_EQ(mill.axes[1].name, 'Z');
  EXPECT_EQ(interpreter_config_for(m, m.channels[1]).dialect, interp::Dialect::dafeng);
}

// G160 without P / Q and G31 P98/P99 in `mcnc run`: the channel's `torque_skip` is params
// 5515/5516, an axis's `skip_load` param 5511.
TEST(InterpreterSetup, TorqueSkipDefaultsAndLoadRatiosAreTheMachineFiles) {
  const config::MachineConfig m = config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 4000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
channels:
  - {name: LATHE, axes: [X1, Z1], torque_skip: {limit: 60, deviation: 1.5}}
  - {name: LOADER, axes: [X2]}
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2, torque_skip: true, skip_load: 35,
     torque_mode: true, torque_mode_speed: 250}
  - {name: X2, address: X, bus: b, node_id: 4}
)");
  const interp::InterpreterConfig lathe = interpreter_config_for(m, m.channels[0]);
  EXPECT_DOUBLE_EQ(lathe.torque_skip_percent, 60.0);
  EXPECT_DOUBLE_EQ(lathe.torque_skip_deviation, 1.5);
  ASSERT_EQ(lathe.axes.size(), 2u);
  EXPECT_DOUBLE_EQ(lathe.axes[1].skip_load, 35.0);
  EXPECT_DOUBLE_EQ(lathe.axes[0].skip_load, 0.0);
  // Param 5521: G10 L14 P10's motor speed where no P11 set one.
  EXPECT_DOUBLE_EQ(lathe.axes[1].torque_mode_speed, 250.0);
  EXPECT_DOUBLE_EQ(lathe.axes[0].torque_mode_speed, 0.0);
  const interp::InterpreterConfig loader = interpreter_config_for(m, m.channels[1]);
  EXPECT_DOUBLE_EQ(loader.torque_skip_percent, 0.0);
  EXPECT_DOUBLE_EQ(loader.torque_skip_deviation, 0.0);
}

// G12.1 and G07.1 in `mcnc run`: the channel's `polar` and `cylindrical_parallel` are its
// interpreter's parameters 5530/5531 and 0016.
TEST(InterpreterSetup, PolarAndCylindricalAxesAreTheChannels) {
  const config::MachineConfig m = config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 4000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
channels:
  - {name: LATHE, axes: [X1, Z1, C1], polar: {linear: X, rotary: C, tolerance: 0.0005},
     cylindrical_parallel: Z}
  - {name: LOADER, axes: [X2]}
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: C1, address: C, type: rotary, bus: b, node_id: 3}
  - {name: X2, address: X, bus: b, node_id: 4}
)");
  const interp::InterpreterConfig lathe = interpreter_config_for(m, m.channels[0]);
  EXPECT_EQ(lathe.polar_linear, 'X');
  EXPECT_EQ(lathe.polar_rotary, 'C');
  EXPECT_DOUBLE_EQ(lathe.polar_tolerance, 0.0005);
  EXPECT_EQ(lathe.cylindrical_parallel, 'Z');
  const interp::InterpreterConfig loader = interpreter_config_for(m, m.channels[1]);
  EXPECT_EQ(loader.polar_linear, 0);
  EXPECT_EQ(loader.cylindrical_parallel, 'Y');
}

}  // namespace
}  // namespace mcnc::channel
