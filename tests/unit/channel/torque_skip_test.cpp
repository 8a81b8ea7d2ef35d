// G160 as a channel runs it (decision 100): the axis's torque limit and skip deviation go out
// with its setpoints from the block on, the move starts once the axis node reports the torque
// skip armed, stops at the planner's reset deceleration once it latched, and the program reads
// the latched position (#5061..). The limit stays after the skip, while other axes move, until
// a move of that axis (G00/G01, or G160 P-1) cancels it. Channel 1 programs X and Z; Z's drive
// takes a torque limit, and its load meets a contact at -12.5 coming from above.
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
constexpr std::size_t kZ = 1;
constexpr double kContact = -12.5;

interp::InterpreterConfig xz_channel(bool torque) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].torque_skip = torque;
  return c;
}

ChannelSetup xz_setup(bool torque) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.probe_inputs = {0, 0};
  s.torque_axes = {false, torque};
  s.probe_arm_cycles = 50;
  return s;
}

// What the channel sent one axis in a cycle, with the block under way.
struct Sent {
  int line = 0;
  double pos = 0.0;
  double torque_limit = 0.0;
  double skip_deviation = 0.0;
  ProbeArm probe = ProbeArm::off;
};

// Axis nodes that follow valid setpoints at once, except that Z's load stands at the contact.
// Z's node reports the torque skip armed a cycle after it is asked with a limit, and latched
// (at the contact) once the setpoint is beyond the contact by more than the deviation: the
// torque is at the limit there.
class TorqueRig : public ChannelRig {
 public:
  explicit TorqueRig(bool torque = true)
      : ChannelRig(xz_channel(torque), alike_axes(kAxes, kDt), xz_setup(torque)),
        feedback_(standing_feedback(kAxes, 1)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(out, feedback_, kAxes);
    AxisFeedbackView& z = feedback_[kZ];
    const CommandedAxis& sz = out.setpoints[kZ];
    z.act = std::max(z.cmd, kContact);
    if (sz.probe != ProbeArm::torque || sz.torque_limit <= 0.0) {
      z.probe = ProbeSeen::off;
    } else if (z.probe == ProbeSeen::off) {
      z.probe = ProbeSeen::armed;
      ++armings;
    } else if (z.probe == ProbeSeen::armed && z.act - z.cmd > sz.skip_deviation) {
      z.probe = ProbeSeen::latched;
      z.probe_pos = z.act;
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      sent[a].push_back(Sent{out.line, out.setpoints[a].pos, out.setpoints[a].torque_limit,
                             out.setpoints[a].skip_deviation, out.setpoints[a].probe});
    }
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::block_ended) {
        ends.push_back(out.events[e]);
      }
    }
    return out;
  }

  [[nodiscard]] double z() const { return feedback_[kZ].act; }
  [[nodiscard]] double z_cmd() const { return feedback_[kZ].cmd; }
  // What axis `a` was sent while line `line` ran.
  [[nodiscard]] std::vector<Sent> during(std::size_t a, int line) const {
    std::vector<Sent> s;
    std::copy_if(sent[a].begin(), sent[a].end(), std::back_inserter(s),
                 [&](const Sent& x) { return x.line == line; });
    return s;
  }
  [[nodiscard]] const ChannelEvent* end_of(int line) const {
    for (const ChannelEvent& e : ends) {
      if (e.line == line) {
        return &e;
      }
    }
    return nullptr;
  }

  std::vector<ChannelEvent> ends;
  std::array<std::vector<Sent>, kAxes> sent;
  int armings = 0;

 private:
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
};

