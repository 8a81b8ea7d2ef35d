// G140/G141/G142 as a channel runs them (spec dafeng §3.3): requests out, the owner from the
// axis feedback, the machine position taken over, and what a channel may not do with an axis
// it does not own. Channel 2 programs X (its own) and A (channel 1's axis, exchange number 14).
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::uint32_t kSelf = 2;

interp::InterpreterConfig xa_channel() {
  interp::InterpreterConfig c;
  c.channel = static_cast<int>(kSelf);
  c.channel_count = 3;
  c.axes = {interp::AxisConfig{'X', false}, interp::AxisConfig{'A', false, true}};
  c.axes[0].exchange = 7;
  c.axes[1].exchange = 14;
  return c;
}

motion::MotionConfig xa_motion() {
  motion::MotionConfig c;
  c.axis_count = 2;
  c.axes[0] = motion::AxisDynamics{50.0, 1000.0, 50000.0};
  c.axes[1] = motion::AxisDynamics{600.0, 10000.0, 500000.0};
  c.rapid_rate = {100.0, 600.0};
  c.cycle_s = kDt;
  return c;
}

// Channel 2 and two simulated axis nodes. A node decides a request in the cycle after it was
// sent, as the real one does (a release or restore at once; an acquire once the axis is free,
// or at once with P1), and its feedback shows the owner one cycle later. Axes follow the
// channel's valid setpoints (the real node follows only its owner's: here the rig counts a
// valid setpoint for an axis the channel knew it did not own).
class ExchangeRig : public ChannelRig {
 public:
  ExchangeRig()
      : ChannelRig(xa_channel(), xa_motion(), [] {
          ChannelSetup s{2, {0.001, 0.001}, kDt};
          s.channel_id = kSelf;
          s.slots = {AxisSlot{'X', false, kSelf}, AxisSlot{'A', true, 1}};
          return s;
        }()) {
    feedback_.resize(2);
    for (auto& f : feedback_) {
      f.enabled = true;
      f.present = true;
    }
    feedback_[0].owner = kSelf;
    feedback_[1].owner = 1;
    feedback_[1].cmd = 20.0;  // channel 1 left A at 20 degrees
    feedback_[1].act = 20.0;
    owner_ = {kSelf, 1};
  }

  const CycleOutput& step() override {
    // The nodes: last cycle's requests decided now, shown in this cycle's feedback.
    for (const AxisRequestOut& r : pending_) {
      for (std::size_t a = 0; a < 2; ++a) {
        if (r.slot != a && r.slot != AxisRequestOut::kAllSlots) {
          continue;
        }
        switch (r.kind) {
          case AxisRequestKind::release:
            refused_[a] = owner_[a] != kSelf;  // not its to release: refused, and said so
            if (owner_[a] == kSelf) {
              owner_[a] = 0;
              released_by_[a] = kSelf;
            }
            break;
          case AxisRequestKind::acquire:
            full_[a] = full_line;  // the node's waiting line has no room: said so
            waiting_[a] = !full_line;
            force_[a] = r.force;
            break;
          case AxisRequestKind::restore:
            if (owner_[a] == kSelf || released_by_[a] == kSelf) {
              owner_[a] = a == 0 ? kSelf : 1;
              released_by_[a] = 0;
            }
            break;
          case AxisRequestKind::withdraw:
            waiting_[a] = false;
            ++withdrawn;
            break;
        }
      }
    }
    for (std::size_t a = 0; a < 2; ++a) {
      if (waiting_[a] && (owner_[a] == 0 || force_[a])) {
        released_by_[a] = owner_[a] == 0 ? released_by_[a] : owner_[a];
        owner_[a] = kSelf;
        waiting_[a] = false;
      }
    }
    const std::array<std::uint32_t, 2> seen{feedback_[0].owner, feedback_[1].owner};
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    pending_.assign(out.axis_requests.begin(), out.axis_requests.begin() + out.axis_request_count);
    requests.insert(requests.end(), pending_.begin(), pending_.end());
    for (std::size_t a = 0; a < 2; ++a) {
      feedback_[a].owner = owner_[a];
      feedback_[a].released_by = released_by_[a];
      feedback_[a].request_refused = refused_[a];
      feedback_[a].request_full = full_[a];
      if (out.setpoints[a].valid) {
        if (seen[a] != kSelf) {
          ++foreign_setpoints;  // a valid setpoint for an axis it knew was not its own
        }
        feedback_[a].cmd = out.setpoints[a].pos;
        feedback_[a].act = out.setpoints[a].pos;
      }
    }
    return out;
  }

  void take_away_from_channel_1() { owner_[1] = 0; }  // channel 1's G140
  void take_x_for(std::uint32_t channel) {  // channel's G141 P1 of X, seen by the node only
    owner_[0] = channel;
    released_by_[0] = kSelf;
  }
  void give_x_to(std::uint32_t channel) {
    owner_[0] = channel;
    released_by_[0] = kSelf;
  }

  const std::vector<AxisFeedbackView>& feedback() const { return feedback_; }

  std::vector<AxisRequestOut> requests;
  int foreign_setpoints = 0;
  int withdrawn = 0;
  bool full_line = false;  // the nodes keep no more waiting requests

