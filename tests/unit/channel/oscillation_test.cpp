// G81.1 / G80.1 as a channel runs them (spec dafeng L2454-2505): Z strokes while the program's
// X moves, dwells and exact stops go on (they do not wait for Z to stand), G80.1 holds the
// program until Z stands at its end position, and a reset ramps the stroke down before the
// channel is in reset. The axis nodes follow the setpoints one cycle late, as in lockstep.
#include "channel/interp/program_alarms.hpp"
#include "channel_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mcnc::channel {
namespace {

constexpr double kDt = 0.001;
constexpr std::size_t kAxes = 2;  // X, Z
constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.channel = 1;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z'}};
  c.axes[kZ].oscillation = true;
  return c;
}

class OscillationRig : public LockstepRig {
 public:
  OscillationRig()
      : LockstepRig(xz_channel(), alike_axes(kAxes, kDt), ChannelSetup{kAxes, {0.001, 0.001}, kDt},
                    kAxes) {}

  std::vector<double> z;
  std::vector<double> x;

 protected:
  void record(const CycleOutput& out) override {
    z.push_back(out.setpoints[kZ].pos);
    x.push_back(out.setpoints[kX].pos);
  }
};

TEST(ChannelOscillation, ZStrokesWhileTheProgramRunsAndG801EndsItAtItsPosition) {
  OscillationRig rig;
  // Strokes of 5 mm at 600 mm/min (0.79 s); X feeds 5 mm (radius) in 3 s, then a dwell.
  rig.load("G00 X10\nG81.1 Z0 Q5 F600\nG01 X20 F100\nG04 X0.5\nG80.1 Z2\nG00 X0\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
  EXPECT_LE(*std::max_element(rig.z.begin(), rig.z.end()), 5.0 + 1e-9);
  EXPECT_GE(*std::min_element(rig.z.begin(), rig.z.end()), -1e-9);
  // Z turned at 5 several times while X fed (X between 5 and 10 radius).
  int tops_while_feeding = 0;
  for (std::size_t i = 1; i + 1 < rig.z.size(); ++i) {
    const bool top = rig.z[i] >= rig.z[i - 1] && rig.z[i] > rig.z[i + 1] && rig.z[i] > 4.99;
    tops_while_feeding += top && rig.x[i] > 5.0 + 1e-6 && rig.x[i] < 10.0 - 1e-6 ? 1 : 0;
  }
  EXPECT_GE(tops_while_feeding, 2);
  // G80.1 Z2: Z ends there; X goes back to 0 only once Z stands at 2.
  EXPECT_DOUBLE_EQ(rig.z.back(), 2.0);
  std::size_t z_rest = 0;
  for (std::size_t i = rig.z.size(); i-- > 0;) {
    if (rig.z[i] != 2.0) {
      z_rest = i + 1;
      break;
    }
  }
  std::size_t x_back = 0;  // the first cycle of G00 X0: after the last at X10
  for (std::size_t i = rig.x.size(); i-- > 0;) {
    if (rig.x[i] >= 10.0 - 1e-9) {
      x_back = i + 1;
      break;
    }
  }
  EXPECT_GT(x_back, z_rest);
  EXPECT_NEAR(rig.x.back(), 0.0, 1e-9);
}

TEST(ChannelOscillation, AResetRampsTheStrokeDownBeforeTheChannelResets) {
  OscillationRig rig;
  rig.load("G81.1 Z0 Q50 F3000\nG04 X10\nG80.1 Z0\nM30\n");
  rig.ctl().request_start();
  // Half a second into the first stroke: Z runs at speed.
  for (int i = 0; i < 500; ++i) {
    rig.step();
  }
  const std::size_t at_reset = rig.z.size();
  const double v = (rig.z[at_reset - 1] - rig.z[at_reset - 2]) / kDt;
  ASSERT_GT(v, 20.0);
  rig.ctl().request_reset();
  // Reset, and at once idle again (the axes are enabled without alarms).
  ASSERT_TRUE(rig.run_until([](const CycleOutput& o) { return o.state == ChannelState::idle; }));
  // It slowed down at the axis's 1000 mm/s^2, never turned back, and stands.
  const std::size_t ramp = rig.z.size() - at_reset;
  EXPECT_GE(ramp, static_cast<std::size_t>(v / 1000.0 / kDt) - 2);
  // (The last cycle, idle again, holds where the axis node says it stands: a cycle behind.)
  for (std::size_t i = at_reset; i + 1 < rig.z.size(); ++i) {
    EXPECT_GE(rig.z[i], rig.z[i - 1]);
  }
  const double stood = rig.z.back();
  for (int i = 0; i < 20; ++i) {
    rig.step();
  }
  EXPECT_DOUBLE_EQ(rig.z.back(), stood);
  EXPECT_TRUE(rig.alarms.empty()) << rig.alarm_text;
}

TEST(ChannelOscillation, TheProgramMayNotEndWhileZOscillates) {
  OscillationRig rig;
  rig.load_with_alarm("G81.1 Z0 Q5 F600\nG00 X10\nM30\n");
  ASSERT_TRUE(rig.run_to_end());
  ASSERT_EQ(rig.alarms.size(), 1U);
  EXPECT_EQ(rig.alarms[0], interp::alarm::kOscillation);
  // Found before the start: nothing moved.
  for (const double z : rig.z) {
    EXPECT_EQ(z, 0.0);
  }
}

}  // namespace
}  // namespace mcnc::channel
