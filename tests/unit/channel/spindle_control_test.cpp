// C1 mode as a channel runs it (Dafeng M18/M17): the spindle taken over as the channel's C axis
// once it stands, C programmed from where it stands (within one turn), its setpoints going to
// the spindle in the spindle's degrees, and back to speed control with M17, at the program's
// end and on a reset. Channel 1 programs X, Z and C (the C axis of its spindle S1).
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
constexpr std::size_t kAxes = 3;  // X, Z, C
constexpr std::size_t kC = 2;

interp::InterpreterConfig xzc_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.spindles = 1;
  c.axes = {interp::AxisConfig{'X'}, interp::AxisConfig{'Z'}, interp::AxisConfig{'C'}};
  c.axes[kC].rotary = true;
  c.axes[kC].spindle = 1;
  return c;
}

motion::MotionConfig xzc_motion() {
  motion::MotionConfig c = alike_axes(kAxes, kDt);
  c.axes[kC] = motion::AxisDynamics{600.0, 3600.0, 180000.0};  // deg/s, deg/s^2, deg/s^3
  c.rapid_rate[kC] = 600.0;
  return c;
}

ChannelSetup xzc_setup() {
  ChannelSetup s{kAxes, {0.001, 0.001, 0.01}, kDt};
  s.channel_id = 1;
  s.spindle_count = 1;
  s.slots = {AxisSlot{'X', false, 1, 1}, AxisSlot{'Z', false, 1, 2}, AxisSlot{'C', false, 1, 3}};
  s.spindle_c_slot = kC;
  return s;
}

// Channel 1 with its axis nodes: X and Z follow valid setpoints; the spindle's node turns at
// the commanded speed (reached at 3600 deg/s^2) under speed control and takes the C setpoint
// under position control. Its feedback is both C's (slot 2) and the spindle's (after the axes).
class SpindleRig : public ChannelRig {
 public:
  SpindleRig() : ChannelRig(xzc_channel(), xzc_motion(), xzc_setup()) {
    feedback_.resize(kAxes + 1);
    for (auto& f : feedback_) {
      f.enabled = true;
      f.present = true;
      f.owner = 1;
    }
    spindle_ = 1000.0;  // where the spindle stands at power-on, degrees
  }

  const CycleOutput& step() override {
    feedback_[kC].cmd = feedback_[kC].act = spindle_;
    feedback_[kAxes] = feedback_[kC];
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    for (std::size_t a = 0; a < 2; ++a) {
      if (out.setpoints[a].valid) {
        feedback_[a].cmd = feedback_[a].act = out.setpoints[a].pos;
      }
    }
    if (out.spindle_position) {
      ++position_cycles;
      if (out.setpoints[kC].valid) {
        jump = std::max(jump, std::fabs(out.setpoints[kC].pos - spindle_));
        spindle_ = out.setpoints[kC].pos;
      }
      velocity_ = 0.0;
    } else {
      const double target = out.spindle_rpm * out.spindle_direction * 6.0;
      const double dv = std::clamp(target - velocity_, -3600.0 * kDt, 3600.0 * kDt);
      velocity_ += dv;
      spindle_ += velocity_ * kDt + drift;
    }
    max_speed = std::max(max_speed, std::fabs(velocity_));
    return out;
  }

  [[nodiscard]] double spindle() const { return spindle_; }
  [[nodiscard]] double velocity() const { return velocity_; }
  [[nodiscard]] double x() const { return feedback_[0].cmd; }

  int position_cycles = 0;  // cycles the spindle was under position control
  double jump = 0.0;        // the largest step between the spindle and its next C setpoint
  double max_speed = 0.0;   // deg/s under speed control
  double drift = 0.0;       // degrees per cycle the spindle creeps under speed control

 private:
  std::vector<AxisFeedbackView> feedback_;
  double spindle_ = 0.0;
  double velocity_ = 0.0;
  std::uint64_t cycle_ = 0;
};

TEST(SpindleControl, M18TakesTheStandingSpindleOverAsCAndM17GivesItBack) {
  SpindleRig rig;
  rig.load("M03 S100\nG04 X0.5\nM05\nM18\nG00 C90\nG01 X10 C180 F3600\nM17\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  // The spindle turned (100 rpm: 600 deg/s), stopped, and C moved it from where it stood: C
  // starts within the turn the spindle stands in, so C180 is that turn's 180 degrees.
  EXPECT_NEAR(rig.max_speed, 600.0, 1e-6);
  EXPECT_GT(rig.position_cycles, 0);
  const double turn = 360.0 * std::floor(rig.spindle() / 360.0);
  EXPECT_NEAR(rig.spindle() - turn, 180.0, 1e-9);
  EXPECT_DOUBLE_EQ(rig.x(), 10.0);
  // Taken over at rest: no step (C's setpoints start where the spindle stands).
  EXPECT_LE(rig.jump, 600.0 * kDt + 1e-9);
  EXPECT_FALSE(rig.step().spindle_position);  // M17: speed control, at rest
  EXPECT_DOUBLE_EQ(rig.velocity(), 0.0);
}

TEST(SpindleControl, M18WaitsUntilTheSpindleStands) {
  SpindleRig rig;
  // M05 then M18 at once: the spindle still coasts down from 600 deg/s (about 0.17 s).
  rig.load("M03 S100\nG04 X0.5\nM05\nM18\nG00 C0\nM30\n");
  rig.ctl().request_start();
  bool moving_under_position = false;
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) {
    moving_under_position = moving_under_position || (o.spindle_position && rig.velocity() != 0.0);
    return o.program_end || o.state == ChannelState::alarm;
  }));
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_FALSE(moving_under_position);
  EXPECT_NEAR(std::fmod(rig.spindle(), 360.0), 0.0, 1e-9);
}

