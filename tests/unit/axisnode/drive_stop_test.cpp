// When a stopping axis node disables its drive (axisnode/node/drive_stop.hpp).
#include "axisnode/node/drive_stop.hpp"

#include <gtest/gtest.h>

using mcnc::axisnode::DriveStop;
using mcnc::axisnode::DriveStopLimits;
using Verdict = DriveStop::Verdict;

namespace {

DriveStopLimits limits() {
  DriveStopLimits l;
  l.quiet_cycles = 5;
  l.silent_drive_cycles = 10;
  l.limit_cycles = 100;
  return l;
}

}  // namespace

TEST(DriveStop, ANodeDisablesItsDriveOnceItIsReadyAndNotBefore) {
  DriveStop stop(false, limits());
  for (int i = 0; i < 30; ++i) {
    EXPECT_EQ(stop.cycle(true, false, 0), Verdict::go_on) << i;
  }
  EXPECT_EQ(stop.cycle(true, true, 0), Verdict::disable);
}

TEST(DriveStop, TheSyncProducerWaitsUntilTheOtherNodesAreQuiet) {
  DriveStop stop(true, limits());
  std::uint64_t rpdos = 0;
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(stop.cycle(true, true, ++rpdos), Verdict::go_on) << i;  // the others still send
  }
  for (int i = 0; i < 4; ++i) {  // the fifth cycle without an RPDO makes them quiet
    EXPECT_EQ(stop.cycle(true, true, rpdos), Verdict::go_on) << i;
  }
  EXPECT_EQ(stop.cycle(true, true, rpdos), Verdict::disable);
}

TEST(DriveStop, ADriveThatNoLongerAnswersIsNotWaitedFor) {
  DriveStop stop(false, limits());
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(stop.cycle(false, false, 0), Verdict::go_on) << i;
  }
  EXPECT_EQ(stop.cycle(false, false, 0), Verdict::drive_gone);
}

TEST(DriveStop, TheStopEndsAtItsLimit) {
  DriveStop stop(true, limits());
  std::uint64_t rpdos = 0;
  Verdict v = Verdict::go_on;
  int cycles = 0;
  while (v == Verdict::go_on) {
    v = stop.cycle(true, false, ++rpdos);
    ++cycles;
  }
  EXPECT_EQ(v, Verdict::timed_out);
  EXPECT_EQ(cycles, 100);
}
