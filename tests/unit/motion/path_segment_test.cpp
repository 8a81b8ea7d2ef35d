// PathSegment's lengths: the whole path of the channel's axes, and the path without one of them
// (the feed of a move that does not count that axis, decision 139).
#include "channel/motion/path_segment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mcnc::motion {
namespace {

TEST(PathSegment, ALineWithoutAnAxisIsTheLineOfTheOthers) {
  const AxisVector from{1.0, 2.0, 0.0};
  const AxisVector to{4.0, 6.0, 12.0};
  const PathSegment line = PathSegment::line(from, to, 3);
  EXPECT_NEAR(line.length(), 13.0, 1e-12);
  EXPECT_NEAR(line.length_without(2), 5.0, 1e-12);
  EXPECT_NEAR(line.length_without(0), std::hypot(4.0, 12.0), 1e-12);
  EXPECT_NEAR(line.length_without(3), 13.0, 1e-12) << "an axis the segment does not have";
}

TEST(PathSegment, AHelicalArcWithoutItsThirdAxisIsItsCircle) {
  // A quarter circle of radius 2 about the origin in axes 0 and 1, axis 2 turning 90 (degrees
  // of a normal direction axis, or millimetres of a helix) along it.
  const AxisVector from{2.0, 0.0, 0.0};
  const AxisVector to{0.0, 2.0, 90.0};
  const PathSegment arc = PathSegment::arc(from, to, 3, 0, 1, 0.0, 0.0, true, 0);
  const double circle = 2.0 * std::numbers::pi / 2.0;
  EXPECT_NEAR(arc.length(), std::hypot(circle, 90.0), 1e-9);
  EXPECT_NEAR(arc.length_without(2), circle, 1e-9);
  // An axis of the circle is not taken off it.
  EXPECT_NEAR(arc.length_without(0), arc.length(), 1e-12);
}

}  // namespace
}  // namespace mcnc::motion
