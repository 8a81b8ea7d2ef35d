// G31 as a channel runs it: the move waits for the touch probes on its input to arm, stops at
// the planner's reset deceleration once a probe latched, its block ends where it stopped, and
// the interpreter reads the latched position (#5061..) and R's flag; without a signal the move
// runs to its end. Channel 1 programs X and Z; Z's drive has a probe on input 13 whose input
// goes on where Z passes -12.5.
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kZ = 1;
constexpr double kTrigger = -12.5;

interp::InterpreterConfig xz_channel(bool probe) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].probe_input = probe ? 13 : 0;
  return c;
}

ChannelSetup xz_setup(bool probe) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.probe_inputs = {0, probe ? 13 : 0};
  s.probe_arm_cycles = 50;
  return s;
}

// The block ends of a cycle's output, added to `ends`.
void note_ends(const CycleOutput& out, std::vector<ChannelEvent>& ends) {
  for (std::size_t e = 0; e < out.event_count; ++e) {
    if (out.events[e].kind == ChannelEventKind::block_ended) {
      ends.push_back(out.events[e]);
    }
  }
}

// Axis nodes that follow valid setpoints at once; Z's drive arms its probe a cycle after it is
// asked (the feedback of the next cycle), latches kTrigger where Z passes it on the way down,
// and reports nothing once the probe is no longer asked for. `arms` false: a probe that never
// reports itself armed.
class SkipRig : public ChannelRig {
 public:
  explicit SkipRig(bool probe = true, bool arms = true)
      : ChannelRig(xz_channel(probe), alike_axes(kAxes, kDt), xz_setup(probe)), arms_(arms) {
    feedback_.resize(kAxes);
    for (auto& f : feedback_) {
      f.enabled = true;
      f.present = true;
      f.owner = 1;
    }
  }

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    const double before = feedback_[kZ].act;
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (out.setpoints[a].valid) {
        feedback_[a].cmd = feedback_[a].act = out.setpoints[a].pos;
      }
    }
    AxisFeedbackView& z = feedback_[kZ];
    if (out.setpoints[kZ].probe == ProbeArm::off || !arms_) {
      z.probe = ProbeSeen::off;
    } else if (z.probe == ProbeSeen::off) {
      z.probe = ProbeSeen::armed;
      ++armings;
    } else if (z.probe == ProbeSeen::armed && out.setpoints[kZ].probe == ProbeArm::rising &&
               before > kTrigger && z.act <= kTrigger) {
      z.probe = ProbeSeen::latched;
      z.probe_pos = kTrigger;
      latched_at_speed = std::fabs(out.setpoints[kZ].vel);
    }
    if (out.setpoints[kZ].probe != ProbeArm::off && z.act < lowest_armed) {
      lowest_armed = z.act;
    }
    note_ends(out, ends);
    return out;
  }

  [[nodiscard]] double z() const { return feedback_[kZ].act; }
  [[nodiscard]] double x() const { return feedback_[0].act; }
  std::vector<ChannelEvent> ends;
  int armings = 0;
  double latched_at_speed = 0.0;
  double lowest_armed = 1e9;

 private:
  bool arms_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
};

const ChannelEvent* end_of_line(const std::vector<ChannelEvent>& ends, int line) {
  for (const ChannelEvent& e : ends) {
    if (e.line == line) {
      return &e;
    }
  }
  return nullptr;
}

