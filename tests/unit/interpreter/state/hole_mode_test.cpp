// The modal hole cycle as a value: active while a group 10 code is in force, reset by a new
// value.
#include "channel/interp/state/hole_mode.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::state {
namespace {

TEST(HoleMode, IsInactiveUntilACycleCodeIsSet) {
  HoleMode h;
  EXPECT_FALSE(h.active());
  EXPECT_EQ(h.retract, -1.0);  // the parameter's back-off until gsk R gives one
  EXPECT_EQ(h.peck_type, -1);
  EXPECT_EQ(h.repeat, 1);
  h.function = GFunction::drill_face;
  EXPECT_TRUE(h.active());
}

TEST(HoleMode, ANewValueEndsTheCycleAndForgetsItsAmounts) {
  HoleMode h;
  h.function = GFunction::drill_face;
  h.has_r = true;
  h.r_level = 5.0;
  h.peck = 2.0;
  h = HoleMode{};
  EXPECT_FALSE(h.active());
  EXPECT_FALSE(h.has_r);
  EXPECT_EQ(h.peck, 0.0);
}

}  // namespace
}  // namespace mcnc::interp::state
