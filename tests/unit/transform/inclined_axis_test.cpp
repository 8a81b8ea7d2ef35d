// Inclined-axis control (channel/interp/transform/inclined_axis.hpp): the spec's worked table
// (dafeng L4701-4765, theta = -30 degrees, X the inclined axis as a diameter, Z orthogonal).
#include "channel/interp/transform/inclined_axis.hpp"
#include "channel/interp/transform/axis_shift.hpp"
#include "channel/interp/transform/transform_chain.hpp"
#include "channel/interp/transform/unit_scale.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mcnc::interp::transform {
namespace {

constexpr int kX = 0;
constexpr int kZ = 1;

// Program (X a diameter) + tool offset (X a diameter) -> inclined machine, and the machine's X
// shown as a diameter again, as the table shows it.
TransformChain lathe_chain(double offset_x, double offset_z) {
  UnitScale radius;
  radius.factor(kX) = 0.5;
  AxisShift tool;
  tool.offset(kX) = offset_x / 2.0;
  tool.offset(kZ) = offset_z;
  InclinedAxis inclined;
  inclined.inclined = kX;
  inclined.orthogonal = kZ;
  inclined.degrees = -30.0;
  UnitScale diameter;
  diameter.factor(kX) = 2.0;
  TransformChain chain;
  chain.then(radius).then(tool).then(inclined).then(diameter);
  return chain;
}

AxisPoint xz(double x, double z) {
  AxisPoint p = AxisPoint::Zero();
  p(kX) = x;
  p(kZ) = z;
  return p;
}

struct Row {
  double offset_x, offset_z;  // the tool offset (T0001: 0, 0; T0002: X5.1 Z2.5)
  double program_x, program_z;
  double machine_x, machine_z;
};

TEST(InclinedAxis, TheSpecsWorkedTable) {
  const Row rows[] = {
      {0, 0, 0, 0, 0, 0},                  // G53 X0 Z0
      {0, 0, -86.603, -75.0, -100, -50},   // G53 X-100 Z-50 (shown, to 0.001)
      {0, 0, 10, 0, 11.547, -2.887},       // T0001 G00 X10 Z0
      {0, 0, -10, 5, -11.547, 7.887},      // G00 X-10 Z5
      {5.1, 2.5, 10, 0, 17.436, -1.859},   // T0002 G00 X10 Z0
      {5.1, 2.5, -10, 5, -5.658, 8.9145},  // G00 X-10 Z5
  };
  for (const Row& r : rows) {
    const TransformChain chain = lathe_chain(r.offset_x, r.offset_z);
    const AxisPoint m = chain.to_machine(xz(r.program_x, r.program_z));
    EXPECT_NEAR(m(kX), r.machine_x, 0.0006) << r.program_x << " " << r.program_z;
    EXPECT_NEAR(m(kZ), r.machine_z, 0.0006) << r.program_x << " " << r.program_z;
    // G53: the machine position shown in program coordinates.
    const AxisPoint shown = chain.to_program(xz(r.machine_x, r.machine_z));
    EXPECT_NEAR(shown(kX), r.program_x, 0.0006);
    EXPECT_NEAR(shown(kZ), r.program_z, 0.0006);
  }
}

TEST(InclinedAxis, RandomRoundTripsAndTheOtherAxesKept) {
  std::mt19937_64 rng(5690);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0);
  std::uniform_real_distribution<double> angle(-60.0, 60.0);
  for (int i = 0; i < 1000; ++i) {
    InclinedAxis inclined;
    inclined.inclined = 2;
    inclined.orthogonal = 5;
    inclined.degrees = angle(rng);
    TransformChain chain;
    chain.then(inclined);
    AxisPoint p;
    for (int k = 0; k < kAxes; ++k) {
      p(k) = coordinate(rng);
    }
    const AxisPoint m = chain.to_machine(p);
    for (const int k : {0, 1, 3, 4, 6, 7}) {
      EXPECT_EQ(m(k), p(k));
    }
    EXPECT_LT((chain.to_program(m) - p).cwiseAbs().maxCoeff(), 1e-9);
  }
}

}  // namespace
}  // namespace mcnc::interp::transform
