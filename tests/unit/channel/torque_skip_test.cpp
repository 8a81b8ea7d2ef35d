// G160 as a channel runs it (decision 100): the axis's torque limit and skip deviation go out
// with its setpoints from the block on, the move starts once the axis node reports the torque
// skip armed, stops at the planner's reset deceleration once it latched, and the program reads
// the latched position (#5061..). The limit stays after the skip, while other axes move, until
// a move of that axis (G00/G01, or G160 P-1) cancels it. G31 P98/P99 (decision 116) go the same
// way with each moving axis's load ratio as its limit and no deviation, P99 also on the touch
// probes of its input. Channel 1 programs X and Z; Z's drive takes a torque limit (its load
// ratio of param 5511 30 %), and its load meets a contact at -12.5 coming from above; X's drive
// has its touch probe on input 13, which a sensor switches on once Z passes `sensor_at`.
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr double kContact = -12.5;

interp::InterpreterConfig xz_channel(bool torque) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].torque_skip = torque;
  c.axes[kZ].skip_load = 30.0;  // param 5511
  c.axes[kX].probe_input = 13;
  return c;
}

ChannelSetup xz_setup(bool torque) {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.probe_inputs = {13, 0};
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
// torque is at the limit there. X's probe arms a cycle after it is asked and latches where Z
// passes the sensor.
class TorqueRig : public ChannelRig {
 public:
  explicit TorqueRig(bool torque = true,
                     double sensor_at = -std::numeric_limits<double>::infinity())
      : ChannelRig(xz_channel(torque), alike_axes(kAxes, kDt), xz_setup(torque)),
        torque_(torque),
        feedback_(standing_feedback(kAxes, 1)),
        sensor_at_(sensor_at) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    follow_setpoints(out, feedback_, kAxes);
    AxisFeedbackView& z = feedback_[kZ];
    const CommandedAxis& sz = out.setpoints[kZ];
    z.act = std::max(z.cmd, kContact);
    // Z's drive reports its load: at the limit (300 % without one) while held at the contact,
    // else 10 % the way it is commanded.
    z.load_known = torque_;
    z.load = z.act > z.cmd ? -(sz.torque_limit > 0.0 ? sz.torque_limit : 300.0)
                           : (sz.vel < 0.0   ? -10.0
                              : sz.vel > 0.0 ? 10.0
                                             : 0.0);
    if (sz.probe != ProbeArm::torque || sz.torque_limit <= 0.0) {
      z.probe = ProbeSeen::off;
    } else if (z.probe == ProbeSeen::off) {
      z.probe = ProbeSeen::armed;
      ++armings;
    } else if (z.probe == ProbeSeen::armed && z.act - z.cmd > sz.skip_deviation) {
      z.probe = ProbeSeen::latched;
      z.probe_pos = z.act;
    }
    AxisFeedbackView& x = feedback_[kX];
    if (out.setpoints[kX].probe != ProbeArm::rising) {
      x.probe = ProbeSeen::off;
    } else if (x.probe == ProbeSeen::off) {
      x.probe = ProbeSeen::armed;
    } else if (x.probe == ProbeSeen::armed && z.act <= sensor_at_) {
      x.probe = ProbeSeen::latched;
      x.probe_pos = x.act;
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

  [[nodiscard]] double x() const { return feedback_[kX].act; }
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
  bool torque_;
  std::vector<AxisFeedbackView> feedback_;
  double sensor_at_;
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

TEST(ChannelLoadSkip, P98LimitsTheTorqueToTheRatioAndSkipsWhereTheAxisIsHeldBack) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"          // 1
      "G10 L14 P6 Z40\n"          // 2
      "G31 W-50 F600 P98 R100\n"  // 3: held back at the contact, -12.5
      "#101=#5062\n"              // 4
      "G00 X[20+#100*10]\n"       // 5: X to 30 (radius 15) when it skipped
      "G01 Z[#101+5] F600\n"      // 6: Z's move cancels the limit
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_EQ(rig.armings, 1);
  // Z limited to G10 L14 P6's 40 %, no deviation, its torque skip armed; X neither.
  const std::vector<Sent> g31 = rig.during(kZ, 3);
  ASSERT_FALSE(g31.empty());
  EXPECT_TRUE(std::all_of(g31.begin(), g31.end(), [](const Sent& s) {
    return s.torque_limit == 40.0 && s.skip_deviation == 0.0;
  }));
  EXPECT_EQ(g31.front().probe, ProbeArm::torque);
  for (const Sent& s : rig.sent[kX]) {
    EXPECT_EQ(s.torque_limit, 0.0);
    EXPECT_EQ(s.probe, ProbeArm::off);  // P98: no touch probe
  }
  // Stopped past the contact within the reaction and the braking, far from -50.
  const ChannelEvent* skipped = rig.end_of(3);
  ASSERT_NE(skipped, nullptr);
  EXPECT_LT(skipped->pos[kZ], kContact);
  EXPECT_GT(skipped->pos[kZ], kContact - 0.2);
  // X's rapid: Z keeps pressing with the limit.
  for (const Sent& s : rig.during(kZ, 5)) {
    EXPECT_EQ(s.torque_limit, 40.0);
    EXPECT_EQ(s.probe, ProbeArm::off);
  }
  EXPECT_NEAR(rig.x(), 15.0, 1e-9);  // R100 = 1
  for (const Sent& s : rig.during(kZ, 6)) {
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  EXPECT_NEAR(rig.z(), kContact + 5.0, 1e-9);  // #5062 = the contact
}

TEST(ChannelLoadSkip, P99SkipsOnTheTouchProbeBeforeTheLoad) {
  TorqueRig rig(true, -6.0);
  rig.load("G98 G00 X20 Z0\nG31 W-50 F600 L13 P99\nG00 Z[#5062+1]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  // X's probe armed on the rising edge and Z's torque skip at param 5511's 30 %.
  const std::vector<Sent> x = rig.during(kX, 2);
  const std::vector<Sent> z = rig.during(kZ, 2);
  ASSERT_FALSE(x.empty());
  ASSERT_FALSE(z.empty());
  EXPECT_EQ(x.front().probe, ProbeArm::rising);
  EXPECT_EQ(x.front().torque_limit, 0.0);
  EXPECT_EQ(z.front().probe, ProbeArm::torque);
  EXPECT_EQ(z.front().torque_limit, 30.0);
  // The sensor at -6 came first: stopped near it, Z never reached the contact.
  const ChannelEvent* skipped = rig.end_of(2);
  ASSERT_NE(skipped, nullptr);
  EXPECT_LT(skipped->pos[kZ], -6.0);
  EXPECT_GT(skipped->pos[kZ], -6.3);
  EXPECT_NEAR(rig.z(), -6.0 + 1.0, 0.02);  // #5062 where Z stood at X's latch
}

TEST(ChannelLoadSkip, P99SkipsOnTheLoadWithoutTheSignal) {
  TorqueRig rig;
  rig.load("G98 G00 X20 Z0\nG31 W-50 F600 L13 P99\nG00 Z[#5062+1]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  const ChannelEvent* skipped = rig.end_of(2);
  ASSERT_NE(skipped, nullptr);
  EXPECT_LT(skipped->pos[kZ], kContact);
  EXPECT_GT(skipped->pos[kZ], kContact - 0.2);
  EXPECT_NEAR(rig.z(), kContact + 1.0, 1e-9);
}

TEST(ChannelLoadSkip, AnAxisWhoseDriveTakesNoLimitIsRefusedBeforeTheProgramRuns) {
  TorqueRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG31 W-50 F600 P98\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("G31 P98: the drive of axis Z takes no torque limit"),
            std::string::npos)
      << alarm->text;
}

// G10 L14 P9 (L5094-5142, decision 120): the limit goes out with the axis's setpoints from the
// block after it, with no skip deviation nor skip; G00 and G01 keep it (modal); a G160's
// stands above it while it lasts; Z0 cancels it, and so does a reset.
TEST(ChannelTorqueLimit, P9LimitsTheAxisFromTheNextBlockUntilCancelled) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"         // 1
      "G10 L14 P9 Z135\n"        // 2
      "G01 Z-5 F600\n"           // 3: under 135 %
      "G00 Z-2\n"                // 4: G00 keeps it
      "G160 W-50 P50 Q1 F600\n"  // 5: G160's 50 % above it, skips at the contact
      "G00 Z0\n"                 // 6: the move ends G160's: 135 % again
      "G10 L14 P9 Z0\n"          // 7
      "G01 Z-1 F600\n"           // 8: none
      "G10 L14 P9 Z80\n"         // 9: stands past the end, until the reset
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  for (const Sent& s : rig.during(kZ, 1)) {
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  for (const int line : {3, 4, 6}) {
    const std::vector<Sent> moved = rig.during(kZ, line);
    ASSERT_FALSE(moved.empty()) << line;
    for (const Sent& s : moved) {
      if (s.probe == ProbeArm::off) {  // not the G160 (line 5), armed while these run
        EXPECT_EQ(s.torque_limit, 135.0) << line;
        EXPECT_EQ(s.skip_deviation, 0.0) << line;
      }
    }
  }
  const std::vector<Sent> g160 = rig.during(kZ, 5);
  ASSERT_FALSE(g160.empty());
  EXPECT_EQ(g160.back().torque_limit, 50.0);
  EXPECT_EQ(g160.back().skip_deviation, 1.0);
  const std::vector<Sent> unlimited = rig.during(kZ, 8);
  ASSERT_FALSE(unlimited.empty());
  for (const Sent& s : unlimited) {
    EXPECT_EQ(s.torque_limit, 0.0);
  }
  for (const Sent& s : rig.sent[kX]) {
    EXPECT_EQ(s.torque_limit, 0.0);  // X was never named
  }
  EXPECT_NEAR(rig.z(), -1.0, 1e-9);
  EXPECT_EQ(rig.sent[kZ].back().torque_limit, 80.0);
  rig.ctl().request_reset();
  for (int i = 0; i < 20; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.sent[kZ].back().torque_limit, 0.0);
}

TEST(ChannelTorqueLimit, P9OfAnAxisWhoseDriveTakesNoLimitIsRefusedBeforeTheProgramRuns) {
  TorqueRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG10 L14 P9 Z50\nG01 Z-5 F600\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("G10 L14 P9: the drive of axis Z takes no torque limit"),
            std::string::npos)
      << alarm->text;
}

// G10 L14 P1 (L4770-4849, decision 121): Z's load watched in its G01 moves; held at the
// contact its load passes 80 %: alarm 1280 at the G01's line, in the cycle its feedback shows
// it, and nothing moves any more: Z stops where it was commanded, X never starts.
TEST(ChannelLoadWatch, P1AlarmsWhereTheG01RunsIntoTheContactAndNothingMovesAfter) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"  // 1
      "G10 L14 P1 Z80\n"  // 2
      "G00 Z-12.5\n"      // 3: a rapid to the contact: not watched
      "G00 Z-10\n"        // 4
      "G01 Z-11 F600\n"   // 5: watched, 10 %
      "G01 Z-20 F600\n"   // 6: into the contact at -12.5
      "G01 X50 F600\n"    // 7: never runs
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{1280}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{6}));
  EXPECT_NE(rig.alarm_text.find("the load of axis 2, 300 %, is above 80 % (overload)"),
            std::string::npos)
      << rig.alarm_text;
  // The command passed the contact in one cycle (0.01 mm at 10 mm/s); the feedback shows it
  // in the next; the channel stops in the cycle after: Z's command stands within three
  // cycles' travel of the contact.
  const double stopped = rig.z_cmd();
  EXPECT_LT(stopped, kContact);
  EXPECT_GT(stopped, kContact - 0.03);
  for (int i = 0; i < 100; ++i) {
    rig.step();
  }
  EXPECT_EQ(rig.z_cmd(), stopped);
  EXPECT_NEAR(rig.x(), 10.0, 1e-12);  // X20 as a radius: line 7 never ran
}