TEST(ChannelSkip, TheMoveStopsAtTheSignalAndTheProgramReadsTheLatchedPosition) {
  SkipRig rig;
  // #5062 is Z's skip position; R100 the flag. The last move goes 2 mm above it.
  rig.load("G98 G00 X20 Z0\nG31 W-50 F1200 L13 R100\nG00 W0.001\nG00 Z[#5062+#100*2]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.armings, 1);
  // Stopped past the trigger within the reaction (a cycle, 0.02 mm) and the jerk-limited
  // braking from 20 mm/s at 1000 mm/s^2 and 50000 mm/s^3 (v^2/2a + v a/2j = 0.4 mm), far from
  // the programmed end (-50).
  const ChannelEvent* g31 = end_of_line(rig.ends, 2);
  ASSERT_NE(g31, nullptr);
  EXPECT_LT(g31->pos[kZ], kTrigger);
  EXPECT_GT(g31->pos[kZ], kTrigger - 0.45);
  EXPECT_GT(rig.latched_at_speed, 19.0);  // the move was at its feed when the probe latched
  // The next block starts where the axes stopped: W0.001 from there.
  const ChannelEvent* after = end_of_line(rig.ends, 3);
  ASSERT_NE(after, nullptr);
  EXPECT_NEAR(after->pos[kZ], g31->pos[kZ] + 0.001, 1e-9);
  // #5062 = -12.5 and #100 = 1: Z ends at -10.5.
  EXPECT_NEAR(rig.z(), kTrigger + 2.0, 1e-9);
  EXPECT_NEAR(rig.x(), 10.0, 1e-9);
}

TEST(ChannelSkip, WithoutTheSignalTheMoveRunsToItsEnd) {
  SkipRig rig;
  rig.load("G98 G00 X20 Z0\nG31 W-5 F1200 L13 R100\nG00 Z[#5062+#100*2]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const ChannelEvent* g31 = end_of_line(rig.ends, 2);
  ASSERT_NE(g31, nullptr);
  EXPECT_NEAR(g31->pos[kZ], -5.0, 1e-9);
  EXPECT_NEAR(rig.z(), -5.0, 1e-9);  // #5062 = the end point, #100 = 0
}

TEST(ChannelSkip, TheMoveStartsOnlyOnceTheProbeIsArmed) {
  SkipRig rig(true, false);
  rig.load("G98 G00 X20 Z0\nG31 W-50 F1200 L13\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1u);
  EXPECT_EQ(rig.alarms[0], kAlarmProbeNotArmed);
  EXPECT_EQ(rig.alarm_lines[0], 2);
  EXPECT_NEAR(rig.z(), 0.0, 1e-12);  // nothing moved
}

TEST(ChannelSkip, AnInputNoProbeIsWiredToIsRefusedBeforeTheProgramRuns) {
  SkipRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG31 W-50 F1200 L13\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
}

// G31 P2 (the PLC's G0014.1, decision 92): the PLC's input bit 5 is skip signal 2; the PLC's
// status shows it on a cycle after Z's feedback passed kTrigger (the status of cycle N-1), or
// from the start (`on_from_start`).
class SignalRig : public ChannelRig {
 public:
  static constexpr int kBit = 5;
  explicit SignalRig(bool wired = true, bool on_from_start = false)
      : ChannelRig(signal_channel(wired), alike_axes(kAxes, kDt), signal_setup(wired)),
        on_from_start_(on_from_start),
        feedback_(standing_feedback(kAxes, 1)) {}

  const CycleOutput& step() override {
    const bool on = on_from_start_ || feedback_[kZ].act <= kTrigger;
    ctl().set_plc_inputs(on ? std::uint64_t{1} << kBit : 0);
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(out, feedback_, kAxes);
    for (std::size_t a = 0; a < kAxes; ++a) {
      probe_asked = probe_asked || out.setpoints[a].probe != ProbeArm::off;
    }
    note_ends(out, ends);
    return out;
  }

  [[nodiscard]] double z() const { return feedback_[kZ].act; }
  std::vector<ChannelEvent> ends;
  bool probe_asked = false;

 private:
  static interp::InterpreterConfig signal_channel(bool wired) {
    interp::InterpreterConfig c = xz_channel(false);
    c.plc = true;
    c.skip_signals[1] = wired;
    return c;
  }
  static ChannelSetup signal_setup(bool wired) {
    ChannelSetup s = xz_setup(false);
    s.plc = true;
    s.skip_signals[1] = wired ? kBit : -1;
    return s;
  }
  bool on_from_start_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
};

TEST(ChannelSkip, G31PStopsWhereThePlcSignalIsSeenAndTheProgramReadsThatPosition) {
  SignalRig rig;
  rig.load("G98 G00 X20 Z0\nG31 W-50 F1200 P2 R100\nG00 W0.001\nG00 Z[#5062+#100*2]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_FALSE(rig.probe_asked);  // no drive's touch probe is armed for a PLC signal
  const ChannelEvent* g31 = end_of_line(rig.ends, 2);
  ASSERT_NE(g31, nullptr);
  // Stopped past the trigger within the PLC's cycle of delay (a cycle at 20 mm/s: 0.02 mm), the
  // channel's and the braking (0.4 mm, as for a probe), far from the end (-50).
  EXPECT_LT(g31->pos[kZ], kTrigger);
  EXPECT_GT(g31->pos[kZ], kTrigger - 0.5);
  const ChannelEvent* after = end_of_line(rig.ends, 3);
  ASSERT_NE(after, nullptr);
  EXPECT_NEAR(after->pos[kZ], g31->pos[kZ] + 0.001, 1e-9);
  // #5062 is where Z stood when the signal was seen: past the trigger by at most two cycles'
  // travel (0.04 mm), before the axis stopped. #100 = 1.
  EXPECT_LE(rig.z(), kTrigger + 2.0);
  EXPECT_GE(rig.z(), kTrigger + 2.0 - 0.041);
  EXPECT_GT(rig.z() - 2.0, g31->pos[kZ]);
}

TEST(ChannelSkip, G31PWithoutTheSignalRunsToItsEnd) {
  SignalRig rig;
  rig.load("G98 G00 X20 Z0\nG31 W-5 F1200 P2 R100\nG00 Z[#5062+#100*2]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.z(), -5.0, 1e-9);  // #5062 = the end point, #100 = 0
}

TEST(ChannelSkip, G31PWithTheSignalAlreadyOnDoesNotMove) {
  SignalRig rig(true, true);
  rig.load("G98 G00 X20 Z0\nG31 W-50 F1200 P2\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1u);
  EXPECT_EQ(rig.alarms[0], kAlarmProbeNotArmed);
  EXPECT_EQ(rig.alarm_lines[0], 2);
  EXPECT_NEAR(rig.z(), 0.0, 1e-12);
}

TEST(ChannelSkip, G31POfASignalThePlcLacksIsRefusedBeforeTheProgramRuns) {
  SignalRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG31 W-50 F1200 P2\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
}

}  // namespace
}  // namespace mcnc::channel
