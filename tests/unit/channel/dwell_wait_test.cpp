// G04 I and G04 PS as a channel runs them: the block waits, with the read-ahead stopped, until
// the PLC's input (its port's bit in the PLC status) is in the wanted state or the spindle's
// actual speed (its axis node's feedback) is within param 1057 of the programmed one; a dwell
// time ends it as well; the time-out is an alarm before anything after the block moves.
// Channel 1 programs X and Z and has spindle S1, whose node turns at the commanded speed
// reached at 6000 deg/s^2 (1000 rpm/s).
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr int kPort = 2;          // G04 I2 reads the PLC's signal 5
constexpr int kSignal = 5;

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.input_ports = {kPort};
  return c;
}

ChannelSetup xz_setup() {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.spindle_count = 1;
  s.input_ports = std::vector<int>(kPort + 1, -1);
  s.input_ports[kPort] = kSignal;
  s.speed_arrival_rpm = 10.0;
  s.speed_arrival_timeout_s = 5.0;
  return s;
}

class WaitRig : public ChannelRig {
 public:
  WaitRig() : ChannelRig(xz_channel(), alike_axes(kAxes, kDt), xz_setup()) {
    feedback_.resize(kAxes + 1);
    for (auto& f : feedback_) {
      f.enabled = true;
      f.present = true;
      f.owner = 1;
    }
  }

  const CycleOutput& step() override {
    // The PLC input comes on at cycle `input_on_at` (its status stamped the cycle before).
    ctl().set_plc_inputs(cycle_ >= input_on_at ? 1ULL << kSignal : 0);
    feedback_[kAxes].vel = velocity_;
    const CycleOutput& out = channel_cycle(cycle_, feedback_);
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (out.setpoints[a].valid) {
        if (feedback_[a].act != out.setpoints[a].pos && first_move == 0) {
          first_move = cycle_;
        }
        feedback_[a].cmd = feedback_[a].act = out.setpoints[a].pos;
      }
    }
    const double target = out.spindle_rpm * out.spindle_direction * 6.0 * reach;
    velocity_ += std::clamp(target - velocity_, -6000.0 * kDt, 6000.0 * kDt);
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::block_ended) {
        ended[out.events[e].line] = cycle_;
      }
    }
    ++cycle_;
    return out;
  }

  [[nodiscard]] double rpm() const { return std::fabs(velocity_) / 6.0; }
  std::uint64_t input_on_at = ~std::uint64_t{0};
  double reach = 1.0;  // the fraction of the commanded speed the spindle reaches
  std::uint64_t first_move = 0;
  std::array<std::uint64_t, 16> ended{};
  std::uint64_t cycle_ = 1;
  std::vector<AxisFeedbackView> feedback_;
  double velocity_ = 0.0;
};

TEST(ChannelDwellWait, G04IEndsWhenThePlcInputComesOnAndNothingMovesBefore) {
  WaitRig rig;
  rig.input_on_at = 400;
  rig.load("G04 I2 J5\nG98 G01 W-1 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.ended[1], 400u);  // the first cycle whose PLC status shows it
  EXPECT_GT(rig.first_move, 400u);
  EXPECT_NEAR(rig.feedback_[1].act, -1.0, 1e-9);
}

TEST(ChannelDwellWait, G04IOffWaitsForTheInputToGoOffAndKForItsWidth) {
  WaitRig rig;
  rig.input_on_at = 0;  // on from the start
  rig.load("G04 I-2 J0.3\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1u);
  EXPECT_EQ(rig.alarms[0], kAlarmInputTimeout);
  EXPECT_EQ(rig.alarm_lines[0], 1);

  WaitRig width;
  width.input_on_at = 100;
  width.load("G04 I2 K0.2\nM30\n");
  ASSERT_TRUE(width.run_to_end());
  EXPECT_TRUE(width.alarms.empty()) << width.alarm_text;
  EXPECT_EQ(width.ended[1], 299u);  // on for 200 cycles in a row
}

TEST(ChannelDwellWait, G04ITimesOutAsAnAlarmBeforeTheNextBlockMoves) {
  WaitRig rig;
  rig.load("G04 I2 J0.25\nG98 G01 W-1 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1u);
  EXPECT_EQ(rig.alarms[0], kAlarmInputTimeout);
  EXPECT_EQ(rig.alarm_lines[0], 1);
  EXPECT_EQ(rig.first_move, 0u);  // nothing moved
  EXPECT_NE(rig.alarm_text.find("input 2 not on within 0.250 s"), std::string::npos)
      << rig.alarm_text;
}

TEST(ChannelDwellWait, G04IWithADwellTimeEndsAtTheTimeWithoutAnAlarm) {
  WaitRig rig;
  rig.load("G04 I2 J5 X0.15\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.ended[1], 150u);
}

TEST(ChannelDwellWait, G04PsEndsWhenTheActualSpeedIsReached) {
  WaitRig rig;
  rig.load("M03 S3000\nG04 PS3000\nG98 G01 W-1 F600\nM05\nG04 PS0\nM30\n");
  std::uint64_t reached = 0;
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) {
    if (reached == 0 && rig.rpm() >= 2990.0) {
      reached = rig.cycle_;
    }
    return o.program_end || o.state == ChannelState::alarm;
  }));
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  // 1000 rpm/s: 2990 rpm after ~2.99 s; the channel sees the speed a cycle later.
  ASSERT_GT(reached, 2900u);
  EXPECT_GE(rig.ended[2], reached);
  EXPECT_LE(rig.ended[2], reached + 2);
  EXPECT_GT(rig.first_move, rig.ended[2]);
  // G04 PS0 waits for the stop: 3 s down, within 10 rpm.
  EXPECT_GT(rig.ended[5], rig.ended[4] + 2900);
  EXPECT_LE(rig.rpm(), 10.0);
}

TEST(ChannelDwellWait, G04PsNotReachedWithinParam1059IsAnAlarm) {
  WaitRig rig;
  rig.reach = 0.9;  // a spindle that stays at 2700 rpm
  rig.load("M03 S3000\nG04 PS3000\nG98 G01 W-1 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1u);
  EXPECT_EQ(rig.alarms[0], kAlarmSpeedTimeout);
  EXPECT_EQ(rig.alarm_lines[0], 2);
  EXPECT_EQ(rig.first_move, 0u);
}

TEST(ChannelDwellWait, AnInputWithoutAPortIsRefusedBeforeTheProgramRuns) {
  WaitRig rig;
  const auto alarm = rig.load_with_alarm("G00 U1\nG04 I7 J1\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kInputPort);
  EXPECT_EQ(alarm->line, 2);
  const auto spindle = rig.load_with_alarm("G04 PS2=100\nM30\n");
  ASSERT_TRUE(spindle.has_value());
  EXPECT_EQ(spindle->number, interp::alarm::kNoSuchSpindle);
}

}  // namespace
}  // namespace mcnc::channel
