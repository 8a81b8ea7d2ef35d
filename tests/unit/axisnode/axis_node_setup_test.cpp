// An axis node's roles and drive start-up as the twin turret's machine file gives them.
#include "axisnode/setup/axis_node_setup.hpp"

#include <gtest/gtest.h>

using namespace mcnc;

namespace {

config::MachineConfig twin_turret() {
  return config::load_machine_file(std::string(MCNC_SOURCE_DIR) +
                                   "/launch/machines/twin_turret.yaml");
}

}  // namespace

TEST(AxisNodeSetup, AnExchangeableAxisMayBeOwnedByItsHomeChannelAndTheOneThatMayAcquireIt) {
  const config::MachineConfig m = twin_turret();
  const config::AxisConfig& a1 = *m.find_axis("A1");
  const axisnode::AxisNodeRoles r = axisnode::roles_of(m, a1, axisnode::drive_startup_of(a1));
  EXPECT_EQ(r.axis, static_cast<std::uint32_t>(a1.id));
  EXPECT_EQ(r.home, static_cast<std::uint32_t>(m.find_channel("CH1")->id));
  ASSERT_EQ(r.candidates.size(), 2U);
  EXPECT_EQ(r.candidates[0], r.home);
  EXPECT_EQ(r.candidates[1], static_cast<std::uint32_t>(m.find_channel("CH2")->id));
  EXPECT_TRUE(r.exchangeable);
  EXPECT_EQ(r.sync_master, 0U);
  EXPECT_DOUBLE_EQ(r.in_position, 0.001);
  EXPECT_EQ(axisnode::other_nodes_on_bus(m, a1), (std::vector<std::uint8_t>{1, 2, 4}));
}

TEST(AxisNodeSetup, TheSubSpindleFollowsTheMainSpindleInTheChannelThatCouplesIt) {
  const config::MachineConfig m = twin_turret();
  const config::AxisConfig& s2 = *m.find_axis("S2");
  const canopen::NodeStartupConfig startup = axisnode::drive_startup_of(s2);
  const axisnode::AxisNodeRoles r = axisnode::roles_of(m, s2, startup);
  EXPECT_EQ(r.sync_group, 1U);
  EXPECT_EQ(r.sync_master, static_cast<std::uint32_t>(m.find_axis("S1")->id));
  EXPECT_EQ(r.sync_channel, static_cast<std::uint32_t>(m.find_channel("CH1")->id));
  EXPECT_FALSE(r.exchangeable);
  EXPECT_TRUE(r.controller.spindle);
  EXPECT_EQ(startup.mode, axisnode::kModeCsv);
  // Heartbeat consumer time: 1.5 producer times, in cycles.
  EXPECT_EQ(r.controller.heartbeat_cycles,
            startup.heartbeat_ms == 0
                ? 0
                : static_cast<int>(1.5 * startup.heartbeat_ms * 1000 / m.cycle_us));
}

TEST(AxisNodeSetup, TheSpindlesLoadIsMappedIntoItsSecondTpdo) {
  const config::MachineConfig m = twin_turret();
  const canopen::NodeStartupConfig s1 = axisnode::drive_startup_of(*m.find_axis("S1"));
  const canopen::NodeStartupConfig s2 = axisnode::drive_startup_of(*m.find_axis("S2"));
  ASSERT_EQ(s1.pdos.tpdo2.count, s2.pdos.tpdo2.count + 1);
  EXPECT_EQ(s1.pdos.tpdo2.objects[s1.pdos.tpdo2.count - 1].index, 0x6077);
  EXPECT_EQ(s1.pdos.tpdo2.objects[s1.pdos.tpdo2.count - 1].bits, 16);
}

// polygon_lathe.yaml (params 5310/5311): T1's node holds the polygon coupling to S1, which CH1
// commands; S1's node follows nobody.
TEST(AxisNodeSetup, ThePolygonAxisFollowsItsMasterSpindleForItsChannel) {
  const config::MachineConfig m = config::load_machine_file(std::string(MCNC_SOURCE_DIR) +
                                                            "/launch/machines/polygon_lathe.yaml");
  const config::AxisConfig& t1 = *m.find_axis("T1");
  const axisnode::AxisNodeRoles r = axisnode::roles_of(m, t1, axisnode::drive_startup_of(t1));
  EXPECT_TRUE(r.polygon);
  EXPECT_EQ(r.sync_group, 0U);
  EXPECT_EQ(r.sync_master, static_cast<std::uint32_t>(m.find_axis("S1")->id));
  EXPECT_EQ(r.sync_channel, static_cast<std::uint32_t>(m.find_channel("CH1")->id));
  EXPECT_DOUBLE_EQ(r.spindle_coupling.max_acceleration, 7200.0);  // its catch-up and stop
  const config::AxisConfig& s1 = *m.find_axis("S1");
  const axisnode::AxisNodeRoles master = axisnode::roles_of(m, s1, axisnode::drive_startup_of(s1));
  EXPECT_FALSE(master.polygon);
  EXPECT_EQ(master.sync_master, 0U);
}

// polygon_servo_lathe.yaml (param 5311 naming a servo axis): C1's node holds the polygon
// coupling to S1 and stays a servo axis, in CSP.
TEST(AxisNodeSetup, AServoPolygonAxisFollowsItsMasterSpindleAsAServoAxis) {
  const config::MachineConfig m = config::load_machine_file(
      std::string(MCNC_SOURCE_DIR) + "/launch/machines/polygon_servo_lathe.yaml");
  const config::AxisConfig& c1 = *m.find_axis("C1");
  const axisnode::AxisNodeRoles r = axisnode::roles_of(m, c1, axisnode::drive_startup_of(c1));
  EXPECT_TRUE(r.polygon);
  EXPECT_FALSE(r.controller.spindle);
  EXPECT_EQ(r.sync_master, static_cast<std::uint32_t>(m.find_axis("S1")->id));
  EXPECT_EQ(r.sync_channel, static_cast<std::uint32_t>(m.find_channel("CH1")->id));
  EXPECT_DOUBLE_EQ(r.spindle_coupling.max_acceleration, 7200.0);
}

// G10 L14 P10-P12: an axis with torque_mode gets the CST objects after the torque limit's, and
// its node switches the drive's mode as its owner asks.
TEST(AxisNodeSetup, ATorqueModeAxisMapsTheModeTheTargetTorqueAndTheSpeedLimit) {
  config::MachineConfig m = twin_turret();
  config::AxisConfig z = *m.find_axis("Z1");
  z.torque_skip = true;
  z.torque_mode = true;
  const canopen::NodeStartupConfig startup = axisnode::drive_startup_of(z);
  const canopen::PdoMapping& rpdo2 = startup.pdos.rpdo2;
  ASSERT_EQ(rpdo2.count, 3U);
  EXPECT_EQ(rpdo2.objects[0].index, 0x6072);
  EXPECT_EQ(rpdo2.objects[1].index, 0x6071);
  EXPECT_EQ(rpdo2.objects[2].index, 0x6080);
  EXPECT_EQ(startup.pdos.rpdo1.objects[startup.pdos.rpdo1.count - 1].index, 0x6060);
  EXPECT_EQ(startup.pdos.tpdo1.objects[startup.pdos.tpdo1.count - 1].index, 0x6061);
  EXPECT_TRUE(axisnode::roles_of(m, z, startup).controller.torque_mode);
  EXPECT_FALSE(
      axisnode::roles_of(m, *m.find_axis("Z1"), axisnode::drive_startup_of(*m.find_axis("Z1")))
          .controller.torque_mode);
}
