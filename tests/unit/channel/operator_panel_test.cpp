// The operator panel as a channel acts on it: feed hold and cycle start, single block, the feed,
// rapid and spindle overrides. Channel 1 programs X and Z; its axis nodes follow every
// valid setpoint.
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X'}, interp::AxisConfig{'Z'}};
  return c;
}

// X measures the radius of G96 (css_axis).
motion::MotionConfig xz_motion() {
  motion::MotionConfig c = alike_axes(2, kDt);
  c.css_axis = 0;
  return c;
}

class PanelRig : public ChannelRig {
 public:
  PanelRig() : ChannelRig(xz_channel(), xz_motion(), xz_spindle_setup(kDt)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(out, feedback_, 2);
    return out;
  }

  [[nodiscard]] double x() const { return feedback_[0].cmd; }
  [[nodiscard]] double z() const { return feedback_[1].cmd; }
  [[nodiscard]] std::uint64_t cycles() const { return cycle_; }

 private:
  std::vector<AxisFeedbackView> feedback_ = standing_feedback(3, 1);
  std::uint64_t cycle_ = 0;
};

// Cycles from the start to the program end.
std::uint64_t run_time(PanelRig& rig) {
  const std::uint64_t from = rig.cycles();
  EXPECT_TRUE(rig.run_to_end());
  return rig.cycles() - from;
}

TEST(OperatorPanel, FeedHoldStopsThePathWhereItIsAndACycleStartGoesOn) {
  PanelRig rig;
  rig.load("G01 X100 F6000\nM30\n");  // 100 mm/s for a second
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.x() > 30.0; }));
  rig.ctl().request_feed_hold();
  EXPECT_EQ(rig.step().state, ChannelState::hold);
  // It decelerates along the path (1000 mm/s^2 from 100 mm/s: 5 mm and more for the jerk) and
  // then stands.
  for (int i = 0; i < 400; ++i) {
    rig.step();
  }
  const double stood = rig.x();
  EXPECT_GT(stood, 35.0);
  EXPECT_LT(stood, 45.0);
  for (int i = 0; i < 500; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::hold);
  }
  EXPECT_DOUBLE_EQ(rig.x(), stood);
  rig.ctl().request_start();
  EXPECT_EQ(rig.step().state, ChannelState::running);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_DOUBLE_EQ(rig.x(), 100.0);
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(OperatorPanel, FeedHoldOutsideARunAndAStartWhileRunningDoNothing) {
  PanelRig rig;
  rig.load("G01 X10 F6000\nM30\n");
  rig.ctl().request_feed_hold();  // before the axes are up: not kept for later
  EXPECT_EQ(rig.step().state, ChannelState::idle);
  rig.ctl().request_feed_hold();
  EXPECT_EQ(rig.step().state, ChannelState::idle);
  rig.ctl().request_start();
  EXPECT_EQ(rig.step().state, ChannelState::running);
  rig.ctl().request_start();  // again: no second start, no hold
  EXPECT_EQ(rig.step().state, ChannelState::running);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_DOUBLE_EQ(rig.x(), 10.0);
}

TEST(OperatorPanel, AResetInFeedHoldEndsTheProgram) {
  PanelRig rig;
  rig.load("G01 X100 F6000\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.x() > 30.0; }));
  rig.ctl().request_feed_hold();
  for (int i = 0; i < 100; ++i) {
    rig.step();  // still decelerating
  }
  rig.ctl().request_reset();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  const double stood = rig.x();
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::idle);
  }
  EXPECT_DOUBLE_EQ(rig.x(), stood);
  EXPECT_LT(stood, 100.0);
}

// Runs until the channel stops in hold (single block) or ends; the state it stopped in.
ChannelState run_to_stop(PanelRig& rig) {
  ChannelState state = ChannelState::running;
  EXPECT_TRUE(rig.run_until([&](const CycleOutput& o) {
    state = o.state;
    return o.state == ChannelState::hold || o.program_end;
  }));
  return state;
}

