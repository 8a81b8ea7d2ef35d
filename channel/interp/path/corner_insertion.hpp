#pragma once
// Automatic chamfer and corner rounding between two moves (spec dafeng §2.4 L1257-1365 `,C`
// `,R`; gsk A.6.10 `L` / `D`): the first move is shortened to the chamfer or tangent point, the
// corner move is inserted, and the second move starts from the corner's other end. Line-line,
// line-arc, arc-line and arc-arc corners.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::path {

enum class CornerKind : std::uint8_t {
  chamfer_setback,  // ,C (dafeng) and gsk type II L: distance from the virtual corner to each
                    // chamfer point, measured as a straight line from the corner (on an arc:
                    // the point at that distance nearest the corner along the arc)
  chamfer_length,   // gsk type I L: length of the chamfer line itself; both chamfer points at
                    // the same straight-line distance from the corner (the smallest that gives
                    // this length)
  round,            // ,R / D: an arc of this radius tangent to both moves, on the side the path
                    // turns to (G03 for a left turn), touching them nearest the corner
};

// `start` is where `first` starts; `first` ends where `second` starts (the virtual corner).
// Both are feed or arc moves. On success `first` and `second` are changed in place and
// `corner` is the inserted move (feed for a chamfer, arc for a round; feed = `feed`, source
// -1). When the two moves leave the corner in the same direction (no corner) nothing changes
// and `inserted` is false (gsk A.6.10 special case 1).
// A move shortened to nothing stays as long as 0 (an arc becomes a feed of length 0 to its end,
// since an arc from its end to its end would be a full circle).
// Alarms 1147: the chamfer or round does not fit on either move (gsk A.6.10 special case 2),
// a size <= 0, the second move turning straight back along the first, a move of length 0, or
// a move that is neither a feed nor an arc. `source` of the error is `first.source`.
struct CornerResult {
  bool inserted = false;
  PlaneMove corner;
};
PathResult insert_corner(Point2 start, PlaneMove& first, PlaneMove& second, CornerKind kind,
                         double size, double feed, CornerResult& result);

}  // namespace mcnc::interp::path
