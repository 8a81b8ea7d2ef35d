// G51.4 / G50.4 as a channel runs them (spec dafeng §3.2): the request out, the end of the block
// from the slave's feedback, an axis that follows is not the program's to move, and after G50.4
// the program goes on from where the master took it. Channel 1 programs X (axis 1), Y (axis 2,
// may follow) and B (axis 4, a gantry's second drive following X from power-on); the machine
// also has C (axis 3, rotary) and Z (axis 5, another channel's).
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 3;

interp::InterpreterConfig xyb_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.channel_count = 2;
  c.axes = {interp::AxisConfig{'X'}, interp::AxisConfig{'Y'}, interp::AxisConfig{'B'}};
  const std::array<int, kAxes> ids{1, 2, 4};
  for (std::size_t i = 0; i < kAxes; ++i) {
    c.axes[i].id = ids[i];
    c.axes[i].may_follow = i > 0;
  }
  return c;
}

ChannelSetup xyb_setup() {
  ChannelSetup s{kAxes, {0.001, 0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.slots = {AxisSlot{'X', false, 1, 1}, AxisSlot{'Y', false, 1, 2, true},
             AxisSlot{'B', false, 1, 4, true, 1, true}};
  using K = MachineAxisKind;
  s.machine_axes = {MachineAxis{K::linear, false}, MachineAxis{K::linear, true},
                    MachineAxis{K::rotary, false}, MachineAxis{K::linear, true},
                    MachineAxis{K::linear, false}};
  return s;
}

// Channel 1 and simulated axis nodes: a G51.4 / G50.4 takes effect in the cycle after it was
// sent and shows in the channel's feedback a cycle later; a coupled slave copies X's increments
// (its master here is X, or Z of the other channel, which stands), the others follow the channel's
// valid setpoints.
class SyncRig : public ChannelRig {
 public:
  SyncRig() : ChannelRig(xyb_channel(), alike_axes(kAxes, kDt), xyb_setup()) {
    feedback_.resize(kAxes);
    for (auto& f : feedback_) {
      f.enabled = true;
      f.present = true;
      f.owner = 1;
    }
    feedback_[2].coupled_to = 1;  // the gantry from power-on
    feedback_[2].coupling_locked = true;
    feedback_[2].cmd = feedback_[2].act = 0.25;  // the beam's skew
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    std::array<std::uint32_t, kAxes> seen{};  // what the channel knew this cycle
    for (std::size_t a = 0; a < kAxes; ++a) {
      seen[a] = feedback_[a].coupled_to;
    }
    if (pending_) {
      feedback_[pending_->slot].coupled_to = pending_->on ? pending_->master : 0;
      feedback_[pending_->slot].coupling_locked = pending_->on;
    }
    pending_.reset();
    if (out.axis_sync_due) {
      pending_ = out.axis_sync;
      sent.push_back(out.axis_sync);
    }
    const double x_moved = out.setpoints[0].valid ? out.setpoints[0].pos - feedback_[0].cmd : 0.0;
    for (std::size_t a = 0; a < kAxes; ++a) {
      AxisFeedbackView& f = feedback_[a];
      if (f.coupled_to != 0) {
        f.cmd += f.coupled_to == 1 ? x_moved : 0.0;
        valid_while_coupled += out.setpoints[a].valid && seen[a] != 0 ? 1 : 0;
      } else if (out.setpoints[a].valid) {
        jump = std::max(jump, std::fabs(out.setpoints[a].pos - f.cmd));
        f.cmd = out.setpoints[a].pos;
      }
      f.act = f.cmd;
    }
    return out;
  }

  [[nodiscard]] const std::vector<AxisFeedbackView>& feedback() const { return feedback_; }
  // The node of `slot` follows `master` without this channel's block (its G51.4 forgotten by a
  // reset before the answer came).
  void node_couples(std::size_t slot, std::uint32_t master) { feedback_[slot].coupled_to = master; }

  std::vector<AxisSyncOut> sent;
  // Valid setpoints for an axis the channel saw following (the real node ignores them).
  int valid_while_coupled = 0;
  double jump = 0.0;  // the largest step of a followed setpoint

 private:
  std::vector<AxisFeedbackView> feedback_;
  std::optional<AxisSyncOut> pending_;
  std::uint64_t cycle_ = 0;
};

TEST(AxisSync, TheSlaveMovesWithItsMasterAndTheProgramGoesOnFromThere) {
  SyncRig rig;
  rig.load("G51.4 P1 Q2\nG01 X10 F3000\nG50.4 Q2\nG01 Y15\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);
  EXPECT_TRUE(rig.sent[0].on);
  EXPECT_EQ(rig.sent[0].slot, 1U);
  EXPECT_EQ(rig.sent[0].master, 1U);
  EXPECT_FALSE(rig.sent[1].on);
  EXPECT_DOUBLE_EQ(rig.feedback()[0].cmd, 10.0);
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 15.0);   // 10 with X, then on to 15 from there
  EXPECT_DOUBLE_EQ(rig.feedback()[2].cmd, 10.25);  // the gantry's drive followed X too
  EXPECT_EQ(rig.valid_while_coupled, 0);
  // No setpoint jumped back to where the program had left Y: no step beyond a cycle at F3000.
  EXPECT_LT(rig.jump, 0.0501);
  EXPECT_TRUE(rig.ctl().commands_axis(1));
  EXPECT_FALSE(rig.ctl().commands_axis(2));
}

TEST(AxisSync, MovingAnAxisThatFollowsIsAnAlarmBeforeTheBlockMoves) {
  SyncRig rig;
  rig.load("G51.4 P1 Q2\nG01 X5 F3000\nG01 X6 Y3\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmAxisFollows}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{3}));
  EXPECT_NE(rig.alarm_text.find("G50.4 Q2"), std::string::npos) << rig.alarm_text;
  EXPECT_DOUBLE_EQ(rig.feedback()[0].cmd, 5.0);  // line 3 moved nothing
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 5.0);
}

TEST(AxisSync, TheGantrysSecondDriveFollowsFromPowerOnUntilG504) {
  SyncRig rig;
  rig.load("G01 B2 F3000\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmAxisFollows}));
  EXPECT_DOUBLE_EQ(rig.feedback()[2].cmd, 0.25);

  SyncRig realigned;
  realigned.load("G01 X4 F3000\nG50.4 Q4\nG01 B[#5003-0.25]\nG51.4 Q4\nG01 X8\nM30\n");
  ASSERT_TRUE(realigned.run_to_end());
  EXPECT_TRUE(realigned.alarms.empty()) << realigned.alarm_text;
  ASSERT_EQ(realigned.sent.size(), 2U);
  EXPECT_EQ(realigned.sent[1].master, 1U);  // G51.4 without P: its parameter 5610
  // 0.25 + 4 with X, the skew taken out, then 4 more with X.
  EXPECT_NEAR(realigned.feedback()[2].cmd, 8.0, 1e-9);
}

// Each refusal is alarm 1260 at its block, before anything is sent to a node.
void expect_refused(const std::string& block, const std::string& why) {
  SyncRig rig;
  rig.load(block + "\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmAxisSync})) << block;
  EXPECT_NE(rig.alarm_text.find(why), std::string::npos) << block << ": " << rig.alarm_text;
  EXPECT_TRUE(rig.sent.empty()) << block;
}

TEST(AxisSync, AnAxisFoundFollowingIsNoLongerTheProgramsToMove) {
  SyncRig rig;
  rig.load("G01 X10 F600\nG01 Y3\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.feedback()[0].cmd > 1.0; }));
  rig.node_couples(1, 1);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }));
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmAxisFollows}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{2}));
  EXPECT_FALSE(rig.ctl().commands_axis(1));
  EXPECT_EQ(rig.valid_while_coupled, 0);
}

