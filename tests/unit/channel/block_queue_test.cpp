// The blocks the planner took, in program order: when each one's start and end are due.
#include "channel/control/block_queue.hpp"

#include <gtest/gtest.h>

namespace mcnc::channel {
namespace {

interp::Command move(std::uint64_t n, interp::Op op, double x, bool exact_stop = false) {
  interp::Command c;
  c.op = op;
  c.n = n;
  c.line = static_cast<int>(n) * 10;
  c.to[0] = x;
  c.exact_stop = exact_stop;
  return c;
}

motion::MotionOutput at(std::uint64_t block, std::uint64_t completed, double velocity) {
  motion::MotionOutput m;
  m.block = block;
  m.completed_block = completed;
  m.path_velocity = velocity;
  return m;
}

TEST(BlockQueue, ABlockStartsWhenThePlannerIsInItAndEndsWhenThePathPassedItsEnd) {
  BlockQueue q(4);
  const interp::AxisVector origin{};
  q.push(move(1, interp::Op::linear, 10.0), origin);
  q.push(move(2, interp::Op::linear, 20.0), interp::AxisVector{10.0});
  EXPECT_EQ(q.due(at(0, 0, 0.0), false), BlockQueue::Due::none);  // not there yet
  ASSERT_EQ(q.due(at(1, 0, 5.0), false), BlockQueue::Due::start);
  q.started();
  EXPECT_EQ(q.due(at(1, 0, 5.0), false), BlockQueue::Due::none);  // under way
  ASSERT_EQ(q.due(at(2, 1, 5.0), false), BlockQueue::Due::end);   // passed, blended
  EXPECT_EQ(q.front().line, 10);
  q.ended();
  ASSERT_EQ(q.due(at(2, 1, 5.0), false), BlockQueue::Due::start);
  q.started();
  // The path stopped at its end: it ends once the axes are in position there.
  EXPECT_EQ(q.due(at(2, 2, 0.0), false), BlockQueue::Due::end_if_in_position);
  q.ended();
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.due(at(2, 2, 0.0), true), BlockQueue::Due::none);
}

TEST(BlockQueue, ExactStopsRapidsAndDwellsWaitForPositionAndStillBlocksPassAtOnce) {
  BlockQueue q(4);
  const interp::AxisVector origin{};
  q.push(move(1, interp::Op::rapid, 5.0), origin);
  q.started();
  EXPECT_EQ(q.due(at(2, 1, 3.0), false), BlockQueue::Due::end_if_in_position);
  q.ended();
  q.push(move(2, interp::Op::linear, 0.0), origin);  // to where the axes are
  EXPECT_EQ(q.due(at(0, 0, 0.0), false), BlockQueue::Due::start);
  q.started();
  EXPECT_EQ(q.due(at(0, 0, 0.0), false), BlockQueue::Due::end);
  q.ended();
  interp::Command m3 = move(3, interp::Op::spindle, 99.0);
  q.push(m3, interp::AxisVector{7.0});
  EXPECT_DOUBLE_EQ(q.front().to[0], 7.0);  // a spindle command ends where it starts
  EXPECT_EQ(q.due(at(0, 0, 0.0), false), BlockQueue::Due::start);
}

TEST(BlockQueue, TheRingHoldsItsCapacityAndFindsTheFirstBlockMovingAnAxis) {
  BlockQueue q(2);
  const interp::AxisVector origin{};
  q.push(move(1, interp::Op::linear, 0.0), origin);
  q.push(move(2, interp::Op::linear, 4.0), origin);
  EXPECT_TRUE(q.full());
  q.push(move(3, interp::Op::linear, 8.0), origin);  // no room: ignored
  EXPECT_EQ(q.first_moving(0, 0.0), 20);
  EXPECT_EQ(q.first_moving(1, 0.0), 0);
  q.end_newest_at(interp::AxisVector{});  // a skip stopped the newest block at 0
  EXPECT_EQ(q.first_moving(0, 0.0), 0);
  q.started();
  q.ended();
  q.push(move(3, interp::Op::linear, 8.0), origin);  // wraps around
  EXPECT_EQ(q.first_moving(0, 0.0), 30);
  q.clear();
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace mcnc::channel
