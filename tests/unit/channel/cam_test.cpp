// G51.8 / G50.8 as a channel runs them (spec dafeng §2.6.7): the table goes to the cam slave's
// node, the block after G51.8 waits until the slave is on its lift, the program moves the slave
// as usual while its node adds the lift (which the channel's in-position check and its reading
// back of positions leave out), G50.8 waits until the lift is off, a reset takes it off, and
// G51.8 on a channel without a cam sends nothing and moves nothing. Channel 1 programs X (the
// slave) and Z and has the spindle S1 (axis 3, the master).
#include "channel_rig.hpp"
#include "coupling_node_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;
constexpr std::uint64_t kCatchUp = 50;  // cycles the simulated node takes to reach the lift
constexpr double kLift = 0.3;           // the simulated lift, on X's command
constexpr double kLag = 0.01;           // X's actual position lags its command while it runs

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  return c;
}

ChannelSetup xz_setup(bool cam) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.spindle_count = 1;
  if (cam) {
    s.cam = coordination::CamSetup{3, 0};
  }
  return s;
}

// The slave's node (CouplingNodeRig, catching up in kCatchUp cycles). While the cam runs X's
// command is the channel's plus the lift, and its actual position lags that by kLag.
class CamRig : public ChannelRig, public CouplingNodeRig<CamOut> {
 public:
  explicit CamRig(bool cam = true)
      : ChannelRig(xz_channel(), alike_axes(kAxes, kDt), xz_setup(cam)),
        CouplingNodeRig<CamOut>(3, kCatchUp) {
    feedback_ = standing_feedback(kAxes + 1, 1);
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    AxisFeedbackView& x = feedback_[0];
    if (answer(cycle_, x)) {
      const double path = x.channel_cmd();
      x.superimposed = coupling_on() ? kLift : 0.0;
      x.cmd = path + x.superimposed;
      x.act = x.cmd - (coupling_on() ? kLag : 0.0);
    }
    if (out.cam_sync != nullptr) {
      record(cycle_, *out.cam_sync);
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (out.setpoints[a].valid) {
        if (feedback_[a].channel_cmd() != out.setpoints[a].pos && first_move == 0) {
          first_move = cycle_;
        }
        feedback_[a].cmd = out.setpoints[a].pos + feedback_[a].superimposed;
        feedback_[a].act = feedback_[a].cmd - (feedback_[a].superimposed != 0.0 ? kLag : 0.0);
      }
    }
    ++cycle_;
    return out;
  }

  std::uint64_t first_move = 0;
  std::uint64_t cycle_ = 0;
  std::vector<AxisFeedbackView> feedback_;
};

TEST(CamChannel, TheMoveAfterG518WaitsForTheLiftAndTheProgramEndsWithItOff) {
  CamRig rig;
  rig.load(
      "#100=0\n#101=0.5\n#102=0.25\nG51.8 P100 L3 R90\nG01 X10 F3000\nG04 X0.1\nG50.8\n"
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_TRUE(rig.sent[0].on);
  EXPECT_EQ(rig.sent[0].shape, 0);
  ASSERT_EQ(rig.sent[0].points, 3U);
  EXPECT_EQ(rig.sent[0].lift[1], 0.5);
  EXPECT_EQ(rig.sent[0].lift[2], 0.25);
  EXPECT_EQ(rig.sent[0].r, 90.0);
  EXPECT_FALSE(rig.sent[1].on);
  ASSERT_GT(rig.locked_at, 0U);
  EXPECT_GT(rig.first_move, rig.locked_at);  // X moved only once it was on the lift
  // The G01 ended in position although X's actual position never met its command: the lift's.
  EXPECT_EQ(rig.feedback_[0].coupled_to, 0U);  // the program ended with the lift off
  EXPECT_EQ(rig.feedback_[0].cmd, 5.0);
}

TEST(CamChannel, AResetTakesTheLiftOffAndTheChannelGoesOnFromThePath) {
  CamRig rig;
  rig.load("G51.8 H1 A10 B8\nG01 X4 F3000\nG04 X10\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) {
    return rig.locked_at != 0 && std::fabs(rig.feedback_[0].channel_cmd() - 2.0) < 1e-12;
  }));
  EXPECT_EQ(rig.sent[0].shape, 1);
  EXPECT_EQ(rig.sent[0].a, 10.0);
  EXPECT_EQ(rig.sent[0].b, 8.0);
  const std::uint64_t reset_at = rig.cycle_;
  rig.ctl().request_reset();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.sent.size() == 2; }, 10));
  EXPECT_EQ(rig.sent_at[1], reset_at);
  EXPECT_FALSE(rig.sent[1].on);
  // The channel reads X back at 2 (its path), not 2.3: once the lift is off it commands 2.
  for (int i = 0; i < 200; ++i) {
    const CycleOutput& out = rig.step();
    if (out.setpoints[0].valid) {
      ASSERT_NEAR(out.setpoints[0].pos, 2.0, 1e-12) << "cycle " << rig.cycle_;
    }
  }
  EXPECT_NEAR(rig.feedback_[0].cmd, 2.0, 1e-12);
  EXPECT_EQ(rig.sent.size(), 2U);  // once
}

TEST(CamChannel, G518WithoutACamSendsNothingAndMovesNothing) {
  CamRig rig(false);
  rig.load("G00 X4\nG51.8 H2 D10 P2\nG01 X10 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, std::vector<int>{coordination::kAlarmCam});
  EXPECT_EQ(rig.alarm_lines, std::vector<int>{2});
  EXPECT_TRUE(rig.sent.empty());
  for (int i = 0; i < 200; ++i) {
    (void)rig.step();
  }
  EXPECT_EQ(rig.feedback_[0].cmd, 2.0);  // X stands where G00 X4 put it (radius)
}

}  // namespace
}  // namespace mcnc::channel
