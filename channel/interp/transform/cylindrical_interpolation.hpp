#pragma once
// Link: cylindrical interpolation, G07.1 (spec dafeng L612-710). The program moves the tool on
// the cylinder's surface unrolled into a plane: the rotary axis as the length around a cylinder
// of radius r, the other plane axis as it is. Promises: degrees = length * 180 / (pi r) and
// back; a straight line of the unrolled plane is a straight line of the machine's axes, an arc
// becomes chords that stay within `tolerance` of it.
#include "channel/interp/transform/polar_interpolation.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcnc::interp::transform {

class CylindricalInterpolation {
 public:
  explicit CylindricalInterpolation(double radius) : radius_(radius) {}

  double to_degrees(double length) const;
  double to_length(double degrees) const;
  // Where the chords of `piece` end, as fractions of it (the last is 1): one for a line, for an
  // arc as many as keep every chord within `tolerance` of the circle (at least 4 a turn); none
  // when that would be more than `max_chords`.
  static std::vector<double> chord_ends(const PlanePiece& piece, double tolerance,
                                        std::size_t max_chords = SIZE_MAX);

 private:
  double radius_ = 0.0;
};

}  // namespace mcnc::interp::transform
