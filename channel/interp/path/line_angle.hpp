#pragma once
// Angle programming: a straight move given by its angle instead of one or both end coordinates
// (spec dafeng §2.4 L1366-1420 `,A`; gsk A.6.11 `Q`, "drawing dimension direct input").
//
// Angles are in degrees, measured from the plane's first axis (a; Z in G18) counter-clockwise
// (towards b). An angle fixes a line, not a sense of travel: 135 and -45 give the same end point,
// the known coordinate decides which way the tool goes (as with FANUC, which works with the
// slope). The caller converts gsk Q (0.001 degree) and makes the end coordinate absolute.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::path {

// Lines closer than this to the axis of the known coordinate, or to each other, have no
// usable intersection (gsk A.6.11 rules 2-5).
inline constexpr double kAngleToleranceDegrees = 1.0;

// `degrees` modulo 360, in [0, 360) (dafeng: values beyond +-360 are taken modulo 360; gsk: Q
// is normalised to 0-360 first).
double normalized_degrees(double degrees);

enum class KnownAxis : std::uint8_t {
  a,  // the first axis' end coordinate is given (Z in G18): b is computed
  b,  // the second axis' end coordinate is given (X in G18): a is computed
};

// Case 1: `G01 X_ ,A_` / `G01 Z_ Q_`. The end of the line from `start` at `degrees` whose `known`
// coordinate is `value`. Alarm 1148 when the line is within 1 degree of parallel to the known
// coordinate's axis (X known and the angle near 0 or 180; Z known and the angle near 90 or 270),
// `end` unchanged.
PathResult line_end_from_angle(Point2 start, double degrees, KnownAxis known, double value,
                               Point2& end);

// Case 2: `G01 ,A_` (angle only) then `G01 X_ Z_ ,A_`. The first line leaves `start` at
// `first_degrees`; the second ends at `second_end` and runs at `second_degrees`. `corner` gets
// their intersection, the first block's end point. Alarm 1148 when the two lines are within 1
// degree of parallel, `corner` unchanged.
PathResult angle_lines_corner(Point2 start, double first_degrees, Point2 second_end,
                              double second_degrees, Point2& corner);

}  // namespace mcnc::interp::path