// J (the example's J2, in seconds): the load above the reference that long, then the alarm.
TEST(ChannelLoadWatch, TheFilterTimeLetsTheLoadStayAboveThatLongFirst) {
  TorqueRig rig;
  rig.load("G98 G00 X20 Z-10\nG10 L14 P1 Z80 J0.05\nG01 Z-20 F600\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{1280}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{3}));
  // 50 cycles above, at 0.01 mm a cycle: about 0.5 mm past the contact.
  EXPECT_LT(rig.z_cmd(), kContact - 0.48);
  EXPECT_GT(rig.z_cmd(), kContact - 0.52);
}

// P0 watches every move, G00 too; G10 L14 P1 without axes cancels every check.
TEST(ChannelLoadWatch, P0WatchesRapidsAndACancelEndsIt) {
  TorqueRig rig;
  rig.load("G98 G00 X20 Z0\nG10 L14 P0 Z80\nG00 Z-20\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_EQ(rig.alarms, (std::vector<int>{1280}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{3}));

  // Cancelled, the same press goes on unwatched (the G01 waits at the contact, in no alarm).
  TorqueRig cancelled;
  cancelled.load("G98 G00 X20 Z0\nG10 L14 P0 Z80\nG10 L14 P1\nG01 Z-13 F600\nM30\n");
  cancelled.ctl().request_start();
  for (int i = 0; i < 3000; ++i) {
    cancelled.step();
  }
  EXPECT_TRUE(cancelled.alarms.empty()) << cancelled.alarm_text;
  EXPECT_NEAR(cancelled.z_cmd(), -13.0, 1e-9);
}

TEST(ChannelLoadWatch, AnAxisWhoseDriveDoesNotReportItsTorqueIsRefusedBeforeTheProgramRuns) {
  TorqueRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG10 L14 P1 Z80\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("G10 L14 P1: the drive of axis Z does not report its torque"),
            std::string::npos)
      << alarm->text;
}

// G10 L14 P2-P5 and P20-P51 (L4770-4849): the timers count while the blocks run; the check
// waits until the blocks before it ended and hands the axes that meet it to #R, which the
// blocks after it read (X moved to 20 + 10·#100 + 100·#101, as a diameter).
TEST(ChannelLoadTimers, TheChecksHandTheAxesThatMeetThemToTheProgram) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"         // 1
      "G10 L14 P2 Z80\n"         // 2: never above 80 % in free motion
      "G10 L14 P3 Z5\n"          // 3: 10 % while Z moves
      "G01 Z-10 F600\n"          // 4: about 1 s of feed
      "G00 Z0\n"                 // 5: P3 times G01 moves only
      "#100=0\n"                 // 6
      "G10 P21 L14 Z0.5 R100\n"  // 7: 0 s, not more than 0.5 s: #100 stays 0
      "#101=0\n"                 // 8
      "G10 P31 L14 Z0.5 R101\n"  // 9: about 1 s, more than 0.5 s: #101 = Z's bit, 2
      "#102=0\n"                 // 10
      "G10 P31 L14 Z1.5 R102\n"  // 11: not more than 1.5 s
      "G00 X[20+#100*10+#101*100+#102*1000]\n"
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.x(), 110.0, 1e-9);  // X220 as a radius
  EXPECT_NE(rig.end_of(9), nullptr);
}