 private:
  std::vector<AxisFeedbackView> feedback_;
  std::vector<AxisRequestOut> pending_;
  std::array<std::uint32_t, 2> owner_{};
  std::array<std::uint32_t, 2> released_by_{};
  std::array<bool, 2> waiting_{};
  std::array<bool, 2> force_{};
  std::array<bool, 2> refused_{};
  std::array<bool, 2> full_{};
  std::uint64_t cycle_ = 0;
};

TEST(AxisExchange, AVirtualAxisMovesNothingAndAnAcquiredOneStartsWhereItStands) {
  ExchangeRig rig;
  rig.load("G00 A-90\nG141 A14\nG00 A[#5002+10]\nM30\n");
  rig.ctl().request_start();
  // The virtual A-90 runs in the channel only; the acquire waits for channel 1's release.
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::waiting; }));
  ASSERT_EQ(rig.requests.size(), 1U);
  EXPECT_EQ(rig.requests[0].kind, AxisRequestKind::acquire);
  EXPECT_EQ(rig.requests[0].slot, 1U);
  EXPECT_FALSE(rig.requests[0].force);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::waiting);  // waits as long as channel 1 keeps A
  }
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 20.0);
  rig.take_away_from_channel_1();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 30.0);  // 20 (channel 1's) + 10
  EXPECT_EQ(rig.foreign_setpoints, 0);
  EXPECT_TRUE(rig.alarms.empty());
  EXPECT_TRUE(rig.ctl().commands_axis(1));
}

TEST(AxisExchange, ReleasingAnAxisTheChannelDoesNotOwnIsAnAlarm) {
  ExchangeRig rig;
  rig.load("G140 A14\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }));
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmNotOwner}));
  EXPECT_TRUE(rig.requests.empty());
}

TEST(AxisExchange, AResetWhileWaitingForAnAxisWithdrawsTheRequest) {
  ExchangeRig rig;
  rig.load("G141 A14\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::waiting; }));
  rig.ctl().request_reset();
  rig.step();
  rig.step();
  EXPECT_EQ(rig.withdrawn, 1);
  rig.take_away_from_channel_1();  // released later: nobody is waiting for it now
  for (int i = 0; i < 10; ++i) {
    rig.step();
  }
  EXPECT_FALSE(rig.ctl().commands_axis(1));
  EXPECT_EQ(rig.feedback()[1].owner, 0U);
}

TEST(AxisExchange, G142GivesTheAxisBackAndTheSlotIsVirtualAgain) {
  ExchangeRig rig;
  rig.load("G141 A14 P1\nG00 A45\nG142\nG00 A-90\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  ASSERT_EQ(rig.requests.size(), 2U);
  EXPECT_TRUE(rig.requests[0].force);
  EXPECT_EQ(rig.requests[1].kind, AxisRequestKind::restore);
  EXPECT_EQ(rig.requests[1].slot, AxisRequestOut::kAllSlots);
  EXPECT_EQ(rig.feedback()[1].owner, 1U);
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 45.0);  // the virtual A-90 after G142 moved nothing
  EXPECT_FALSE(rig.ctl().commands_axis(1));
  EXPECT_EQ(rig.foreign_setpoints, 0);
}

TEST(AxisExchange, MovingAnOwnAxisAnotherChannelHasIsAnAlarmBeforeItMoves) {
  ExchangeRig rig;
  rig.give_x_to(3);  // channel 3 took X (G141 P1) before this program started
  rig.step();
  rig.load("G00 A5\nG00 X10\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }));
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmAxisAway}));
  EXPECT_EQ(rig.ctl().last_alarm().line, 2);
  EXPECT_DOUBLE_EQ(rig.feedback()[0].cmd, 0.0);
  EXPECT_EQ(rig.foreign_setpoints, 0);
}

// The node answers in its feedback; a request it could not keep is an alarm in the asker, never
// a wait for ever (it was before: the answer was decided and never sent).
TEST(AxisExchange, AnAcquireTheNodeCannotKeepIsAnAlarmNotAWaitForEver) {
  ExchangeRig rig;
  rig.full_line = true;
  rig.load("G141 A14\nG00 A10\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }));
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmRequestRefused}));
  EXPECT_EQ(rig.ctl().last_alarm().line, 1);
  EXPECT_EQ(rig.ctl().last_alarm().axis, 2);
  EXPECT_NE(std::string(rig.ctl().last_alarm().text.data()).find("G141 A"), std::string::npos);
  EXPECT_DOUBLE_EQ(rig.feedback()[1].cmd, 20.0);  // A stays where channel 1 left it
  EXPECT_EQ(rig.foreign_setpoints, 0);
}

// Another channel takes X (G141 P1) in the cycle this channel's G140 X goes out: the node
// refuses the release, and the channel says so instead of taking X as released.
TEST(AxisExchange, AReleaseTheNodeRefusesIsAnAlarm) {
  ExchangeRig rig;
  rig.load("G140 X7\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.axis_request_count > 0; }));
  rig.take_x_for(3);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::alarm; }));
  EXPECT_EQ(rig.alarms, (std::vector<int>{kAlarmRequestRefused}));
  EXPECT_NE(std::string(rig.ctl().last_alarm().text.data()).find("G140 X: the axis node refused"),
            std::string::npos);
  EXPECT_NE(std::string(rig.ctl().last_alarm().text.data()).find("channel 3 has it"),
            std::string::npos);
}

}  // namespace
}  // namespace mcnc::channel
