// The P..Q contour as a value: its mode, the first motion block's plane axes (G71/G72 type II)
// and the line of each captured element.
#include "channel/interp/state/contour_capture.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::state {
namespace {

TEST(ContourCapture, BeginForgetsThePreviousContoursFirstBlock) {
  ContourCapture c;
  EXPECT_FALSE(c.active());
  c.begin(ContourMode::capture);
  c.note_motion(true, true);
  EXPECT_TRUE(c.active());
  EXPECT_TRUE(c.capturing());
  EXPECT_TRUE(c.type2());
  c.begin(ContourMode::finish);
  EXPECT_TRUE(c.active());
  EXPECT_FALSE(c.capturing());
  EXPECT_EQ(c.motions, 0);
  EXPECT_FALSE(c.type2());
}

TEST(ContourCapture, OnlyTheFirstMotionBlockDecidesTheType) {
  ContourCapture c;
  c.begin(ContourMode::capture);
  c.note_motion(true, false);  // type I: the first block gives X only
  c.note_motion(true, true);
  EXPECT_EQ(c.motions, 2);
  EXPECT_FALSE(c.type2());
}

TEST(ContourCapture, NamesTheLineOfACapturedElementOnly) {
  ContourCapture c;
  c.lines = {12, 14, 15};
  EXPECT_EQ(c.line_of(1), 14);
  EXPECT_EQ(c.line_of(-1), std::nullopt);
  EXPECT_EQ(c.line_of(3), std::nullopt);
}

}  // namespace
}  // namespace mcnc::interp::state
