// The links of the coordinate chain (channel/interp/transform/) and their composition: the
// spec's worked examples and seeded round trips program -> machine -> program.
#include "channel/interp/transform/transform_chain.hpp"
#include "channel/interp/transform/axis_mirror.hpp"
#include "channel/interp/transform/axis_shift.hpp"
#include "channel/interp/transform/plane_rotation.hpp"
#include "channel/interp/transform/unit_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::transform {
namespace {

constexpr int kX = 0;  // axis order of the example lathe: X (diameter), Z, C
constexpr int kZ = 1;
constexpr int kC = 2;

AxisPoint point(double x, double z, double c = 0.0) {
  AxisPoint p = AxisPoint::Zero();
  p(kX) = x;
  p(kZ) = z;
  p(kC) = c;
  return p;
}

UnitScale diameter_x() {
  UnitScale u;
  u.factor(kX) = 0.5;
  return u;
}

TEST(TransformChain, EmptyChainChangesNoBit) {
  TransformChain chain;
  const AxisPoint p = point(0.1 + 0.2, -1e-300, 123456.789);
  EXPECT_TRUE(chain.identity());
  EXPECT_EQ(chain.to_machine(p), p);
  EXPECT_EQ(chain.to_program(p), p);
}

TEST(TransformChain, LinksApplyInTheOrderAdded) {
  AxisShift shift;
  shift.offset(kX) = 10.0;
  TransformChain chain;
  chain.then(diameter_x()).then(shift);  // halve, then shift: X100 -> 50 + 10
  EXPECT_DOUBLE_EQ(chain.to_machine(point(100, 0))(kX), 60.0);
  TransformChain reversed;
  reversed.then(shift).then(diameter_x());  // shift, then halve: (100 + 10) / 2
  EXPECT_DOUBLE_EQ(reversed.to_machine(point(100, 0))(kX), 55.0);
}

// Spec dafeng L4254-4276: under G51.1 X0, X100 and X90 (diameters) go to -100 and -90.
TEST(AxisMirror, MirrorsAboutXZeroAsTheSpecExample) {
  AxisMirror mirror;
  mirror.mirrored[kX] = true;
  TransformChain chain;
  chain.then(diameter_x()).then(mirror);
  EXPECT_DOUBLE_EQ(chain.to_machine(point(100, 0))(kX), -50.0);
  EXPECT_DOUBLE_EQ(chain.to_machine(point(90, -20))(kX), -45.0);
  EXPECT_DOUBLE_EQ(chain.to_machine(point(90, -20))(kZ), -20.0);
  EXPECT_TRUE(chain.reverses(kZ, kX));
}

TEST(AxisMirror, MirrorsAboutItsCentreAndTwiceIsIdentity) {
  AxisMirror mirror;
  mirror.mirrored[kZ] = true;
  mirror.centre(kZ) = -5.0;
  TransformChain once;
  once.then(mirror);
  EXPECT_DOUBLE_EQ(once.to_machine(point(7, 3))(kZ), -13.0);
  EXPECT_DOUBLE_EQ(once.to_machine(point(7, 3))(kX), 7.0);
  TransformChain twice;
  twice.then(mirror).then(mirror);
  EXPECT_DOUBLE_EQ(twice.to_machine(point(7, 3))(kZ), 3.0);
  EXPECT_FALSE(twice.reverses(kZ, kX));
}

// Spec dafeng L4619-4650: G68.1 X100 Z0 R60 in G18 turns the frame 60 degrees counter-
// clockwise about X100 Z0 (X a diameter); the hole programmed at X210 Z20 lies there.
TEST(PlaneRotation, RotatesTheSpecExampleAboutItsCentre) {
  PlaneRotation r;
  r.axes = {kZ, kX};
  r.centre = {0.0, 50.0};  // Z0, X100 as a radius
  r.degrees = 60.0;
  TransformChain chain;
  chain.then(diameter_x()).then(r);
  const AxisPoint m = chain.to_machine(point(210, 20, 33));
  // (Z20, X105) is (20, 55) from the centre; turned by 60 degrees in the Z-X plane.
  const double c = 0.5;
  const double s = std::sqrt(3.0) / 2.0;
  EXPECT_NEAR(m(kZ), 20 * c - 55 * s, 1e-12);
  EXPECT_NEAR(m(kX), 50 + 20 * s + 55 * c, 1e-12);
  EXPECT_DOUBLE_EQ(m(kC), 33.0);  // an axis outside the plane keeps its coordinate
  const AxisPoint centre = chain.to_machine(point(100, 0));
  EXPECT_NEAR(centre(kZ), 0.0, 1e-12);
  EXPECT_NEAR(centre(kX), 50.0, 1e-12);
  EXPECT_FALSE(chain.reverses(kZ, kX));
}

TEST(PlaneRotation, KeepsLengthsInThePlane) {
  PlaneRotation r;
  r.axes = {kZ, kX};
  r.centre = {3.0, -4.0};
  r.degrees = 37.5;
  TransformChain chain;
  chain.then(r);
  const AxisPoint a = chain.to_machine(point(1, 2));
  const AxisPoint b = chain.to_machine(point(-6, 9));
  EXPECT_NEAR((a - b).norm(), (point(1, 2) - point(-6, 9)).norm(), 1e-12);
  const AxisPoint d = chain.direction_to_machine(point(1, 0));  // X direction, no translation
  EXPECT_NEAR(d.norm(), 1.0, 1e-15);
  EXPECT_NEAR(d(kX), std::cos(37.5 * M_PI / 180.0), 1e-15);
}

// Seeded random chains as the interpreter builds them (the units first, then turns, mirrors and
// shifts in any order), coordinates of a machine: program -> machine -> program within 1e-9.
TEST(TransformChain, RandomRoundTripsReturnToTheProgrammedPoint) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> coordinate(-2000.0, 2000.0);
  std::uniform_real_distribution<double> angle(-360.0, 360.0);
  std::uniform_int_distribution<int> axis(0, kAxes - 1);
  std::uniform_int_distribution<int> kind(1, 3);
  std::bernoulli_distribution coin(0.5);
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    TransformChain chain;
    UnitScale units;
    for (int i = 0; i < kAxes; ++i) {
      units.factor(i) = coin(rng) ? 1.0 : (coin(rng) ? 0.5 : 25.4 / 2.0);
    }
    chain.then(units);
    for (int link = 0; link < 6; ++link) {
      switch (kind(rng)) {
        case 1: {
          AxisMirror m;
          for (int i = 0; i < kAxes; ++i) {
            m.mirrored[static_cast<std::size_t>(i)] = coin(rng);
            m.centre(i) = coordinate(rng);
          }
          chain.then(m);
          break;
        }
        case 2: {
          PlaneRotation r;
          r.axes = {axis(rng), axis(rng)};
          while (r.axes[1] == r.axes[0]) {
            r.axes[1] = axis(rng);
          }
          r.centre = {coordinate(rng), coordinate(rng)};
          r.degrees = angle(rng);
          chain.then(r);
          break;
        }
        default: {
          AxisShift s;
          for (int i = 0; i < kAxes; ++i) {
            s.offset(i) = coordinate(rng);
          }
          chain.then(s);
        }
      }
    }
    AxisPoint p;
    for (int i = 0; i < kAxes; ++i) {
      p(i) = coordinate(rng);
    }
    const AxisPoint back = chain.to_program(chain.to_machine(p));
    worst = std::max(worst, (back - p).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace mcnc::interp::transform
