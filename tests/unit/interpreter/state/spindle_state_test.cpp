// The spindles as a value: all stopped at first, G96 on the reference spindle only.
#include "channel/interp/state/spindle_state.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::state {
namespace {

TEST(SpindleState, StartsWithEverySpindleStoppedInSpeedControl) {
  const SpindleState s;
  for (std::size_t k = 0; k < SpindleState::kSlots; ++k) {
    EXPECT_EQ(s.direction[k], SpindleDirection::stop) << k;
    EXPECT_FALSE(s.position_control[k]) << k;
    EXPECT_EQ(s.rpm[k], 0.0) << k;
  }
  EXPECT_EQ(s.reference, 1);
  EXPECT_FALSE(s.css);
}

TEST(SpindleState, TheReferenceSpindlesSpeedAndTurning) {
  SpindleState s;
  s.rpm[1] = 800.0;
  s.rpm[2] = 1200.0;
  s.direction[2] = SpindleDirection::ccw;
  EXPECT_EQ(s.reference_rpm(), 800.0);
  EXPECT_EQ(s.reference_direction(), SpindleDirection::stop);
  s.reference = 2;  // SP2
  EXPECT_EQ(s.reference_rpm(), 1200.0);
  EXPECT_EQ(s.reference_direction(), SpindleDirection::ccw);
}

TEST(SpindleState, SurfaceSpeedActsOnTheReferenceSpindleOnly) {
  SpindleState s;
  EXPECT_FALSE(s.surface_speed_on(1));  // G97
  s.css = true;
  EXPECT_TRUE(s.surface_speed_on(1));
  EXPECT_FALSE(s.surface_speed_on(2));
  s.reference = 2;
  EXPECT_FALSE(s.surface_speed_on(1));
  EXPECT_TRUE(s.surface_speed_on(2));
}

}  // namespace
}  // namespace mcnc::interp::state