TEST(AxisSync, WhatCannotLeadOrFollowIsRefused) {
  expect_refused("G51.4 Q2", "no default master");
  expect_refused("G51.4 P3 Q2", "not of the same kind");
  expect_refused("G51.4 P4 Q2", "cannot lead");
  expect_refused("G51.4 P9 Q2", "no such axis");
  expect_refused("G51.4 P5 Q4", "already follows axis 1");
}

TEST(AxisSync, AMasterInAnotherChannelAndRepeatsThatChangeNothing) {
  SyncRig rig;
  rig.load("G51.4 P5 Q2\nG51.4 P5 Q2\nG51.4 Q4\nG50.4 Q2\nG50.4 Q2\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  ASSERT_EQ(rig.sent.size(), 2U);  // the second G51.4, B's G51.4 and the second G50.4: nothing
  EXPECT_EQ(rig.sent[0].master, 5U);
  EXPECT_FALSE(rig.sent[1].on);
}

TEST(AxisSync, TheSlaveMustBeOneOfTheChannelsAxesThatMayFollow) {
  interp::InterpreterSource source(xyb_channel());
  auto alarm = source.load("G51.4 P2 Q1\nM30\n", "T.nc");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_NE(alarm->text.find("cannot follow"), std::string::npos) << alarm->text;
  alarm = source.load("G50.4 Q5\nM30\n", "T.nc");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_NE(alarm->text.find("not one of this channel's axes"), std::string::npos) << alarm->text;
}

}  // namespace
}  // namespace mcnc::channel
