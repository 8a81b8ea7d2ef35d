#include "common/config/cyclic_routes.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::config {
namespace {

const std::string kSourceDir = MCNC_SOURCE_DIR;

// The twin turret has every kind of route: CH1 programs X1 Z1 A1 and S1's C axis C1, CH2 may take
// A1 (G141), S2 follows S1 by G114.1 from CH1, CH3 has two axes of its own.
class TwinTurretRoutes : public ::testing::Test {
 protected:
  const MachineConfig machine = load_machine_file(kSourceDir + "/launch/machines/twin_turret.yaml");
  const ChannelConfig& ch(const char* name) { return *machine.find_channel(name); }
};

TEST_F(TwinTurretRoutes, AChannelReadsTheNodesOfItsAxesSpindlesAndSyncSlavesOnce) {
  // C1 travels on S1's node: S1 is named once.
  EXPECT_EQ(node_keys(fed_axes(machine, ch("CH1"))),
            (std::vector<std::string>{"X1", "Z1", "A1", "S1", "S2"}));
  EXPECT_EQ(node_keys(fed_axes(machine, ch("CH2"))),
            (std::vector<std::string>{"X2", "Z2", "A1", "S2"}));
  EXPECT_EQ(node_keys(fed_axes(machine, ch("CH3"))), (std::vector<std::string>{"X3", "Z3"}));
}

TEST_F(TwinTurretRoutes, FedAxesKeepTheChannelsSlotOrder) {
  std::vector<std::string> names;
  for (const AxisConfig* a : fed_axes(machine, ch("CH1"))) {
    names.push_back(a->name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"X1", "Z1", "A1", "C1", "S1", "S2"}));
}

TEST_F(TwinTurretRoutes, ACAxisTravelsInItsSpindlesPartition) {
  EXPECT_EQ(node_key(*machine.find_axis("C1")), "S1");
  EXPECT_EQ(node_key(*machine.find_axis("X1")), "X1");
}

TEST_F(TwinTurretRoutes, EachNodeCountsTheChannelsThatReadIt) {
  EXPECT_EQ(channels_fed_by(machine, "A1"), 2U);  // its home channel and the one that may take it
  EXPECT_EQ(channels_fed_by(machine, "S2"), 2U);  // its channel and its G114.1 master's
  EXPECT_EQ(channels_fed_by(machine, "S1"), 1U);
  EXPECT_EQ(channels_fed_by(machine, "X3"), 1U);
  EXPECT_EQ(channels_fed_by(machine, "nobody"), 0U);
}

TEST_F(TwinTurretRoutes, AChannelHearsEveryOtherChannelAndThePlcEveryChannel) {
  EXPECT_EQ(other_channels(machine, ch("CH2")), (std::vector<std::string>{"CH1", "CH3"}));
  EXPECT_EQ(channel_names(machine), (std::vector<std::string>{"CH1", "CH2", "CH3"}));
}

}  // namespace
}  // namespace mcnc::config
