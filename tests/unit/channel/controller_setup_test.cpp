// A channel's axes in program order and its controller's set-up, as the twin turret's machine
// file gives them.
#include "channel/setup/controller_setup.hpp"

#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace mcnc::channel
