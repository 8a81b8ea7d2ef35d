#pragma once
// Link: a mirror of chosen axes, each about its own centre (the programmable mirror G51.1, spec
// dafeng L4233-4278; the facing turret's G68 is X about 0). Promises: x -> 2c - x on a mirrored
// axis, the others kept exactly; applying it twice is the identity.
#include "channel/interp/transform/axis_point.hpp"

#include <array>

namespace mcnc::interp::transform {

struct AxisMirror {
  std::array<bool, kAxes> mirrored{};
  AxisPoint centre = AxisPoint::Zero();  // used on the mirrored axes only

  bool active() const {
    for (const bool m : mirrored) {
      if (m) {
        return true;
      }
    }
    return false;
  }

  AxisMap map() const {
    AxisMap m = AxisMap::Identity();
    for (int i = 0; i < kAxes; ++i) {
      if (mirrored[static_cast<std::size_t>(i)]) {
        m.linear()(i, i) = -1.0;
        m.translation()(i) = 2.0 * centre(i);
      }
    }
    return m;
  }
};

}  // namespace mcnc::interp::transform
