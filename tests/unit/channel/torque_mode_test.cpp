// G10 L14 P10-P12 as a channel runs them (decision 152): P10 holds an axis in torque mode, its
// setpoints carrying the torque and the motor speed (P11's, else param 5521) while the program
// goes on with the other axes; a block that moves that axis meanwhile is alarm 1263 at its line;
// P12 (or P10 α0) puts it back in position mode where the motor took it and the program goes
// on from there. Channel 1 programs X and Z; Z is a tailstock whose drive has torque mode; in
// torque mode its simulated node moves the motor towards the torque's sign until the centre
// (kContact) holds it, its command following the motor.
#include "channel/coordination/coordination_alarm.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr double kContact = -12.5;
constexpr double kPush = 0.01;  // mm per cycle the motor moves in torque mode until it touches

interp::InterpreterConfig xz_channel(bool torque_mode) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].torque_skip = true;
  c.axes[kZ].torque_mode = torque_mode;
  c.axes[kZ].torque_mode_speed = 300.0;  // param 5521
  return c;
}

ChannelSetup xz_setup(bool reset_leaves) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.torque_axes = {false, true};
  s.torque_mode_axes = {false, true};
  s.torque_mode_speeds = {0.0, 300.0};
  s.reset_leaves_torque_mode = reset_leaves;
  return s;
}

// What the channel sent Z in a cycle, with the line under way.
struct Sent {
  int line = 0;
  bool valid = false;
  double pos = 0.0;
  bool torque_mode = false;
  double torque = 0.0;
  double speed = 0.0;
  double torque_limit = 0.0;
};

class TorqueModeRig : public ChannelRig {
 public:
  explicit TorqueModeRig(bool torque_mode = true, bool reset_leaves = false)
      : ChannelRig(xz_channel(torque_mode), alike_axes(kAxes, kDt), xz_setup(reset_leaves)),
        feedback_(standing_feedback(kAxes, 1)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(out, feedback_, 1);  // X
    const CommandedAxis& sz = out.setpoints[kZ];
    AxisFeedbackView& z = feedback_[kZ];
    // Z's node: in torque mode (kept while the setpoints hold) the motor moves the way the
    // torque turns it until the centre holds it, and the command follows the motor; in
    // position mode it follows valid setpoints.
    in_torque_ = sz.valid ? sz.torque_mode : in_torque_;
    if (in_torque_) {
      const double step = sz.torque < 0.0 ? -kPush : sz.torque > 0.0 ? kPush : 0.0;
      z.act = std::max(z.act + step, kContact);
      z.cmd = z.act;
    } else if (sz.valid) {
      z.cmd = z.act = std::max(sz.pos, kContact);
    }
    sent.push_back(Sent{out.line, sz.valid, sz.pos, sz.torque_mode, sz.torque, sz.torque_speed,
                        sz.torque_limit});
    return out;
  }

  [[nodiscard]] double x() const { return feedback_[kX].act; }
  [[nodiscard]] double z() const { return feedback_[kZ].act; }
  [[nodiscard]] std::vector<Sent> during(int line) const {
    std::vector<Sent> s;
    std::copy_if(sent.begin(), sent.end(), std::back_inserter(s),
                 [&](const Sent& x) { return x.line == line; });
    return s;
  }

  std::vector<Sent> sent;

 private:
  std::vector<AxisFeedbackView> feedback_;
  bool in_torque_ = false;
  std::uint64_t cycle_ = 1;
};

