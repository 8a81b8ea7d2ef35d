// G81.4 / G80.4 as a channel runs them (spec dafeng §2.6.11): the gear goes to the work axis's
// node, the block after G81.4 waits until the work axis is locked, the program moves the other
// axes while the node lays the gear's offset over C (which the channel's in-position check
// leaves out), G80.4 waits until C stands, and the channel then commands C at the angle it
// stopped at, telling the node in the same cycle, so that the move after it starts from there
// without a jump. Channel 1 programs X, Z and C (the work axis) and has the spindle S1 (axis 4,
// the tool).
#include "channel_rig.hpp"
#include "coupling_node_rig.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 3;
constexpr std::size_t kC = 2;
constexpr std::uint64_t kCatchUp = 50;  // cycles the simulated node takes to lock, or to stop
constexpr double kTurn = 0.09;          // degrees the simulated gear turns C per cycle

interp::InterpreterConfig xzc_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'},
            interp::AxisConfig{'C', false, true}};
  return c;
}

ChannelSetup xzc_setup(bool no_wait) {
  ChannelSetup s{kAxes, {0.001, 0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.spindle_count = 1;
  s.egb = coordination::EgbSetup{4, kAxes, kC, true, no_wait};
  return s;
}

// The work axis's node (CouplingNodeRig): while the gear runs, C's offset grows by kTurn a
// cycle; G80.4 stops it where it is; the hand-over takes it off in the cycle after it was sent,
// when the channel's setpoint carries it.
class EgbRig : public ChannelRig, public CouplingNodeRig<EgbOut> {
 public:
  explicit EgbRig(bool no_wait = false)
      : ChannelRig(xzc_channel(), alike_axes(kAxes, kDt), xzc_setup(no_wait)),
        CouplingNodeRig<EgbOut>(4, kCatchUp) {
    feedback_ = standing_feedback(kAxes + 1, 1);
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    AxisFeedbackView& c = feedback_[kC];
    (void)answer(cycle_, c);
    if (c.coupled_to != 0 && coupling_on()) {
      c.superimposed += kTurn;
    }
    if (out.egb_sync_due && out.egb_sync.off == EgbOut::Off::absorb) {
      absorbed_at = cycle_;
      c.superimposed = 0.0;
    } else if (out.egb_sync_due) {
      record(cycle_, out.egb_sync);
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (out.setpoints[a].valid) {
        if (feedback_[a].channel_cmd() != out.setpoints[a].pos) {
          first_move[a] = first_move[a] == 0 ? cycle_ : first_move[a];
        }
        feedback_[a].cmd = out.setpoints[a].pos + feedback_[a].superimposed;
      } else {
        feedback_[a].cmd = feedback_[a].channel_cmd() + feedback_[a].superimposed;
      }
      feedback_[a].act = feedback_[a].cmd;
    }
    c_cmd.push_back(c.cmd);
    ++cycle_;
    return out;
  }

  std::uint64_t cycle_ = 0;
  std::uint64_t absorbed_at = 0;
  std::array<std::uint64_t, kAxes> first_move{};  // the cycle each axis was first moved in
  std::vector<double> c_cmd;                      // C as its node commands it, per cycle
  std::vector<AxisFeedbackView> feedback_;
};

TEST(EgbChannel, G804HandsTheReachedAngleToTheChannelAndCMovesOnFromThereWithoutAJump) {
  EgbRig rig;
  rig.load("G81.4 T20 L1 R0\nG01 X10 F3000\nG80.4\nG00 H90\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_TRUE(rig.sent[0].on);
  EXPECT_EQ(rig.sent[0].teeth, 20);
  EXPECT_TRUE(rig.sent[0].phase);
  EXPECT_FALSE(rig.sent[1].on);
  EXPECT_EQ(rig.sent[1].off, EgbOut::Off::stop);
  ASSERT_GT(rig.absorbed_at, rig.sent_at[1]);
  // C stood still from its stop to the hand-over, and then moved on by 90 at most at its rapid
  // rate (100 units/s): never a jump.
  const double reached = rig.c_cmd.at(rig.absorbed_at);
  EXPECT_GT(reached, 10.0);
  for (std::size_t k = rig.absorbed_at + 1; k < rig.c_cmd.size(); ++k) {
    ASSERT_LE(std::fabs(rig.c_cmd[k] - rig.c_cmd[k - 1]), 100.0 * kDt + 1e-9) << "cycle " << k;
  }
  EXPECT_NEAR(rig.c_cmd.back(), reached + 90.0, 1e-9);
  EXPECT_EQ(rig.feedback_[kC].superimposed, 0.0);
}

TEST(EgbChannel, ASecondG814IsRefusedAndTheGearKeepsRunning) {
  EgbRig rig;
  rig.load("G81.4 T20 L1 R0\nG81.4 T10 L1 R0\nG01 X10 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, std::vector<int>{coordination::kAlarmEgb});
  EXPECT_EQ(rig.alarm_lines, std::vector<int>{2});
  EXPECT_EQ(rig.sent.size(), 1U);
  EXPECT_EQ(rig.feedback_[0].cmd, 0.0);  // X never moved
}

// Param 5320.5 = 1 (spec dafeng L3331-3333): G81.4 does not wait for the work axis to lock,
// the rapid after it runs at once, and the cutting block after that waits for the lock.
TEST(EgbChannel, WithoutWaitTheNextCuttingBlockWaitsForTheLock) {
  EgbRig rig(true);
  rig.load("G81.4 T20 L1 R0\nG00 Z0.1\nG01 X10 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_GT(rig.locked_at, 0U);
  ASSERT_GT(rig.first_move[1], 0U);
  EXPECT_LT(rig.first_move[1], rig.locked_at);  // Z: while C catches up
  EXPECT_GT(rig.first_move[0], rig.locked_at);  // X (G01): only once C was locked
  EXPECT_EQ(rig.feedback_[0].cmd, 5.0);
}

}  // namespace
}  // namespace mcnc::channel