TEST(OperatorPanel, SingleBlockStopsOnEachBlocksEndPointAndACycleStartRunsTheNext) {
  PanelRig rig;
  // Corners that G64 would blend: in single block each block ends on its point.
  rig.load("G01 X10 F3000\nZ10\nX20\nM30\n");
  rig.ctl().set_single_block(true);
  rig.ctl().request_start();
  const double ends[2][2] = {{10.0, 0.0}, {10.0, 10.0}};
  for (const auto& end : ends) {
    ASSERT_EQ(run_to_stop(rig), ChannelState::hold);
    EXPECT_DOUBLE_EQ(rig.x(), end[0]);
    EXPECT_DOUBLE_EQ(rig.z(), end[1]);
    for (int i = 0; i < 300; ++i) {
      EXPECT_EQ(rig.step().state, ChannelState::hold);  // it waits for the operator
    }
    EXPECT_DOUBLE_EQ(rig.x(), end[0]);
    EXPECT_DOUBLE_EQ(rig.z(), end[1]);
    rig.ctl().request_start();
  }
  // The last block's end is the program's end.
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_DOUBLE_EQ(rig.x(), 20.0);
  EXPECT_DOUBLE_EQ(rig.z(), 10.0);
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(OperatorPanel, SingleBlockStopsBeforeABlockThatMovesNothing) {
  PanelRig rig;
  // G04.1 of a channel alone passes at once; the motion before it ends the planner's queue.
  rig.load("G01 X10 F3000\nG04.1 P1\nG01 X20\nM30\n");
  rig.ctl().set_single_block(true);
  rig.ctl().request_start();
  ASSERT_EQ(run_to_stop(rig), ChannelState::hold);
  EXPECT_DOUBLE_EQ(rig.x(), 10.0);
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_DOUBLE_EQ(rig.x(), 20.0);
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(OperatorPanel, SingleBlockOnMidRunStopsAtTheNextReachableBlockEndAndOffRunsOn) {
  PanelRig rig;
  rig.load("G01 X10 F3000\nZ10\nX20\nZ20\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.x() > 2.0; }));
  rig.ctl().set_single_block(true);
  ASSERT_EQ(run_to_stop(rig), ChannelState::hold);
  // At a block's end as the path runs: the blocks already blended end where their line meets
  // the blend, within the path tolerance of the corner.
  const double corners[3][2] = {{10.0, 0.0}, {10.0, 10.0}, {20.0, 10.0}};
  double nearest = 1e9;
  for (const auto& c : corners) {
    nearest = std::min(nearest, std::hypot(rig.x() - c[0], rig.z() - c[1]));
  }
  EXPECT_LT(nearest, 0.1) << rig.x() << " " << rig.z();
  const double stood_x = rig.x();
  // Off while stopped: still stopped until the cycle start, then no more stops.
  rig.ctl().set_single_block(false);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::hold);
  }
  EXPECT_DOUBLE_EQ(rig.x(), stood_x);
  rig.ctl().request_start();
  EXPECT_EQ(run_to_stop(rig), ChannelState::idle);
  EXPECT_DOUBLE_EQ(rig.x(), 20.0);
  EXPECT_DOUBLE_EQ(rig.z(), 20.0);
}

TEST(OperatorPanel, TheFeedOverrideScalesTheFeedAndTheRapidOverrideTheRapids) {
  const auto time_of = [](const char* program, double feed, double rapid) {
    PanelRig rig;
    rig.load(program);
    rig.ctl().set_feed_override(feed);
    rig.ctl().set_rapid_override(rapid);
    return static_cast<double>(run_time(rig));
  };
  const char* feed = "G01 X100 F3000\nM30\n";  // 50 mm/s: 2 s, the ramps short beside it
  const double full = time_of(feed, 100, 100);
  EXPECT_NEAR(time_of(feed, 50, 100) / full, 2.0, 0.05);
  EXPECT_NEAR(time_of(feed, 150, 100) / full, 1.0 / 1.5, 0.05);
  EXPECT_NEAR(time_of(feed, 300, 100) / full, 0.5, 0.05);  // clamped at 200 %
  // G00 at 100 mm/s takes 1.1 s with its ramps; at 25 % 4 s and shorter ramps.
  const char* rapid = "G00 X100\nM30\n";
  const double rapid_full = time_of(rapid, 100, 100);
  EXPECT_NEAR(time_of(rapid, 100, 25) * kDt, 4.05, 0.05);
  EXPECT_NEAR(time_of(rapid, 50, 100) / rapid_full, 1.0, 0.01);  // the feed override: not G00
}

TEST(OperatorPanel, TheSpindleOverrideScalesTheCommandedSpeedWithinItsRange) {
  PanelRig rig;
  rig.load("M03 S1000\nG04 X1\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.spindle_rpm > 0.0; }));
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 1000.0);
  rig.ctl().set_spindle_override(120);
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 1200.0);
  rig.ctl().set_spindle_override(200);
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 1200.0);  // at most 120 %
  rig.ctl().set_spindle_override(10);
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 500.0);  // at least 50 %
  rig.ctl().set_spindle_override(std::nan(""));
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 500.0);  // not a number: ignored
  rig.ctl().set_feed_override(std::nan(""));
  rig.ctl().set_rapid_override(std::nan(""));
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(OperatorPanel, TheSpindleOverrideUnderG96StaysWithinTheG50Limit) {
  PanelRig rig;
  // 100 m/min at a radius of 20 mm is 796 rpm; 120 % of it would be 955, G50 S800 limits it.
  rig.load("G00 X20\nG50 S800\nG96 S100 M03\nG04 X1\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.spindle_rpm > 0.0; }));
  const double base = rig.step().spindle_rpm;
  EXPECT_LT(base, 800.0);
  rig.ctl().set_spindle_override(120);
  EXPECT_DOUBLE_EQ(rig.step().spindle_rpm, 800.0);
}

// MDI blocks, checked as the channel shell checks them, prepared in the source.
void prepare_mdi(PanelRig& rig, const std::string& blocks) {
  interp::CheckedProgram checked =
      interp::InterpreterSource::check(xz_channel(), blocks, std::string(interp::kMdiName), true);
  ASSERT_FALSE(checked.alarm.has_value()) << checked.alarm->text;
  rig.source().prepare_mdi(std::move(checked));
}

// Runs until the channel has run and stands in idle again; the kinds of its events on the way.
std::vector<ChannelEventKind> run_back_to_idle(PanelRig& rig) {
  std::vector<ChannelEventKind> kinds;
  bool ran = false;
  EXPECT_TRUE(rig.run_until([&](const CycleOutput& o) {
    for (std::size_t e = 0; e < o.event_count; ++e) {
      kinds.push_back(o.events[e].kind);
    }
    ran = ran || o.state == ChannelState::running;
    return ran && o.state != ChannelState::running;
  }));
  return kinds;
}

TEST(OperatorPanel, MdiBlocksRunFromIdleAndEndWithoutAProgramEnd) {
  PanelRig rig;
  rig.load("G01 X100 F6000\nM30\n");
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  prepare_mdi(rig, "G01 X10 Z5 F6000");
  ASSERT_TRUE(rig.ctl().may_change_program());
  rig.ctl().request_mdi();
  const std::vector<ChannelEventKind> kinds = run_back_to_idle(rig);
  EXPECT_EQ(rig.step().state, ChannelState::idle);
  EXPECT_NEAR(rig.x(), 10.0, 1e-9);
  EXPECT_NEAR(rig.z(), 5.0, 1e-9);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), ChannelEventKind::mdi_end), 1);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), ChannelEventKind::program_end), 0);
  EXPECT_FALSE(rig.step().program_end);
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;

  // The next cycle start runs the channel's own program from its start.
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_NEAR(rig.x(), 100.0, 1e-9);
  EXPECT_EQ(rig.step().end_code, 30);
}

