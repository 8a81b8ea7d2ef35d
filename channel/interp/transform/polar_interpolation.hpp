#pragma once
// Link (not affine): polar interpolation, G12.1 (spec dafeng L711-849). The program moves the
// tool tip in a Cartesian plane: x along the linear axis (physical, a radius measured from the
// turning centre), y along a virtual axis at right angles to it. The machine turns the work on
// the rotary axis and moves the linear axis: radius = |(x, y)|, angle = zero + atan2(y, x) in
// degrees (positive towards +y), the turn of the angle chosen continuous with the last one.
//
// A straight move of the machine between two such points is a spiral in the plane, so a
// contour piece becomes machine points close enough that the tip stays within `tolerance` of
// the piece (checked at a quarter, half and three quarters of every step against the piece at
// the same fraction, with half the tolerance; the tests sample it densely). Near the turning centre
// the steps get short and turn the rotary axis far: the planner's per-axis limits then slow the
// path, since each step is an ordinary line of the machine.
#include <array>
#include <vector>

namespace mcnc::interp::transform {

struct PolarPoint {
  double radius = 0.0;
  double degrees = 0.0;
};

// A contour piece in the polar plane: a line, or an arc about `centre` (counter-clockwise when
// `ccw`, seen with x to the right and y up) with `turns` extra full turns.
struct PlanePiece {
  std::array<double, 2> from{};
  std::array<double, 2> to{};
  bool arc = false;
  std::array<double, 2> centre{};
  bool ccw = false;
  int turns = 0;

  std::array<double, 2> at(double fraction) const;  // 0: from, 1: to
  double length() const;
};

struct PolarStep {
  PolarPoint machine;
  double plane_length = 0.0;  // the length of the piece this step covers
};

class PolarInterpolation {
 public:
  // `zero_degrees`: the rotary axis's machine angle where the virtual axis reads 0.
  explicit PolarInterpolation(double zero_degrees) : zero_degrees_(zero_degrees) {}

  // The machine point of plane point p, its angle the turn nearest `near_degrees`.
  PolarPoint to_machine(const std::array<double, 2>& p, double near_degrees) const;
  std::array<double, 2> to_plane(const PolarPoint& m) const;
  // Appends the steps of `piece` starting at machine angle `from_degrees` (the angle of
  // piece.from); false when more than `max_steps` would be needed.
  bool steps(const PlanePiece& piece, double from_degrees, double tolerance,
             std::vector<PolarStep>& out, std::size_t max_steps = 1000000) const;

 private:
  double zero_degrees_ = 0.0;
};

}  // namespace mcnc::interp::transform
