// G31.8 as a channel runs it: the move arms its axis's touch probe to latch every edge (the
// drive's continuous mode), goes on past each tooth, keeps each latched position by the drive's
// edge count, and ends at its end point or at the Q-th tooth (stopped there as a G31 is). The
// interpreter then reads the positions in #P.. and their count in #R; a variable the probe did
// not fill keeps what it held. Edges faster than the drive reports them are an alarm; a probe
// not on the moving axis's drive is refused before anything moves. Channel 1 programs X and Z;
// Z's drive has its probe on input 1, whose input goes on as Z passes each tooth going down.
#include "channel/coordination/skip_probe.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kZ = 1;

interp::InterpreterConfig xz_channel(std::size_t probe_axis) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[probe_axis].probe_input = 1;
  return c;
}

ChannelSetup xz_setup(std::size_t probe_axis) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.probe_inputs = {0, 0};
  s.probe_inputs[probe_axis] = 1;
  s.probe_arm_cycles = 50;
  return s;
}

// Axis nodes that follow valid setpoints at once; Z's drive arms its probe a cycle after it is
// asked and, while asked for every rising edge, counts each tooth Z passes going down, with the
// last one's position, as the axis node reports its drive's continuous latching.
class TeethRig : public ChannelRig {
 public:
  explicit TeethRig(std::vector<double> teeth, std::size_t probe_axis = kZ, bool read_ahead = false)
      : ChannelRig(xz_channel(probe_axis), alike_axes(kAxes, kDt), xz_setup(probe_axis),
                   read_ahead),
        teeth_(std::move(teeth)),
        feedback_(standing_feedback(kAxes, 1)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    const double before = feedback_[kZ].act;
    follow_setpoints(out, feedback_, kAxes);
    // Z's drive `lag` cycles behind its command, as a following error.
    z_commands_.push_back(feedback_[kZ].act);
    if (z_commands_.size() > lag + 1) {
      z_commands_.erase(z_commands_.begin());
    }
    feedback_[kZ].act = z_commands_.front();
    AxisFeedbackView& z = feedback_[kZ];
    if (out.setpoints[kZ].probe != ProbeArm::every_rising) {
      z.probe = ProbeSeen::off;
      z.probe_count = 0;
    } else if (z.probe == ProbeSeen::off) {
      z.probe = ProbeSeen::armed;
      ++armings;
    } else {
      for (const double t : teeth_) {
        if (before > t && z.act <= t) {
          ++z.probe_count;
          z.probe = ProbeSeen::latched;
          z.probe_pos = t;
        }
      }
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
  [[nodiscard]] const ChannelEvent* end_of_line(int line) const {
    for (const ChannelEvent& e : ends) {
      if (e.line == line) {
        return &e;
      }
    }
    return nullptr;
  }
  std::vector<ChannelEvent> ends;
  int armings = 0;
  std::size_t lag = 0;

 private:
  std::vector<double> teeth_;
  std::vector<double> z_commands_;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
};

// #503 = 7, then the G31.8 (line 3); Z to each stored position in turn (lines 4-6), X to twice
// the count (a diameter: X stands at the count, line 7), then X to #503 (line 8): what it held,
// unless the probe filled it.
std::string teeth_program(const std::string& g318) {
  return "G98 G00 X20 Z0\n#503=7\n" + g318 +
         "\nG00 Z[#500]\nG00 Z[#501]\nG00 Z[#502]\nG00 X[#1*2]\nG00 X[#503]\nM30\n";
}

TEST(ChannelMultiSkip, StoresEachToothAndRunsToTheEndBeforeQ) {
  TeethRig rig({-10.0, -12.0, -14.0});
  rig.load(teeth_program("G31.8 W-20 F1200 L1 P500 Q5 R1"));
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.armings, 1);
  const ChannelEvent* g318 = rig.end_of_line(3);
  ASSERT_NE(g318, nullptr);
  EXPECT_NEAR(g318->pos[kZ], -20.0, 1e-9);  // three teeth of five: on to the end point
  for (int line = 4; line <= 6; ++line) {
    const ChannelEvent* e = rig.end_of_line(line);
    ASSERT_NE(e, nullptr);
    EXPECT_NEAR(e->pos[kZ], -10.0 - 2.0 * (line - 4), 1e-9);  // #500-#502 at the teeth
  }
  const ChannelEvent* count = rig.end_of_line(7);
  ASSERT_NE(count, nullptr);
  EXPECT_NEAR(count->pos[0], 3.0, 1e-9);  // #1 = 3
  // #503 was not measured: the 7 it held (the check before the run filled it).
  EXPECT_NEAR(rig.x(), 3.5, 1e-9);
}

TEST(ChannelMultiSkip, ATeethNearTheEndPointCountsOnceTheAxisStandsThere) {
  // Z 10 cycles behind its command (0.2 mm at 20 mm/s): its last tooth, 0.05 mm before the end
  // point, passes after the command got there; the block waits for Z to stand at the end.
  TeethRig rig({-10.0, -12.0, -19.95});
  rig.lag = 10;
  rig.load("G98 G00 X20 Z0\nG31.8 W-20 F1200 L1 P500 Q5 R1\nG00 X[#1*2]\nG00 Z[#502]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.x(), 3.0, 1e-9);  // #1 = 3
  const ChannelEvent* e = rig.end_of_line(4);
  ASSERT_NE(e, nullptr);
  EXPECT_NEAR(e->pos[kZ], -19.95, 1e-9);  // #502
}

TEST(ChannelMultiSkip, TheQthToothStopsTheMove) {
  TeethRig rig({-10.0, -12.0, -14.0});
  rig.load(
      "G98 G00 X20 Z0\nG31.8 W-20 F1200 L1 P500 Q2 R1\nG00 X[#1*2]\n"
      "IF[#502NE#0]GOTO9\nG00 Z[#501]\nM30\nN9 #3000=1(FILLED)\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const ChannelEvent* g318 = rig.end_of_line(2);
  ASSERT_NE(g318, nullptr);
  // Stopped past the second tooth within a cycle's reaction and the braking from 20 mm/s
  // (0.45 mm, as a G31), before the third.
  EXPECT_LT(g318->pos[kZ], -12.0);
  EXPECT_GT(g318->pos[kZ], -12.45);
  EXPECT_NEAR(rig.x(), 2.0, 1e-9);    // #1 = 2
  EXPECT_NEAR(rig.z(), -12.0, 1e-9);  // #501 = -12
}

TEST(ChannelMultiSkip, EdgesFasterThanTheDriveReportsThemAreAnAlarm) {
  // Three teeth within 0.0002 mm, a cycle's travel being 0.02 mm: at least two come in one
  // cycle, and the drive holds one position.
  TeethRig rig({-10.0, -10.0001, -10.0002});
  rig.load(teeth_program("G31.8 W-20 F1200 L1 P500 Q5 R1"));
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{coordination::kAlarmEdgesLost}));
  EXPECT_NE(rig.alarm_text.find("edges on input 1 within one cycle"), std::string::npos)
      << rig.alarm_text;
  EXPECT_GT(rig.z(), -10.5);  // stopped there, not run on to -20
  EXPECT_EQ(rig.end_of_line(4), nullptr);
}

TEST(ChannelMultiSkip, AProbeOnAnotherAxisIsRefusedBeforeAnythingMoves) {
  TeethRig rig({-10.0}, 0);  // the probe on X's drive
  const auto alarm = rig.load_with_alarm(teeth_program("G31.8 W-20 F1200 L1 P500 Q5 R1"));
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_NE(alarm->text.find("axis Z"), std::string::npos) << alarm->text;
  rig.ctl().request_start();
  for (int i = 0; i < 100; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.z(), 0.0);
  EXPECT_EQ(rig.x(), 0.0);
}

TEST(ChannelMultiSkip, TheReadAheadThreadGetsThePositions) {
  // As in the channel process: the result crosses to the read-ahead thread with its resume.
  TeethRig rig({-10.0, -12.0, -14.0}, kZ, true);
  rig.load(teeth_program("G31.8 W-20 F1200 L1 P500 Q5 R1"));
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const ChannelEvent* e = rig.end_of_line(6);
  ASSERT_NE(e, nullptr);
  EXPECT_NEAR(e->pos[kZ], -14.0, 1e-9);
  EXPECT_NEAR(rig.x(), 3.5, 1e-9);
}

}  // namespace
}  // namespace mcnc::channel
