// The coordinate systems as a value: how EXT, the work system selected, the G50 shift and G52
// add up, and how G50 and G52 set them from a position.
#include "channel/interp/state/coordinate_systems.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mcnc::interp::state {
namespace {

constexpr int kX = 0;
constexpr int kZ = 1;

CoordinateSystems systems() {
  std::vector<CoordinateSystems::AxisValues> work(3);
  work[0][kZ] = 1.0;    // EXT
  work[1][kZ] = 100.0;  // G54
  work[2][kZ] = 200.0;  // G55
  return CoordinateSystems(work);
}

TEST(CoordinateSystems, TheSumIsExtPlusTheSelectedSystemPlusShiftAndLocal) {
  CoordinateSystems c = systems();
  EXPECT_EQ(c.selected(), 1);
  EXPECT_EQ(c.sum(kZ), 101.0);
  c.select(2);
  EXPECT_EQ(c.sum(kZ), 201.0);
  EXPECT_EQ(c.sum(kX), 0.0);
  c.offset(0, kX) = 3.0;  // G10 L2 P0 / #5201
  EXPECT_EQ(c.sum(kX), 3.0);
}

TEST(CoordinateSystems, SystemsNotConfiguredReadZeroUpToG54Point1P99) {
  CoordinateSystems c = systems();
  c.select(6 + kExtendedWorkSystems);  // G54.1 P99
  EXPECT_EQ(c.sum(kZ), 1.0);
  c.offset(6 + kExtendedWorkSystems, kZ) = 5.0;
  EXPECT_EQ(c.sum(kZ), 6.0);
}

TEST(CoordinateSystems, G52IsKeptPerWorkSystem) {
  CoordinateSystems c = systems();
  c.set_local(kZ, 10.0);  // G52 in G54
  EXPECT_EQ(c.sum(kZ), 111.0);
  c.select(2);
  EXPECT_EQ(c.sum(kZ), 201.0);
  c.set_local_from(kZ, 250.0, 4.0, 1.0);  // W1 from Z 250 (machine) with a 4 mm tool offset
  EXPECT_EQ(c.sum(kZ), 201.0 + (250.0 - 1.0 - 200.0 - 4.0 + 1.0));
}

TEST(CoordinateSystems, G50MakesThePositionReadTheValueAndEndsG52Everywhere) {
  CoordinateSystems c = systems();
  c.set_local(kZ, 10.0);
  c.select(2);
  c.set_local(kZ, 20.0);
  c.set_position(kZ, 250.0, 30.0);  // G50 Z30 at machine Z 250
  EXPECT_EQ(250.0 - c.sum(kZ), 30.0);
  c.select(1);
  EXPECT_EQ(c.sum(kZ), 101.0 + (250.0 - 1.0 - 200.0 - 30.0));  // the shift stays, G52 ended
  c.shift_by(kZ, 2.0);                                         // G50 W2: the position reads 2 more
  EXPECT_EQ(c.sum(kZ), 101.0 + (250.0 - 1.0 - 200.0 - 30.0) - 2.0);
}

TEST(CoordinateSystems, HomingEndsTheShiftAndG52OfTheAxisOnly) {
  CoordinateSystems c = systems();
  c.set_local(kX, 7.0);
  c.set_local(kZ, 10.0);
  c.shift_by(kZ, 2.0);
  c.clear_shift_and_local(kZ);
  EXPECT_EQ(c.sum(kZ), 101.0);
  EXPECT_EQ(c.sum(kX), 7.0);
}

}  // namespace
}  // namespace mcnc::interp::state
