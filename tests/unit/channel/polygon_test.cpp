// G51.2 / G50.2 as a channel runs them (spec dafeng §2.6.6): the request goes to the polygon
// axis's node, the cutting block after G51.2 waits until the axis is in phase, G50.2 waits until
// it stands free, a reset lets it go, and a refused G51.2 sends nothing and moves nothing.
// Channel 1 programs X and Z and has the spindles S1 (axis 3, the master) and T1 (axis 4, the
// polygon axis, at most 3000 rpm).
#include "channel_rig.hpp"
#include "coupling_node_rig.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;
constexpr std::size_t kMaster = kAxes;     // S1's feedback
constexpr std::size_t kSlave = kAxes + 1;  // T1's
constexpr std::uint64_t kCatchUp = 50;     // cycles the simulated node takes to lock

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 2;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  return c;
}

ChannelSetup xz_setup(bool no_wait) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.spindle_count = 2;
  s.polygon = coordination::PolygonSetup{3, kMaster, kSlave, 3000.0 * 6.0};
  s.polygon.no_wait = no_wait;
  return s;
}

// The polygon axis's node (CouplingNodeRig): it locks kCatchUp cycles after G51.2 and stands
// free kCatchUp cycles after G50.2.
class PolygonRig : public ChannelRig, public CouplingNodeRig<PolygonOut> {
 public:
  explicit PolygonRig(bool no_wait = false)
      : ChannelRig(xz_channel(), alike_axes(kAxes, kDt), xz_setup(no_wait)),
        CouplingNodeRig<PolygonOut>(3, kCatchUp) {
    feedback_ = standing_feedback(kAxes + 2, 1);
    feedback_[kMaster].vel = 3000.0;  // S1 turns at 500 rpm
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    (void)answer(cycle_, feedback_[kSlave]);
    if (out.polygon_sync_due) {
      record(cycle_, out.polygon_sync);
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (out.setpoints[a].valid) {
        if (feedback_[a].act != out.setpoints[a].pos && first_move == 0) {
          first_move = cycle_;
        }
        if (feedback_[a].act != out.setpoints[a].pos && first_move_of[a] == 0) {
          first_move_of[a] = cycle_;
        }
        feedback_[a].cmd = feedback_[a].act = out.setpoints[a].pos;
      }
    }
    ++cycle_;
    return out;
  }

  std::uint64_t first_move = 0;
  std::array<std::uint64_t, kAxes> first_move_of{};  // X's, Z's
  std::uint64_t cycle_ = 0;
  std::vector<AxisFeedbackView> feedback_;
};

TEST(PolygonChannel, TheCutAfterG512WaitsForThePhaseAndG502ForTheStop) {
  PolygonRig rig;
  rig.load("G51.2 P1 Q2 R30\nG01 X10 F3000\nG50.2\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_TRUE(rig.sent[0].on);
  EXPECT_EQ(rig.sent[0].p, 1);
  EXPECT_EQ(rig.sent[0].q, 2);
  EXPECT_EQ(rig.sent[0].r, 30.0);
  EXPECT_FALSE(rig.sent[1].on);
  EXPECT_TRUE(rig.sent[1].wait);
  ASSERT_GT(rig.locked_at, 0U);
  EXPECT_GT(rig.first_move, rig.locked_at);         // X moved only once T1 was in phase
  EXPECT_EQ(rig.feedback_[kSlave].coupled_to, 0U);  // the program ended after T1 stood free
  EXPECT_EQ(rig.feedback_[0].cmd, 5.0);
}

TEST(PolygonChannel, AResetLetsThePolygonAxisGo) {
  PolygonRig rig;
  rig.load("G51.2 P1 Q2\nG04 X10\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.locked_at != 0; }));
  const std::uint64_t reset_at = rig.cycle_;
  rig.ctl().request_reset();
  // In the dwell nothing moves: the reset ends in its first cycle.
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.sent.size() == 2; }, 10));
  EXPECT_EQ(rig.sent_at[1], reset_at);
  EXPECT_NE(rig.ctl().state(), ChannelState::running);
  EXPECT_FALSE(rig.sent[1].on);
  EXPECT_FALSE(rig.sent[1].wait);
  // Once: the next cycles send nothing more.
  for (int i = 0; i < 100; ++i) {
    (void)rig.step();
  }
  EXPECT_EQ(rig.sent.size(), 2U);
}

TEST(PolygonChannel, ARefusedG512SendsNothingAndMovesNothing) {
  PolygonRig rig;
  rig.load("G00 X4\nG51.2 P1 Q7\nG01 X10 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, std::vector<int>{coordination::kAlarmPolygon});
  EXPECT_EQ(rig.alarm_lines, std::vector<int>{2});
  EXPECT_EQ(rig.alarm_text,
            "G51.2 P1 Q7: the polygon axis would turn at 3500 rpm, above its 3000 rpm (parameter "
            "5312: polygon max_rpm)");
  EXPECT_TRUE(rig.sent.empty());
  for (int i = 0; i < 200; ++i) {
    (void)rig.step();
  }
  EXPECT_EQ(rig.feedback_[0].cmd, 2.0);  // X stands where G00 X4 put it (radius)
}

// Param 5300.5 = 1 (spec dafeng L2917-2919): G51.2 does not wait for the polygon axis to lock,
// the rapid after it runs at once, and the cutting block after that waits for the lock.
TEST(PolygonChannel, WithoutWaitTheNextCuttingBlockWaitsForThePhase) {
  PolygonRig rig(true);
  rig.load("G51.2 P1 Q2\nG00 Z0.1\nG01 X10 F3000\nG50.2\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_GT(rig.locked_at, 0U);
  ASSERT_GT(rig.first_move_of[1], 0U);
  EXPECT_LT(rig.first_move_of[1], rig.locked_at);  // Z: while T1 catches up
  EXPECT_GT(rig.first_move_of[0], rig.locked_at);  // X (G01): only once T1 was in phase
  EXPECT_EQ(rig.feedback_[0].cmd, 5.0);
}

}  // namespace
}  // namespace mcnc::channel
