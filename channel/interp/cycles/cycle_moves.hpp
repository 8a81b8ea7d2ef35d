#pragma once
// Straight moves of the cycles' paths (plane_path.hpp).
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::cycles {

inline path::PlaneMove rapid_to(path::Point2 to) {
  path::PlaneMove m;
  m.kind = path::MoveKind::rapid;
  m.to = to;
  return m;
}

inline path::PlaneMove feed_to(path::Point2 to, double feed) {
  path::PlaneMove m;
  m.kind = path::MoveKind::feed;
  m.to = to;
  m.feed = feed;
  return m;
}

}  // namespace mcnc::interp::cycles
