// G10 L14 P7 as a channel runs it (decision 162): the G83's in-feed runs with Z's load watched;
// an overload stops it and takes the drill back to R, then the cycle alarms (1282), goes on
// with the next block (#R counted) or feeds in again, as params 5100.2-5100.4 say; without the
// retract the overload is the alarm where the drill stopped. Channel 1 programs X and Z; Z's
// drive reports its load: 150 % while it feeds down through a hard layer between Z-5 and Z-6
// (for the first `hard_passes` passes; then the layer is gone), else 10 % as it moves.
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
constexpr double kLayerTop = -5.0;
constexpr double kLayerBottom = -6.0;

interp::InterpreterConfig xz_channel(interp::OverloadParams params) {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].torque_skip = true;  // its drive reports its torque (0x6077)
  c.cycles.drill_overload = params;
  return c;
}

ChannelSetup xz_setup() {
  ChannelSetup s{kAxes, {0.001, 0.001}, kDt};
  s.channel_id = 1;
  s.torque_axes = {false, true};
  return s;
}

class DrillRig : public ChannelRig {
 public:
  explicit DrillRig(interp::OverloadParams params, int hard_passes = 1000, bool read_ahead = false)
      : ChannelRig(xz_channel(params), alike_axes(kAxes, kDt), xz_setup(), read_ahead),
        hard_passes_(hard_passes),
        feedback_(standing_feedback(kAxes, 1)) {}

  const CycleOutput& step() override {
    const CycleOutput& out = channel_cycle(cycle_++, feedback_);
    const double before = feedback_[kZ].act;
    follow_setpoints(out, feedback_, kAxes);
    AxisFeedbackView& z = feedback_[kZ];
    const double vel = out.setpoints[kZ].vel;
    const bool in_layer = z.act <= kLayerTop && z.act >= kLayerBottom;
    if (in_layer && !was_in_layer_ && z.act < before) {
      ++passes_;
    }
    was_in_layer_ = in_layer;
    const bool hard = in_layer && vel < 0.0 && passes_ <= hard_passes_;
    z.load_known = true;
    z.load = hard ? -150.0 : vel < 0.0 ? -10.0 : vel > 0.0 ? 10.0 : 0.0;
    z_sent.push_back(out.setpoints[kZ].pos);
    return out;
  }

  [[nodiscard]] double x() const { return feedback_[kX].act; }
  [[nodiscard]] double z() const { return feedback_[kZ].act; }
  [[nodiscard]] double lowest_z() const { return *std::min_element(z_sent.begin(), z_sent.end()); }
  // The Z positions sent, each turn of direction kept once: where Z went down to and back up to.
  [[nodiscard]] std::vector<double> z_turns() const {
    std::vector<double> turns;
    for (std::size_t i = 1; i + 1 < z_sent.size(); ++i) {
      const double a = z_sent[i] - z_sent[i - 1];
      std::size_t j = i + 1;
      while (j < z_sent.size() && z_sent[j] == z_sent[i]) {
        ++j;
      }
      if (j == z_sent.size()) {
        break;
      }
      const double b = z_sent[j] - z_sent[i];
      if (a != 0.0 && a * b < 0.0) {
        turns.push_back(z_sent[i]);
      }
    }
    return turns;
  }

  std::vector<double> z_sent;

 private:
  int hard_passes_;
  int passes_ = 0;
  bool was_in_layer_ = false;
  std::vector<AxisFeedbackView> feedback_;
  std::uint64_t cycle_ = 1;
};

constexpr const char* kDrill =
    "G98 G00 X0 Z10\n"        // 1
    "#100=0\n"                // 2
    "G10 L14 P7 Z100 R100\n"  // 3
    "G83 X0 R1 Z-10 F600\n"   // 4: into the layer at Z-5
    "G80\n"                   // 5
    "G00 X[20+#100*10]\n"     // 6: X20 (radius 10), X30 after one overload
    "M30\n";