// Without R, the condition met is alarm 1281 at the check's line; nothing moves after it.
TEST(ChannelLoadTimers, WithoutRTheConditionMetIsAnAlarmAndNothingMovesAfter) {
  TorqueRig rig;
  rig.load(
      "G98 G00 X20 Z0\n"
      "G10 L14 P4 Z5\n"     // 2: every move
      "G00 Z-10\n"          // 3
      "G10 P40 L14 Z100\n"  // 4: the rapid took less than 100 s: the alarm
      "G00 X50\n"           // 5: never runs
      "M30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{1281}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{4}));
  EXPECT_NE(rig.alarm_text.find("G10 L14 P40: the load of axis 2 was above 5 % for"),
            std::string::npos)
      << rig.alarm_text;
  for (int i = 0; i < 100; ++i) {
    rig.step();
  }
  EXPECT_NEAR(rig.x(), 10.0, 1e-12);
  EXPECT_NEAR(rig.z_cmd(), -10.0, 1e-9);
}

TEST(ChannelLoadTimers, AnAxisWhoseDriveDoesNotReportItsTorqueIsRefusedBeforeTheProgramRuns) {
  TorqueRig rig(false);
  const auto alarm = rig.load_with_alarm("G98 G00 X20 Z0\nG10 L14 P4 Z80\nM30\n");
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(alarm->number, interp::alarm::kSkipInput);
  EXPECT_EQ(alarm->line, 2);
  EXPECT_NE(alarm->text.find("G10 L14 P4: the drive of axis Z does not report its torque"),
            std::string::npos)
      << alarm->text;
}

}  // namespace
}  // namespace mcnc::channel
