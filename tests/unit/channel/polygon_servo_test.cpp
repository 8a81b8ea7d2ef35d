// G51.2 / G50.2 with a rotary servo axis as the polygon axis (spec dafeng L2897-2899, param
// 5311): while C follows its master spindle the channel sends no valid setpoint for it and the
// program may not move it; G50.2 (P0 too) waits until it stands and the channel then commands
// it where it stands, so that the program moves it on from there; after a reset the next run
// takes it where the release left it. Channel 1 programs X, Z and C (axis 3, the polygon axis)
// and has the spindle S1 (axis 4, the master).
#include "channel_rig.hpp"
#include "coupling_node_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 3;
constexpr std::size_t kC = 2;
constexpr std::size_t kMaster = kAxes;  // S1's feedback
constexpr std::uint64_t kCatchUp = 50;  // cycles the simulated node takes to lock, or to stop
constexpr double kTurn = 6.0;           // degrees the simulated node turns C per cycle

interp::InterpreterConfig xzc_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'},
            interp::AxisConfig{'C', false, true}};
  return c;
}

ChannelSetup xzc_setup() {
  ChannelSetup s{kAxes, {0.001, 0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.spindle_count = 1;
  s.slots = {AxisSlot{'X', false, 1, 1}, AxisSlot{'Z', false, 1, 2},
             AxisSlot{'C', false, 1, 3, false, 0, false, true}};
  s.polygon = coordination::PolygonSetup{4, kMaster, kC, 3000.0 * 6.0, true};
  return s;
}

// C's node (CouplingNodeRig): from the cycle after G51.2 it turns C by kTurn a cycle, whatever
// the channel sends; after G50.2 it goes on until it stands free, and then holds where it is
// until the channel's setpoints are valid again.
class PolygonServoRig : public ChannelRig, public CouplingNodeRig<PolygonOut> {
 public:
  PolygonServoRig()
      : ChannelRig(xzc_channel(), alike_axes(kAxes, kDt), xzc_setup()),
        CouplingNodeRig<PolygonOut>(4, kCatchUp) {
    feedback_ = standing_feedback(kAxes + 1, 1);
    feedback_[kMaster].vel = 3000.0;  // S1 turns at 500 rpm
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    AxisFeedbackView& c = feedback_[kC];
    const bool turned = c.coupled_to != 0;
    (void)answer(cycle_, c);
    if (out.polygon_sync_due) {
      record(cycle_, out.polygon_sync);
    }
    c_valid.push_back(out.setpoints[kC].valid);
    c_coupled.push_back(turned);
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (a == kC && turned) {
        c.cmd += kTurn;
      } else if (out.setpoints[a].valid) {
        if (a != kC && feedback_[a].cmd != out.setpoints[a].pos && first_move == 0) {
          first_move = cycle_;
        }
        feedback_[a].cmd = out.setpoints[a].pos;
      }
      feedback_[a].act = feedback_[a].cmd;
    }
    c_cmd.push_back(c.cmd);
    ++cycle_;
    return out;
  }

  std::uint64_t first_move = 0;  // of X or Z
  std::uint64_t cycle_ = 0;
  std::vector<bool> c_valid;    // the channel's setpoint of C is valid, per cycle
  std::vector<bool> c_coupled;  // C's node turns it, per cycle
  std::vector<double> c_cmd;    // C as its node commands it, per cycle
  std::vector<AxisFeedbackView> feedback_;
};

TEST(PolygonServoChannel, CFollowsWithoutTheChannelsSetpointsAndMovesOnFromWhereItStands) {
  PolygonServoRig rig;
  rig.load("G51.2 P1 Q2\nG01 X10 F3000\nG50.2\nG00 H90\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_TRUE(rig.sent[0].on);
  EXPECT_FALSE(rig.sent[1].on);
  ASSERT_GT(rig.locked_at, 0U);
  EXPECT_GT(rig.first_move, rig.locked_at);  // X moved only once C was in phase
  // From G51.2's lock to G50.2's end the channel sends C no valid setpoint.
  std::uint64_t turning = 0;
  for (std::size_t k = rig.locked_at; k < rig.c_valid.size() && rig.c_coupled[k]; ++k) {
    ASSERT_FALSE(rig.c_valid[k]) << "cycle " << k;
    ++turning;
  }
  EXPECT_GT(turning, 100U);
  // Once it stands free, C is commanded where it stood (no jump) and H90 moves it on by 90 at
  // its rapid rate (100 units/s).
  std::size_t back = rig.locked_at;
  while (back < rig.c_valid.size() && !(rig.c_valid[back] && !rig.c_coupled[back])) {
    ++back;
  }
  ASSERT_LT(back, rig.c_cmd.size());
  const double stood = rig.c_cmd.at(back - 1);
  EXPECT_GT(stood, 600.0);
  for (std::size_t k = back; k < rig.c_cmd.size(); ++k) {
    ASSERT_LE(std::fabs(rig.c_cmd[k] - rig.c_cmd[k - 1]), 100.0 * kDt + 1e-9) << "cycle " << k;
  }
  EXPECT_NEAR(rig.c_cmd.back(), stood + 90.0, 1e-9);
}

TEST(PolygonServoChannel, AMoveOfCWhileItFollowsIsAnAlarmAndG502P0Waits) {
  {
    PolygonServoRig rig;
    rig.load("G51.2 P1 Q2\nG00 C10\nM30\n");
    ASSERT_TRUE(rig.run_to_end());
    ASSERT_EQ(rig.alarms, std::vector<int>{coordination::kAlarmAxisFollows});
    EXPECT_EQ(rig.alarm_lines, std::vector<int>{2});
    EXPECT_EQ(rig.alarm_text,
              "C is the polygon axis, turning with its master spindle (G51.2): G50.2 before the "
              "program moves it");
  }
  PolygonServoRig rig;
  rig.load("G51.2 P1 Q2\nG50.2 P0\nG01 X10 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_FALSE(rig.sent[1].wait);
  // X moved only once C stood free (decision 158): the program knows where C is.
  ASSERT_GT(rig.first_move, rig.sent_at[1] + kCatchUp);
  EXPECT_FALSE(rig.c_coupled.at(rig.first_move));
}

TEST(PolygonServoChannel, AfterAResetTheNextRunTakesCWhereTheReleaseLeftIt) {
  PolygonServoRig rig;
  rig.load("G51.2 P1 Q2\nG04 X10\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.locked_at != 0; }));
  rig.ctl().request_reset();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.sent.size() == 2; }, 10));
  EXPECT_FALSE(rig.sent[1].on);
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return !rig.c_coupled.back(); }, 200));
  for (int i = 0; i < 10; ++i) {
    (void)rig.step();
  }
  const double stood = rig.feedback_[kC].cmd;
  rig.load("G00 H-30\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.feedback_[kC].cmd, stood - 30.0, 1e-9);
}

}  // namespace
}  // namespace mcnc::channel