// Example 1 (L4965-4993; 5100.2 = 1, .3 = 0, .4 = 1): back to R at once, then the alarm.
TEST(ChannelOverload, RetractsToRThenAlarms) {
  DrillRig rig({true, false, true, 0});
  rig.load(kDrill);
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{1282}));
  EXPECT_EQ(rig.alarm_lines, (std::vector<int>{4}));
  EXPECT_NE(rig.alarm_text.find("G10 L14 P7: the load of axis 2, 150 %, is above 100 %"),
            std::string::npos)
      << rig.alarm_text;
  // Stopped just inside the layer (the reaction and the braking at 10 mm/s: under 0.2 mm).
  EXPECT_LT(rig.lowest_z(), kLayerTop);
  EXPECT_GT(rig.lowest_z(), kLayerTop - 0.2);
  EXPECT_NEAR(rig.z(), 1.0, 1e-9);  // at R
  for (int i = 0; i < 200; ++i) {
    rig.step();
  }
  EXPECT_NEAR(rig.z(), 1.0, 1e-9);
  EXPECT_NEAR(rig.x(), 0.0, 1e-12);  // line 6 never ran
}

// 5100.2 = 1, .3 = 0, .4 = 0 (example 3's reading): back to R, no alarm; the block ends there
// and the program goes on, #R counting the overload. Through the read-ahead thread, as in the
// channel process.
TEST(ChannelOverload, RetractsToRAndGoesOnWithTheNextBlock) {
  DrillRig rig({true, false, false, 0}, 1000, true);
  rig.load(kDrill);
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_GT(rig.lowest_z(), kLayerTop - 0.2);  // never deeper than the overload
  EXPECT_NEAR(rig.z(), 1.0, 1e-9);             // the block ended at R
  EXPECT_NEAR(rig.x(), 15.0, 1e-9);            // X30: #100 = 1
  const std::vector<double> turns = rig.z_turns();
  ASSERT_EQ(turns.size(), 2u) << ::testing::PrintToString(turns);
  EXPECT_NEAR(turns[0], 10.0, 1e-9);  // up to the initial level, down to the layer, up to R
  EXPECT_LT(turns[1], kLayerTop);
}

// 5100.3 = 1: back to R and the in-feed again; the layer gives way on the second pass, so the
// hole is drilled to its bottom (and #R counts the one overload).
TEST(ChannelOverload, RetriesTheInFeedUntilItGetsThrough) {
  DrillRig rig({true, true, false, 0}, 1);
  rig.load(kDrill);
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.lowest_z(), -10.0, 1e-9);
  EXPECT_NEAR(rig.x(), 15.0, 1e-9);  // #100 = 1
  const std::vector<double> turns = rig.z_turns();
  ASSERT_EQ(turns.size(), 4u) << ::testing::PrintToString(turns);
  EXPECT_NEAR(turns[0], 10.0, 1e-9);  // the initial level; down to the layer, up to R, down
  EXPECT_LT(turns[1], kLayerTop);     // to the bottom, up to R
  EXPECT_GT(turns[1], kLayerTop - 0.2);
  EXPECT_NEAR(turns[2], 1.0, 1e-9);
  EXPECT_NEAR(turns[3], -10.0, 1e-9);
  EXPECT_NEAR(rig.z(), 1.0, 1e-9);  // the cycle's own way out to R
}

// 5100.2 = 0: no retract; the overload is the alarm where the drill stopped.
TEST(ChannelOverload, WithoutTheRetractTheDrillStopsWhereItOverloaded) {
  DrillRig rig({false, false, false, 0});
  rig.load(kDrill);
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms, (std::vector<int>{1282}));
  for (int i = 0; i < 200; ++i) {
    rig.step();
  }
  EXPECT_LT(rig.z(), kLayerTop);
  EXPECT_GT(rig.z(), kLayerTop - 0.2);
}

// Without an overload the cycle runs as programmed.
TEST(ChannelOverload, ALoadBelowTheLimitLetsTheCycleRun) {
  DrillRig rig({true, false, true, 0});
  rig.load(
      "G98 G00 X0 Z10\n#100=0\nG10 L14 P7 Z200 R100\nG83 X0 R1 Z-10 F600\nG80\n"
      "G00 X[20+#100*10]\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_NEAR(rig.lowest_z(), -10.0, 1e-9);
  EXPECT_NEAR(rig.x(), 10.0, 1e-9);  // #100 = 0
}

}  // namespace
}  // namespace mcnc::channel
