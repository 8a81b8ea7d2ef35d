// G98.1 / G99.1 chip breaking's split of one move (channel/interp/cycles/chip_breaking.hpp):
// where the breaks fall, the dwell or the move back, the count carried from move to move, and
// arcs split on their circle.
#include "channel/interp/cycles/chip_breaking.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mcnc::interp::cycles::test {
namespace {

AxisVector at(double x, double z) {
  AxisVector p{};
  p[0] = x;
  p[1] = z;
  return p;
}

// A line to (x, z) at 0.2 mm/rev: Q5 = 1 mm of path between breaks.
Command line_to(double x, double z, double every, double brk) {
  Command c;
  c.op = Op::linear;
  c.to = at(x, z);
  c.feed = 0.2;
  c.feed_mode = FeedMode::per_rev;
  c.chip_rev_length = 0.2;
  c.chip_every = every;
  c.chip_break = brk;
  c.exact_stop = true;
  return c;
}

TEST(ChipBreaking, DwellBreaksEveryQRevolutions) {
  std::vector<Command> out;
  double revs = 0.0;
  split_for_chip_breaking(line_to(25, -2.5, 5, 1.5), at(25, 0), 2, revs, out);
  // 2.5 mm = 12.5 revolutions: breaks after 1 mm and 2 mm, then 0.5 mm (2.5 revolutions) on.
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].op, Op::linear);
  EXPECT_NEAR(out[0].to[1], -1.0, 1e-12);
  EXPECT_FALSE(out[0].exact_stop);
  EXPECT_EQ(out[1].op, Op::dwell);
  EXPECT_TRUE(out[1].in_revs);
  EXPECT_NEAR(out[1].seconds, 1.5, 1e-12);
  EXPECT_NEAR(out[2].to[1], -2.0, 1e-12);
  EXPECT_EQ(out[3].op, Op::dwell);
  EXPECT_NEAR(out[4].to[1], -2.5, 1e-12);
  EXPECT_TRUE(out[4].exact_stop);  // the move's own end keeps its exact stop
  EXPECT_NEAR(revs, 2.5, 1e-9);
}

TEST(ChipBreaking, NegativePFeedsBackAndForward) {
  std::vector<Command> out;
  double revs = 0.0;
  split_for_chip_breaking(line_to(25, -1.5, 5, -1.5), at(25, 0), 2, revs, out);
  // Break at Z-1: back 1.5 revolutions (0.3 mm) to Z-0.7, forward to Z-1, on to Z-1.5.
  ASSERT_EQ(out.size(), 4u);
  EXPECT_NEAR(out[0].to[1], -1.0, 1e-12);
  EXPECT_NEAR(out[1].to[1], -0.7, 1e-12);
  EXPECT_NEAR(out[2].to[1], -1.0, 1e-12);
  EXPECT_NEAR(out[3].to[1], -1.5, 1e-12);
  for (const Command& c : out) {
    EXPECT_EQ(c.op, Op::linear);
    EXPECT_NEAR(c.to[0], 25, 1e-12);
  }
}

TEST(ChipBreaking, TheCountGoesOnFromMoveToMove) {
  std::vector<Command> out;
  double revs = 0.0;
  split_for_chip_breaking(line_to(25, -0.6, 5, 2), at(25, 0), 2, revs, out);
  EXPECT_EQ(out.size(), 1u);
  EXPECT_NEAR(revs, 3.0, 1e-9);
  // 0.4 mm (2 revolutions) into the next move the fifth revolution ends, 1 mm later the next.
  split_for_chip_breaking(line_to(27, -0.6, 5, 2), at(25, -0.6), 2, revs, out);
  ASSERT_EQ(out.size(), 6u);
  EXPECT_NEAR(out[1].to[0], 25.4, 1e-12);
  EXPECT_EQ(out[2].op, Op::dwell);
  EXPECT_NEAR(out[3].to[0], 26.4, 1e-12);
  EXPECT_EQ(out[4].op, Op::dwell);
  EXPECT_NEAR(out[5].to[0], 27, 1e-12);
  EXPECT_NEAR(revs, 3.0, 1e-9);
}

TEST(ChipBreaking, TheMoveBackStopsAtTheMovesStart) {
  std::vector<Command> out;
  double revs = 4.0;  // the break comes 0.2 mm into this move; P-5 would go back 1 mm
  split_for_chip_breaking(line_to(25, -0.5, 5, -5), at(25, 0), 2, revs, out);
  ASSERT_GE(out.size(), 3u);
  EXPECT_NEAR(out[0].to[1], -0.2, 1e-12);
  EXPECT_NEAR(out[1].to[1], 0.0, 1e-12);
  EXPECT_NEAR(out[2].to[1], -0.2, 1e-12);
}

TEST(ChipBreaking, ArcsSplitOnTheirCircleAndTurnBack) {
  // A quarter circle of radius 10 about X 0, Z 0 from Z 10 (X 0) to X 10 (Z 0),
  // counter-clockwise in the ZX plane (a = Z, b = X): 15.708 mm, breaks every 5 mm (25
  // revolutions of 0.2 mm).
  Command c = line_to(10, 0, 25, -5);
  c.op = Op::arc;
  c.center_axes = {1, 0};
  c.center = {0, 0};
  c.direction = ArcDirection::ccw;
  std::vector<Command> out;
  double revs = 0.0;
  split_for_chip_breaking(c, at(0, 10), 2, revs, out);
  ASSERT_EQ(out.size(), 10u);  // 3 breaks (each piece, back, forward) and the rest
  for (const Command& p : out) {
    EXPECT_EQ(p.op, Op::arc);
    EXPECT_NEAR(std::hypot(p.to[0], p.to[1]), 10.0, 1e-9);
  }
  // The first piece ends 5 mm along: 0.5 rad from Z+ towards X+.
  EXPECT_NEAR(out[0].to[1], 10 * std::cos(0.5), 1e-9);
  EXPECT_NEAR(out[0].to[0], 10 * std::sin(0.5), 1e-9);
  EXPECT_EQ(out[0].direction, ArcDirection::ccw);
  EXPECT_EQ(out[1].direction, ArcDirection::cw);  // back: 1 mm
  EXPECT_NEAR(out[1].to[1], 10 * std::cos(0.4), 1e-9);
  EXPECT_EQ(out[2].direction, ArcDirection::ccw);
  EXPECT_NEAR(out.back().to[0], 10, 1e-12);
  EXPECT_NEAR(out.back().to[1], 0, 1e-12);
}

TEST(ChipBreaking, AMoveWithoutChipBreakingPassesAsItIs) {
  Command c = line_to(25, -2.5, 5, 1.5);
  c.chip_rev_length = 0.0;
  std::vector<Command> out;
  double revs = 1.0;
  split_for_chip_breaking(c, at(25, 0), 2, revs, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(revs, 1.0, 1e-12);
}

}  // namespace
}  // namespace mcnc::interp::cycles::test
