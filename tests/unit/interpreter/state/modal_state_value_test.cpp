// The modal state at power-on, per G-code system and dialect (spec dafeng §2.1, gsk B.1), as
// #4001.. reads it.
#include "channel/interp/state/modal_state.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::state {
namespace {

TEST(PowerOnModalState, SystemAOfTheLathe) {
  const ModalState m = ModalState::power_on(GCodeSystem::a, Dialect::dafeng, FeedMode::per_rev);
  EXPECT_EQ(m.motion, GFunction::rapid);
  EXPECT_EQ(m.plane, Plane::zx);
  EXPECT_EQ(m.feed_mode, FeedMode::per_rev);
  EXPECT_TRUE(m.metric);
  EXPECT_FALSE(m.incremental);
  EXPECT_EQ(m.codes[1], 0);
  EXPECT_EQ(m.codes[2], 97);
  EXPECT_EQ(m.codes[3], 0);  // system A has no G90/G91 group
  EXPECT_EQ(m.codes[5], 99);
  EXPECT_EQ(m.codes[11], 0);
  EXPECT_EQ(m.codes[14], 54);
  EXPECT_EQ(m.codes[16], 18);
  EXPECT_EQ(m.codes[17], 69.1);
  EXPECT_EQ(m.codes[19], 40.1);
}

TEST(PowerOnModalState, SystemBAddsG90AndTheReturnLevel) {
  const ModalState per_min = ModalState::power_on(GCodeSystem::b, Dialect::gsk, FeedMode::per_min);
  EXPECT_EQ(per_min.codes[3], 90);
  EXPECT_EQ(per_min.codes[5], 94);
  EXPECT_EQ(per_min.codes[11], 98);
  const ModalState per_rev = ModalState::power_on(GCodeSystem::b, Dialect::gsk, FeedMode::per_rev);
  EXPECT_EQ(per_rev.codes[5], 95);
}

TEST(PowerOnModalState, TheMillStartsInG17WithG49AndWithoutG96OrG22) {
  const ModalState m = ModalState::power_on(GCodeSystem::a, Dialect::fanuc_mill, FeedMode::per_min);
  EXPECT_EQ(m.plane, Plane::xy);
  EXPECT_EQ(m.codes[16], 17);
  EXPECT_EQ(m.codes[8], 49);
  EXPECT_EQ(m.codes[2], 0);
  EXPECT_EQ(m.codes[9], 0);
  EXPECT_EQ(m.codes[19], 0);
  EXPECT_EQ(m.codes[5], 98);
}

}  // namespace
}  // namespace mcnc::interp::state