// The interpreter finds the three mistakes of C1 mode when the program is loaded: the alarm
// names the line, and nothing of the program moves.
struct Mistake {
  const char* program;
  int line;
  const char* says;
};

TEST(SpindleControl, MistakesAreAlarmsAtTheLoadAndNothingMoves) {
  for (const Mistake& m : {Mistake{"G00 X10\nG00 C90\nM30\n", 2, "M18 switches it"},
                           Mistake{"M18\nG00 C45\nM03 S100\nM30\n", 3, "M17 returns it"},
                           Mistake{"M03 S100\nM18\nM30\n", 2, "stop it (M05)"},
                           Mistake{"G00 X10 M18\nM30\n", 1, "without axis words"}}) {
    SpindleRig rig;
    const double before = rig.spindle();
    const auto alarm = rig.load_with_alarm(m.program);
    ASSERT_TRUE(alarm.has_value()) << m.program;
    EXPECT_EQ(alarm->number, std::string(m.says) == "without axis words"
                                 ? interp::alarm::kMustBeAlone
                                 : interp::alarm::kSpindleControl);
    EXPECT_EQ(alarm->line, m.line);
    EXPECT_NE(alarm->text.find(m.says), std::string::npos) << alarm->text;
    rig.ctl().request_start();
    for (int i = 0; i < 200; ++i) {
      rig.step();
    }
    EXPECT_EQ(rig.alarms, std::vector<int>{alarm->number});
    EXPECT_DOUBLE_EQ(rig.x(), 0.0);
    EXPECT_DOUBLE_EQ(rig.spindle(), before);
    EXPECT_EQ(rig.max_speed, 0.0);
    EXPECT_EQ(rig.position_cycles, 0);
  }
}

TEST(SpindleControl, ASpindleThatDoesNotComeToRestIsAnAlarmAfterTenSeconds) {
  SpindleRig rig;
  rig.drift = 0.05;  // 50 deg/s, beyond C's in-position width per cycle
  rig.load("M18\nG00 C0\nM30\n");
  int cycles = 0;
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) {
    ++cycles;
    return o.program_end || o.state == ChannelState::alarm;
  }));
  ASSERT_EQ(rig.alarms, std::vector<int>{kAlarmSpindleNotAtRest});
  EXPECT_EQ(rig.alarm_lines.front(), 1);
  EXPECT_NEAR(cycles * kDt, 10.0, 0.01);
  EXPECT_EQ(rig.position_cycles, 0);
}

TEST(SpindleControl, TheProgramEndAndAResetEndPositionControl) {
  SpindleRig rig;
  rig.load("M18\nG00 C30\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_FALSE(rig.step().spindle_position);
  // Again, reset while C moves: the ramp down under position control, then speed control.
  rig.load("M18\nG01 C3000 F600\nM30\n");
  rig.ctl().request_start();
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) {
    return o.spindle_position && std::fmod(rig.spindle(), 360.0) > 100.0;
  }));
  rig.ctl().request_reset();
  // The reset ends in the cycle the ramp does; the channel is idle again at once (the axes
  // stayed enabled).
  ASSERT_TRUE(rig.run_until([&](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  const double stood = rig.spindle();
  EXPECT_FALSE(rig.step().spindle_position);
  EXPECT_DOUBLE_EQ(rig.spindle(), stood);
  EXPECT_LE(rig.jump, 600.0 * kDt + 1e-9);
}

TEST(SpindleControl, GskM14AndM15AreTheSameCodes) {
  interp::InterpreterConfig gsk = xzc_channel();
  gsk.dialect = interp::Dialect::gsk;
  interp::InterpreterSource source(gsk);
  ASSERT_FALSE(source.load("M14\nG00 C90\nM15\nM30\n", "T.nc").has_value());
  source.rewind(interp::AxisVector{});
  std::vector<std::string> ops;
  while (auto pulled = source.next()) {
    const auto* c = std::get_if<interp::Command>(&*pulled);
    ASSERT_NE(c, nullptr);
    if (c->op == interp::Op::end) {
      break;
    }
    if (c->op == interp::Op::spindle_mode) {
      ops.emplace_back(c->position_control ? "position" : "speed");
      EXPECT_TRUE(c->barrier);
    }
  }
  EXPECT_EQ(ops, (std::vector<std::string>{"position", "speed"}));
}

}  // namespace
}  // namespace mcnc::channel