TEST(ChannelTorqueSkip, PressesSkipsAndKeepsTheLimitUntilAMoveOfTheAxis) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"         // 1
      "G160 W-50 P50 Q1 F600\n"  // 2: presses against the contact at -12.5
      "G01 X10 F600\n"           // 3: X cuts, Z keeps pressing
      "#100=#5062\n"             // 4
      "G01 Z[#100+5] F600\n"     // 5: Z's move cancels the limit
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.armings, 1);
  // No limit before the G160 arms: the limit comes with its request for the torque skip, Z
  // still standing. From then on 50 % with Q = 1 mm.
  const auto limited = std::find_if(rig.sent[kZ].begin(), rig.sent[kZ].end(),
                                    [](const Sent& s) { return s.torque_limit != 0.0; });
  ASSERT_NE(limited, rig.sent[kZ].end());
  EXPECT_EQ(limited->probe, ProbeArm::torque);
  EXPECT_EQ(limited->pos, 0.0);
  const std::vector<Sent> g160 = rig.during(kZ, 2);
  ASSERT_FALSE(g160.empty());
  EXPECT_TRUE(std::all_of(g160.begin(), g160.end(), [](const Sent& s) {
    return s.torque_limit == 50.0 && s.skip_deviation == 1.0;
  }));
  EXPECT_EQ(g160.front().probe, ProbeArm::torque);
  // Stopped past contact + Q within the reaction (a cycle at 10 mm/s) and the braking (v^2/2a
  // + v a/2j: 0.15 mm), far from its end at -50.
  const ChannelEvent* skipped = rig.end_of(2);
  ASSERT_NE(skipped, nullptr);
  EXPECT_LT(skipped->pos[kZ], kContact - 1.0);
  EXPECT_GT(skipped->pos[kZ], kContact - 1.0 - 0.2);
  // X's cut: Z stays where it stopped, pressed with the limit; X never limited.
  const std::vector<Sent> cut = rig.during(kZ, 3);
  ASSERT_FALSE(cut.empty());
  for (const Sent& s : cut) {
    EXPECT_EQ(s.torque_limit, 50.0);
    EXPECT_EQ(s.skip_deviation, 1.0);
    EXPECT_EQ(s.probe, ProbeArm::off);
    EXPECT_NEAR(s.pos, skipped->pos[kZ], 1e-12);
  }
  for (const Sent& s : rig.sent[0]) {
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  // #5062 is the contact: Z's move to 5 above it cancels the limit from its start.
  const std::vector<Sent> away = rig.during(kZ, 5);
  ASSERT_FALSE(away.empty());
  for (const Sent& s : away) {
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  EXPECT_NEAR(rig.z(), kContact + 5.0, 1e-9);
}

TEST(ChannelTorqueSkip, PMinusOneMovesWithTheLimitCancelled) {
  TorqueRig rig;
  rig.load("G98 G00 X20 Z0\nG160 W-50 P50 Q1 F600\nG160 Z0 P-1 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const std::vector<Sent> back = rig.during(kZ, 3);
  ASSERT_FALSE(back.empty());
  for (const Sent& s : back) {
    EXPECT_EQ(s.torque_limit, 0.0);
    EXPECT_EQ(s.probe, ProbeArm::off);
  }
  EXPECT_EQ(rig.armings, 1);
  EXPECT_NEAR(rig.z(), 0.0, 1e-9);
}

TEST(ChannelTorqueSkip, WithoutTheContactTheMoveRunsToItsEnd) {
  TorqueRig rig;
  rig.load("G98 G00 X20 Z0\nG160 W-5 P50 Q1 F600\nG00 Z[#5062-1]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const ChannelEvent* g160 = rig.end_of(2);
  ASSERT_NE(g160, nullptr);
  EXPECT_NEAR(g160->pos[kZ], -5.0, 1e-9);
  EXPECT_NEAR(rig.z(), -6.0, 1e-9);  // #5062 = the end point
}

TEST(ChannelTorqueSkip, AnAxisWhoseDriveTakesNoLimitIsRefusedBeforeTheProgramRuns) {
  TorqueRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG160 W-50 P50 Q1 F600\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("torque_skip"), std::string::npos) << alarm->text;
}

TEST(ChannelTorqueSkip, PMinusOneNeedsNoTorqueMapping) {
  TorqueRig rig(false);
  rig.load("G98 G00 X20 Z0\nG160 W-5 P-1 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.z(), -5.0, 1e-9);
}

}  // namespace
}  // namespace mcnc::channel