TEST(ChannelTorqueMode, P10HoldsTheAxisWhileTheProgramGoesOnAndP12TakesItBackWhereItStands) {
  TorqueModeRig rig;
  rig.load(
      "G98 G00 X20 Z-10\n"  // 1
      "G10 L14 P10 Z-50\n"  // 2: pushed into the centre at -12.5 with 50 %, 300 rpm (5521)
      "G04 X0.5\n"          // 3: the push reaches the centre (2.5 mm at 0.01 mm a cycle)
      "G01 X10 F600\n"      // 4: X cuts while Z pushes
      "G10 L14 P12 Z-1\n"   // 5: back to position mode, no torque limit
      "G01 W2 F600\n"       // 6: from where the centre held it
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  // Before P10 nothing of torque mode goes out.
  for (const Sent& s : rig.during(1)) {
    EXPECT_FALSE(s.torque_mode);
  }
  // From P10 to P12: torque mode with P10's torque and param 5521's speed, every cycle.
  for (const int line : {3, 4}) {
    const std::vector<Sent> held = rig.during(line);
    ASSERT_FALSE(held.empty()) << line;
    for (const Sent& s : held) {
      EXPECT_TRUE(s.torque_mode) << line;
      EXPECT_EQ(s.torque, -50.0) << line;
      EXPECT_EQ(s.speed, 300.0) << line;
    }
  }
  // X cut to 10 while Z stood against the centre.
  const std::vector<Sent> cut = rig.during(4);
  EXPECT_NEAR(cut.back().pos, kContact, 1e-12);
  EXPECT_NEAR(rig.x(), 5.0, 1e-9);  // X in diameter: radius 5
  // P12: position mode at the reached position, no jump; Z's move goes on from there.
  const auto back = std::find_if(rig.sent.begin(), rig.sent.end(),
                                 [](const Sent& s) { return s.line >= 5 && !s.torque_mode; });
  ASSERT_NE(back, rig.sent.end());
  EXPECT_NEAR(back->pos, kContact, 1e-12);
  for (const Sent& s : rig.during(6)) {
    EXPECT_FALSE(s.torque_mode);
    EXPECT_GE(s.pos, kContact - 1e-12);
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  EXPECT_NEAR(rig.z(), kContact + 2.0, 1e-9);
}

TEST(ChannelTorqueMode, P11SetsTheSpeedAndP12ItsTorqueLimit) {
  TorqueModeRig rig;
  rig.load(
      "G98 G00 X20 Z-10\n"  // 1
      "G10 L14 P11 Z120\n"  // 2
      "G10 L14 P10 Z-30\n"  // 3
      "G04 X0.5\n"          // 4
      "G10 L14 P12 Z40\n"   // 5: back, limited to 40 %
      "G04 X0.1\n"          // 6
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const std::vector<Sent> held = rig.during(4);
  ASSERT_FALSE(held.empty());
  EXPECT_EQ(held.back().speed, 120.0);
  EXPECT_EQ(held.back().torque, -30.0);
  const std::vector<Sent> after = rig.during(6);
  ASSERT_FALSE(after.empty());
  EXPECT_FALSE(after.back().torque_mode);
  EXPECT_EQ(after.back().torque_limit, 40.0);
  EXPECT_NEAR(after.back().pos, kContact, 1e-12);
}

TEST(ChannelTorqueMode, ABlockThatMovesTheAxisInTorqueModeIsAnAlarmAtItsLine) {
  TorqueModeRig rig;
  rig.load(
      "G98 G00 X20 Z-10\n"   // 1
      "G10 L14 P10 Z-50\n"   // 2
      "G04 X0.5\n"           // 3
      "G01 X10 Z-20 F600\n"  // 4: moves Z: 1263, nothing of it moves
      "M30\n");
  ASSERT_FALSE(rig.run_to_end() && rig.alarms.empty());
  ASSERT_EQ(rig.alarms.size(), 1U);
  EXPECT_EQ(rig.alarms[0], coordination::kAlarmTorqueMode);
  EXPECT_EQ(rig.alarm_lines[0], 4);
  EXPECT_NE(rig.alarm_text.find("torque mode"), std::string::npos) << rig.alarm_text;
  EXPECT_NEAR(rig.x(), 10.0, 1e-9);  // X stayed at radius 10 too
  EXPECT_NEAR(rig.z(), kContact, 1e-9);
  EXPECT_TRUE(rig.sent.back().torque_mode);  // the tailstock keeps holding the part
}

TEST(ChannelTorqueMode, AnAxisWithoutTorqueModeIsRefusedBeforeTheProgramRuns) {
  TorqueModeRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z-10\nG10 L14 P10 Z-50\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("G10 L14 P10: the drive of axis Z has no torque mode"),
            std::string::npos)
      << alarm->text;
}

// Param 5520.1: 0 keeps the torque through a reset, 1 takes the axis back where it stands.
TEST(ChannelTorqueMode, AResetLeavesTorqueModeOnlyWithParam5520Bit1) {
  for (const bool leaves : {false, true}) {
    TorqueModeRig rig(true, leaves);
    rig.load("G98 G00 X20 Z-10\nG10 L14 P10 Z-50\nG04 X10\nM30\n");
    rig.ctl().request_start();
    ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.line == 3; }));
    for (int i = 0; i < 400; ++i) {
      rig.step();
    }
    rig.ctl().request_reset();
    for (int i = 0; i < 50; ++i) {
      rig.step();
    }
    EXPECT_EQ(rig.sent.back().torque_mode, !leaves) << leaves;
    EXPECT_NEAR(rig.z(), kContact, 1e-9) << leaves;
    if (leaves) {
      EXPECT_NEAR(rig.sent.back().pos, kContact, 1e-12);
    }
  }
}

}  // namespace
}  // namespace mcnc::channel
