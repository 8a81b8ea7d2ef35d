// The stored stroke check 2's geometry (channel/interp/limits/stroke_zone.hpp): points, lines
// through the box and arcs that bulge into it, inside and outside forbidden.
#include "channel/interp/limits/stroke_zone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mcnc::interp::limits::test {
namespace {

// X 10..50, Z -50..50 (axes 0 and 1).
StrokeZone box(bool inside) {
  StrokeZone z;
  z.inside_forbidden = inside;
  z.minus[0] = 10;
  z.plus[0] = 50;
  z.minus[1] = -50;
  z.plus[1] = 50;
  return z;
}

AxisVector at(double x, double z) {
  AxisVector p{};
  p[0] = x;
  p[1] = z;
  return p;
}

Command line_to(double x, double z) {
  Command c;
  c.op = Op::linear;
  c.to = at(x, z);
  return c;
}

// An arc in the ZX plane (a = Z, b = X) about (z, x).
Command arc_to(double x, double z, double cz, double cx, bool ccw) {
  Command c;
  c.op = Op::arc;
  c.to = at(x, z);
  c.center_axes = {1, 0};
  c.center = {cz, cx};
  c.direction = ccw ? ArcDirection::ccw : ArcDirection::cw;
  return c;
}

TEST(StrokeZone, PointsInsideOutsideAndOnTheBoundary) {
  const StrokeZone in = box(true);
  EXPECT_TRUE(forbidden(in, at(30, 0), 2));
  EXPECT_FALSE(forbidden(in, at(5, 0), 2));
  EXPECT_FALSE(forbidden(in, at(10, 0), 2));  // on the boundary: touching is allowed
  const StrokeZone out = box(false);
  EXPECT_FALSE(forbidden(out, at(30, 0), 2));
  EXPECT_TRUE(forbidden(out, at(5, 0), 2));
  EXPECT_FALSE(forbidden(out, at(50, 50), 2));
  EXPECT_FALSE(forbidden(StrokeZone{}, at(30, 0), 2));  // no limit: nothing forbidden
}

TEST(StrokeZone, ALineThroughTheBoxEntersItsEndsOutside) {
  const StrokeZone in = box(true);
  EXPECT_TRUE(enters(in, at(0, 0), line_to(60, 0), 2));
  EXPECT_FALSE(enters(in, at(0, 60), line_to(60, 60), 2));
  EXPECT_FALSE(enters(in, at(0, 0), line_to(10, 0), 2));  // up to the boundary
  // Along the boundary.
  EXPECT_FALSE(enters(in, at(10, -60), line_to(10, 60), 2));
  // Corner to corner outside the box, cutting its corner.
  EXPECT_TRUE(enters(in, at(0, 45), line_to(20, 50), 2));
  EXPECT_FALSE(enters(in, at(0, 55), line_to(20, 65), 2));
}

TEST(StrokeZone, OutsideForbiddenIsATravelRange) {
  const StrokeZone out = box(false);
  EXPECT_FALSE(enters(out, at(20, 0), line_to(40, 40), 2));
  EXPECT_TRUE(enters(out, at(20, 0), line_to(60, 0), 2));
  EXPECT_TRUE(enters(out, at(5, 0), line_to(20, 0), 2));  // starts outside
}

TEST(StrokeZone, AnArcThatBulgesIntoTheBoxEntersIt) {
  const StrokeZone in = box(true);
  // Half circle about X 0, Z 0 of radius 20 from Z -20 to Z 20 through X 20: its top is in X
  // 10..50 while both ends are at X 0.
  EXPECT_TRUE(enters(in, at(0, -20), arc_to(0, 20, 0, 0, false), 2));
  // The other way round (through X -20) stays clear.
  EXPECT_FALSE(enters(in, at(0, -20), arc_to(0, 20, 0, 0, true), 2));
  // Radius 9.99: its top stops short of X 10.
  EXPECT_FALSE(enters(in, at(0, -9.99), arc_to(0, 9.99, 0, 0, false), 2));
}

TEST(StrokeZone, ArcsAgreeWithTheirPointsOnSeededCases) {
  // An arc enters the box when one of its points (sampled densely) lies in it, beyond the
  // chord tolerance.
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> coord(-80.0, 80.0);
  std::uniform_real_distribution<double> radius(1.0, 60.0);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  const StrokeZone in = box(true);
  int entered = 0;
  for (int i = 0; i < 300; ++i) {
    const double cz = coord(rng);
    const double cx = coord(rng);
    const double r = radius(rng);
    const double t0 = angle(rng);
    const double sweep = std::uniform_real_distribution<double>(0.1, 6.0)(rng);
    const bool ccw = i % 2 == 0;
    const double t1 = t0 + (ccw ? sweep : -sweep);
    const AxisVector from = at(cx + r * std::sin(t0), cz + r * std::cos(t0));
    const Command c = arc_to(cx + r * std::sin(t1), cz + r * std::cos(t1), cz, cx, ccw);
    bool deep = false;     // a point of the arc in the box by more than the chord tolerance
    bool touches = false;  // a point of the arc in the box at all
    for (int k = 0; k <= 20000; ++k) {
      const double t = t0 + (ccw ? 1 : -1) * sweep * k / 20000.0;
      const double x = cx + r * std::sin(t);
      const double z = cz + r * std::cos(t);
      const double depth = std::min({x - 10, 50 - x, z + 50, 50 - z});
      deep = deep || depth > 2 * kChordTolerance;
      touches = touches || depth > 0;
    }
    const bool e = enters(in, from, c, 2);
    if (deep) {
      EXPECT_TRUE(e) << i;
    }
    if (!touches) {
      EXPECT_FALSE(e) << i;
    }
    entered += e ? 1 : 0;
  }
  EXPECT_GT(entered, 30);
}

}  // namespace
}  // namespace mcnc::interp::limits::test
