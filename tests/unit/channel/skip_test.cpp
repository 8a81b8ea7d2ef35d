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
    for (std::size_t e = 0; e < out.event_count; ++e) {
      if (out.events[e].kind == ChannelEventKind::block_ended) {
        ends.push_back(out.events[e]);
      }
    }
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

}  // namespace
}  // namespace mcnc::channel
