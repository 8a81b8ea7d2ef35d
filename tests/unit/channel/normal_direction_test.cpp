// G41.1 on the cutter compensated path as a channel runs it (spec dafeng L3880, the mill's
// G41 D: no T code, which would need the PLC node), through the read-ahead as in the channel
// process: while X and Y cut, the setpoint of C points the tool at the travel direction + 90
// degrees, along the offset lines and round the corner arcs; it turns alone where the direction
// jumps; G40.1 leaves it where it stands. The axis nodes follow the setpoints one cycle late, as
// in lockstep.
#include "channel/interp/dialect.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 4;  // X, Y, Z, C
constexpr std::size_t kX = 0;
constexpr std::size_t kY = 1;
constexpr std::size_t kC = 3;

interp::InterpreterConfig mill_channel() {
  interp::InterpreterConfig c;
  interp::select_dialect(c, interp::Dialect::fanuc_mill);
  c.channel = 1;
  c.axes.push_back(interp::AxisConfig{'C', false, true});
  c.normal_axis = 'C';
  c.normal_feed = 36000.0;
  c.tool_geometry[1].radius = 1.0;
  return c;
}

class NormalRig : public LockstepRig {
 public:
  explicit NormalRig(const motion::MotionConfig& axes = alike_axes(kAxes, kDt))
      : LockstepRig(mill_channel(), axes, ChannelSetup{kAxes, {0.001, 0.001, 0.001, 0.001}, kDt},
                    kAxes, true) {}

  struct Sample {
    double x;
    double y;
    double c;
    int line;
  };
  std::vector<Sample> samples;

 protected:
  void record(const CycleOutput& out) override {
    samples.push_back(
        {out.setpoints[kX].pos, out.setpoints[kY].pos, out.setpoints[kC].pos, out.line});
  }
};

// The golden gsk-B1-L15-17-mill-g411-cutter-compensation's square, G40.1 before the G40 move
// (which the look-ahead then still holds the last side of the square for), run to its end.
void run_the_square(NormalRig& rig) {
  rig.load(
      "G00 X0 Y-20 Z0\nG41.1\nG41 D1 G01 X0 Y0 F1200\nY40\nX40\nY0\nX0\nG40.1\n"
      "G40 G00 X0 Y-20\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until(
      [](const CycleOutput& o) { return o.program_end || o.state == ChannelState::alarm; },
      100000));
  ASSERT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(ChannelNormalDirection, AxisPointsNormalToTheOffsetPathWhileCutting) {
  NormalRig rig;
  ASSERT_NO_FATAL_FAILURE(run_the_square(rig));
  int cutting = 0;
  double worst = 0.0;
  for (std::size_t i = 1; i < rig.samples.size(); ++i) {
    const auto& p = rig.samples[i - 1];
    const auto& q = rig.samples[i];
    const double dx = q.x - p.x;
    const double dy = q.y - p.y;
    // The cutting moves of lines 3-7 (the rapids before and after leave C alone).
    if (q.line < 3 || q.line > 7 || std::hypot(dx, dy) < 1e-6) {
      continue;
    }
    const double want = std::atan2(dy, dx) * 180.0 / M_PI + 90.0;
    worst = std::max(worst, std::fabs(std::remainder(q.c - want, 360.0)));
    ++cutting;
  }
  EXPECT_GT(cutting, 5000);  // 160 mm and more at 20 mm/s
  // Within a cycle's turn on the corner arcs (C at its limit of 100 degrees/s there: 0.1
  // degrees a cycle, the planner's path speed shared between C and the circle).
  EXPECT_LT(worst, 0.1);
  // G40.1: the G40 rapid leaves C at the left normal of the last side (along -X): 270.
  EXPECT_NEAR(std::remainder(rig.samples.back().c - 270.0, 360.0), 0.0, 1e-9);
  EXPECT_NEAR(rig.samples.back().y, -20.0, 1e-9);
}

// FANUC's feed under normal direction control is the tool's along the path in the plane: the
// corner arcs of radius 1 at F1200 take 1.57 mm / 20 mm/s = 79 ms each, C turning its 90
// degrees in that time, not the 4.5 s that counting C's degrees as millimetres of path took
// (decision 139). The axes' limits are set high enough here not to slow the turn: the planner
// bounds an arc's acceleration along its path by the smallest limit of its axes, X's and Y's
// too, though they take a sixtieth of the path.
TEST(ChannelNormalDirection, TheFeedIsTheToolsAlongTheCornerArcsInThePlane) {
  motion::MotionConfig axes = alike_axes(kAxes, kDt);
  for (std::size_t i = 0; i < kAxes; ++i) {
    axes.axes[i] = motion::AxisDynamics{3000.0, 200000.0, 1.0e8};
  }
  NormalRig rig(axes);
  ASSERT_NO_FATAL_FAILURE(run_the_square(rig));
  // The corner arcs: cycles of the cutting lines in which X or Y and C move together.
  std::vector<int> arc_cycles;
  std::vector<double> arc_speeds;  // mm/s in the plane
  bool in_arc = false;
  for (std::size_t i = 1; i < rig.samples.size(); ++i) {
    const auto& p = rig.samples[i - 1];
    const auto& q = rig.samples[i];
    const double in_plane = std::hypot(q.x - p.x, q.y - p.y);
    // C turns by 90 degrees on the square's three outside corners, in steps of about a degree.
    const bool arc = q.line >= 3 && q.line <= 7 && in_plane > 1e-6 && std::fabs(q.c - p.c) > 0.01;
    if (arc && !in_arc) {
      arc_cycles.push_back(0);
    }
    if (arc) {
      ++arc_cycles.back();
      arc_speeds.push_back(in_plane / kDt);
    }
    in_arc = arc;
  }
  ASSERT_EQ(arc_cycles.size(), 3U) << ::testing::PrintToString(arc_cycles);
  for (const int cycles : arc_cycles) {
    EXPECT_GE(cycles, 75);
    EXPECT_LE(cycles, 100);  // 79 ms at F1200, and the few cycles it takes to reach it
  }
  std::sort(arc_speeds.begin(), arc_speeds.end());
  EXPECT_NEAR(arc_speeds[arc_speeds.size() / 2], 20.0, 0.2);  // the median: F1200 in the plane
}

}  // namespace
}  // namespace mcnc::channel
