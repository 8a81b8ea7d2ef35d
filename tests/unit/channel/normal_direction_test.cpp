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
  NormalRig()
      : LockstepRig(mill_channel(), alike_axes(kAxes, kDt),
                    ChannelSetup{kAxes, {0.001, 0.001, 0.001, 0.001}, kDt}, kAxes, true) {}

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

TEST(ChannelNormalDirection, AxisPointsNormalToTheOffsetPathWhileCutting) {
  NormalRig rig;
  // The golden gsk-B1-L15-17-mill-g411-cutter-compensation's square, G40.1 before the G40 move
  // (which the look-ahead then still holds the last side of the square for).
  rig.load(
      "G00 X0 Y-20 Z0\nG41.1\nG41 D1 G01 X0 Y0 F1200\nY40\nX40\nY0\nX0\nG40.1\n"
      "G40 G00 X0 Y-20\nM30\n");
  // The planner counts C's degrees in the corner arcs' length (90 degrees at F1200: 4.5 s each).
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until(
      [](const CycleOutput& o) { return o.program_end || o.state == ChannelState::alarm; },
      100000));
  ASSERT_TRUE(rig.alarms.empty()) << rig.alarm_text;
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
  // Within a cycle's turn on the corner arcs (C at F1200 there: 0.02 degrees a cycle).
  EXPECT_LT(worst, 0.1);
  // G40.1: the G40 rapid leaves C at the left normal of the last side (along -X): 270.
  EXPECT_NEAR(std::remainder(rig.samples.back().c - 270.0, 360.0), 0.0, 1e-9);
  EXPECT_NEAR(rig.samples.back().y, -20.0, 1e-9);
}

}  // namespace
}  // namespace mcnc::channel