TEST(OperatorPanel, MdiIsIgnoredWhileTheProgramRuns) {
  PanelRig rig;
  rig.load("G01 X50 F6000\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.x() > 10.0; }));
  EXPECT_FALSE(rig.ctl().may_change_program());
  prepare_mdi(rig, "G00 Z30");
  rig.ctl().request_mdi();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_NEAR(rig.x(), 50.0, 1e-9);
  for (int i = 0; i < 200; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::idle);
  }
  EXPECT_NEAR(rig.z(), 0.0, 1e-9);  // the MDI block never ran
}

TEST(OperatorPanel, ACycleStartWaitsForAProgramBeingCheckedThenRunsIt) {
  PanelRig rig;
  rig.load("G01 X50 F6000\nM30\n");
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  rig.ctl().set_program_pending(true);
  rig.ctl().request_start();
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(rig.step().state, ChannelState::idle);
  }
  rig.source().adopt(
      interp::InterpreterSource::check(xz_channel(), "G01 Z20 F6000\nM30\n", "NEW.nc", false));
  rig.ctl().set_program_pending(false);
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.program_end; }));
  EXPECT_NEAR(rig.z(), 20.0, 1e-9);
  EXPECT_NEAR(rig.x(), 0.0, 1e-9);  // the program selected before never ran
}

TEST(OperatorPanel, TheRunEpochCountsRunStartsAndResetsSoThatStaleMdiIsDropped) {
  PanelRig rig;
  rig.load("G01 X10 F6000\nM30\n");
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  const std::uint64_t idle = rig.ctl().run_epoch();
  for (int i = 0; i < 50; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.ctl().run_epoch(), idle);  // standing changes nothing
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.ctl().run_epoch(), idle + 1);  // the start; the end is no new epoch
  rig.ctl().request_reset();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  EXPECT_EQ(rig.ctl().run_epoch(), idle + 2);
}

TEST(OperatorPanel, AResetDuringMdiBlocksLeavesTheChannelsProgramToRun) {
  PanelRig rig;
  rig.load("G01 Z10 F6000\nM30\n");
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  prepare_mdi(rig, "G01 X100 F600");
  rig.ctl().request_mdi();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput&) { return rig.x() > 1.0; }));
  rig.ctl().request_reset();
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  EXPECT_LT(rig.x(), 100.0);
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_NEAR(rig.z(), 10.0, 1e-9);
  EXPECT_EQ(rig.step().end_code, 30);
}

}  // namespace
}  // namespace mcnc::channel
