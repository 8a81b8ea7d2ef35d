// G31.8 in the axis node's core, in closed loop with a simulated drive whose probe input passes
// three teeth (on within 1 mm above 10, 12 and 14): the owner's every_rising asks the drive's
// continuous mode (0x60B8 bit 1), and the node reports each edge the drive counted (0x60B9 bits
// 6-7) in probe_count, with the last edge's position in probe_pos; without the request the
// count is 0.
#include "tests/unit/axisnode/node_drive_loop.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace mcnc;
using axisnode::AxisNodeController;
using axisnode::AxisNodeInput;
using axisnode::ProbeRequest;
using axisnode::ProbeState;

namespace {

constexpr double kCycle = 0.001;
namespace tp = canopen::touch_probe;

// The node and a drive whose probe passes three teeth, on within 1 mm above 10, 12 and 14.
struct ProbeLoop : test::NodeDriveLoop {
  ProbeLoop()
      : NodeDriveLoop(
            axisnode::AxisNodeSetup{10000.0, kCycle, 5},
            [] {
              drivesim::DriveParams p{1, 10000.0, 0.004, 500.0, 5000.0, 0.0};
              p.probe_side = 1;
              p.probe_at = 10.0;
              p.probe_pitch = 2.0;
              p.probe_width = 1.0;
              p.probe_count = 3;
              return p;
            }(),
            kCycle) {}
};

AxisNodeInput moving(double pos, ProbeRequest probe) {
  AxisNodeInput in;
  in.have_setpoint = true;
  in.setpoint_valid = true;
  in.setpoint_pos = pos;
  in.setpoint_vel = 10.0;
  in.probe = probe;
  return in;
}

TEST(AxisNodeContinuousProbe, CountsEveryToothWithItsPosition) {
  ProbeLoop loop;
  const auto* out = &loop.step(moving(0.0, ProbeRequest::every_rising));
  for (int i = 0; i < 3; ++i) {
    out = &loop.step(moving(0.0, ProbeRequest::every_rising));
  }
  EXPECT_EQ(loop.drive.objects().touch_probe(), tp::kEnable | tp::kContinuous | tp::kPositiveEdge);
  EXPECT_EQ(out->probe, ProbeState::armed);
  EXPECT_EQ(out->probe_count, 0u);
  std::vector<double> seen;
  std::uint32_t count = 0;
  for (double pos = 0.0; pos < 20.0;) {
    pos += 0.01;
    out = &loop.step(moving(pos, ProbeRequest::every_rising));
    if (out->probe_count != count) {
      EXPECT_EQ(out->probe_count, count + 1);
      count = out->probe_count;
      seen.push_back(out->probe_pos);
    }
  }
  EXPECT_EQ(seen, (std::vector<double>{10.0, 12.0, 14.0}));
  EXPECT_EQ(out->probe, ProbeState::latched);
  // Off: the function goes, the count restarts.
  for (int i = 0; i < 3; ++i) {
    out = &loop.step(moving(20.0, ProbeRequest::off));
  }
  EXPECT_EQ(out->probe, ProbeState::off);
  EXPECT_EQ(out->probe_count, 0u);
}

TEST(AxisNodeContinuousProbe, TheFirstEventModeCountsNothing) {
  ProbeLoop loop;
  const auto* out = &loop.step(moving(0.0, ProbeRequest::rising));
  for (double pos = 0.0; pos < 20.0;) {
    pos += 0.01;
    out = &loop.step(moving(pos, ProbeRequest::rising));
  }
  EXPECT_EQ(loop.drive.objects().touch_probe(), tp::kEnable | tp::kPositiveEdge);
  EXPECT_EQ(out->probe, ProbeState::latched);
  EXPECT_DOUBLE_EQ(out->probe_pos, 10.0);
  EXPECT_EQ(out->probe_count, 0u);
}

}  // namespace
