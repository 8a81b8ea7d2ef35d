// The simulated drive's touch probe 1 (CiA 402 0x60B8-0x60BB): its input is on beyond the
// configured position; enabled through an RPDO that maps 0x60B8, it latches the position of the
// first positive (or negative) edge, reports it in 0x60B9/0x60BA/0x60BB through the TPDOs the
// master mapped (canopen::add_touch_probe), and forgets it when disabled.
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/drive_pdos.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace mcnc::drivesim {
namespace {

namespace tp = canopen::touch_probe;
constexpr double kCycle = 0.001;
constexpr double kCounts = 10000.0;

// Powered, started and enabled at `start`, with a probe whose input is on below -12.5 (with
// `teeth`: {pitch, width, count}, only within those windows).
SimulatedDrive probing_drive(double start, std::array<double, 3> teeth = {0.0, 0.0, 1.0}) {
  DriveParams p{1, kCounts, 0.004, 500.0, 5000.0, start};
  p.probe_side = -1;
  p.probe_at = -12.5;
  p.probe_pitch = teeth[0];
  p.probe_width = teeth[1];
  p.probe_count = static_cast<int>(teeth[2]);
  SimulatedDrive d(p, kCycle);
  d.power_on();
  d.on_nmt(canopen::NmtCommand::start);
  for (const std::uint16_t cw : {0x06, 0x07, 0x0F, 0x0F}) {
    d.on_rpdo(canopen::RxPdoCsp{cw, static_cast<std::int32_t>(std::lround(start * kCounts))});
    d.on_sync();
  }
  return d;
}

// One cycle towards `target` (units) with the touch probe function `function`.
void cycle(SimulatedDrive& d, double target, std::uint16_t function) {
  RpdoValues v;
  v.controlword = 0x0F;
  v.has_controlword = true;
  v.target_position = static_cast<std::int32_t>(std::lround(target * kCounts));
  v.has_target_position = true;
  v.touch_probe = function;
  v.has_touch_probe = true;
  d.on_rpdo(v);
  d.on_sync();
}

// Down from 0 at 10 mm/s until `until`, with `function`.
void move_down(SimulatedDrive& d, double until, std::uint16_t function) {
  for (double target = d.target(); target > until;) {
    target -= 0.01;
    cycle(d, target, function);
  }
  for (int i = 0; i < 100; ++i) {
    cycle(d, until, function);
  }
}

TEST(DriveTouchProbe, LatchesThePositionOfTheFirstPositiveEdge) {
  SimulatedDrive d = probing_drive(0.0);
  const std::uint16_t rising = tp::kEnable | tp::kPositiveEdge;
  cycle(d, 0.0, rising);
  EXPECT_EQ(d.objects().live.touch_probe_status, tp::kEnabled);
  move_down(d, -14.0, rising);
  ASSERT_LT(d.position(), -13.9);
  EXPECT_EQ(d.objects().live.touch_probe_status, tp::kEnabled | tp::kPositiveStored);
  EXPECT_EQ(d.objects().live.probe_positive, -125000);
  // Back up over the edge and down again: the first event stays.
  for (int i = 0; i < 200; ++i) {
    cycle(d, -10.0, rising);
  }
  move_down(d, -13.0, rising);
  EXPECT_EQ(d.objects().live.probe_positive, -125000);
  // Disabled: the status and what it stored go.
  cycle(d, -13.0, 0);
  EXPECT_EQ(d.objects().live.touch_probe_status, 0);
}

TEST(DriveTouchProbe, TheNegativeEdgeIsWhereTheInputGoesOff) {
  SimulatedDrive d = probing_drive(-14.0);
  const std::uint16_t falling = tp::kEnable | tp::kNegativeEdge;
  cycle(d, -14.0, falling);
  for (double target = -14.0; target < -11.0; target += 0.01) {
    cycle(d, target, falling);
  }
  for (int i = 0; i < 100; ++i) {
    cycle(d, -11.0, falling);
  }
  EXPECT_EQ(d.objects().live.touch_probe_status, tp::kEnabled | tp::kNegativeStored);
  EXPECT_EQ(d.objects().live.probe_negative, -125000);
}

// The edge count of continuous mode (0x60B9 bits 6-7).
int edge_count(const SimulatedDrive& d) {
  return (d.objects().live.touch_probe_status & tp::kEdgeCountMask) >> tp::kEdgeCountShift;
}

// Teeth below -12.5: the input is on within 1 mm below -12.5, -14.5 and -16.5.
SimulatedDrive teeth_drive(double pitch, double width, int count) {
  return probing_drive(0.0, {pitch, width, static_cast<double>(count)});
}

TEST(DriveTouchProbe, ContinuousModeLatchesEveryToothAndCountsIt) {
  SimulatedDrive d = teeth_drive(2.0, 1.0, 3);
  const std::uint16_t every = tp::kEnable | tp::kContinuous | tp::kPositiveEdge;
  cycle(d, 0.0, every);
  std::vector<std::int32_t> latched;
  int seen = edge_count(d);
  EXPECT_EQ(seen, 0);
  for (double target = 0.0; target > -20.0;) {
    target -= 0.01;
    cycle(d, target, every);
    const int now = edge_count(d);
    if (now != seen) {
      EXPECT_EQ((now - seen) & 3, 1);  // one tooth per cycle at 10 mm/s
      latched.push_back(d.objects().live.probe_positive);
      seen = now;
    }
  }
  EXPECT_EQ(latched, (std::vector<std::int32_t>{-125000, -145000, -165000}));
  // Back over the teeth going up: their far sides are the rising edges now.
  for (double target = -20.0; target < -15.0;) {
    target += 0.01;
    cycle(d, target, every);
  }
  EXPECT_EQ(edge_count(d), 1);  // 3 + 2 (-17.5, -15.5), modulo 4
  EXPECT_EQ(d.objects().live.probe_positive, -155000);
  // The first-event mode keeps the first tooth only and counts nothing.
  SimulatedDrive f = teeth_drive(2.0, 1.0, 3);
  const std::uint16_t first = tp::kEnable | tp::kPositiveEdge;
  cycle(f, 0.0, first);
  move_down(f, -20.0, first);
  EXPECT_EQ(f.objects().live.probe_positive, -125000);
  EXPECT_EQ(edge_count(f), 0);
}

TEST(DriveTouchProbe, EdgesFasterThanTheCycleShowInTheCount) {
  // Teeth 0.004 apart at 10 mm/s: two or three edges in each cycle; the drive holds the last
  // position, the count tells how many there were.
  SimulatedDrive d = teeth_drive(0.004, 0.002, 10);
  const std::uint16_t every = tp::kEnable | tp::kContinuous | tp::kNegativeEdge;
  cycle(d, 0.0, every);
  int seen = edge_count(d);
  int total = 0;
  int most = 0;
  for (double target = 0.0; target > -14.0;) {
    target -= 0.01;
    cycle(d, target, every);
    const int step = (edge_count(d) - seen) & 3;
    total += step;
    most = std::max(most, step);
    seen = edge_count(d);
  }
  EXPECT_EQ(total, 10);
  EXPECT_GE(most, 2);
  EXPECT_EQ(d.objects().live.probe_negative, std::lround((-12.5 - 0.036 - 0.002) * kCounts));
}

TEST(DriveTouchProbe, TheMastersMappingCarriesItsObjects) {
  SimulatedDrive d = probing_drive(0.0);
  canopen::PdoLayout layout = canopen::axis_pdos(false, false, false);
  canopen::add_touch_probe(layout);
  EXPECT_EQ(layout.rpdo1.count, 3u);
  EXPECT_EQ(layout.tpdo1.count, 3u);
  EXPECT_EQ(layout.tpdo2.count, 2u);
  // The simulator packs and the master unpacks by the same layout: the status and the edge.
  canopen::DriveFeedback drive;
  drive.touch_probe_status = tp::kEnabled | tp::kPositiveStored;
  drive.probe_positive = -125000;
  drive.probe_negative = 7;
  can::CanFrame frame;
  ASSERT_TRUE(canopen::pack_feedback(layout.tpdo2, 1, drive, frame));
  EXPECT_EQ(frame.dlc, 8);
  canopen::DriveFeedback read;
  ASSERT_TRUE(canopen::unpack_feedback(layout.tpdo2, frame, read));
  EXPECT_EQ(read.probe_positive, -125000);
  EXPECT_EQ(read.probe_negative, 7);
  ASSERT_TRUE(canopen::pack_feedback(layout.tpdo1, 1, drive, frame));
  EXPECT_EQ(frame.dlc, 8);
  ASSERT_TRUE(canopen::unpack_feedback(layout.tpdo1, frame, read));
  EXPECT_EQ(read.touch_probe_status, tp::kEnabled | tp::kPositiveStored);
  (void)d;
}

}  // namespace
}  // namespace mcnc::drivesim
