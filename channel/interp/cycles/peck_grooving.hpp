#pragma once
// G74 (face grooving / deep-hole pecking along the first axis, Z) and G75 (OD/ID grooving and
// cut-off along the second, X) of spec dafeng §2.5 L1709-1762 and gsk A.6.31: peck to the
// bottom of each groove with a short retract after every peck, relieve at the bottom, go back to
// the start level, step to the next groove, and return to the start point at the end.
#include "channel/interp/path/plane_path.hpp"

namespace mcnc::interp::cycles {

enum class PeckAxis : std::uint8_t {
  a,  // G74: pecks along the first axis (Z), grooves stepped along the second (X)
  b,  // G75: pecks along the second axis (X), grooves stepped along the first (Z)
};

struct PeckGrooving {
  PeckAxis axis = PeckAxis::a;
  path::Point2 end;      // X/U Z/W: the last groove's bottom (point Bf); physical
  double peck = 0.0;     // depth of one peck along the peck axis (G74 Q, G75 P); 0: no pecking
  double step = 0.0;     // shift between grooves along the other axis (G74 P, G75 Q); > 0 when
                         // the end point differs from the start on that axis
  double relief = 0.0;   // R(d): move off the groove wall at the bottom, along the step axis,
                         // away from the next groove; 0: none
  double retract = 0.0;  // R(e): back-off after each peck, >= 0
  double feed = 0.0;
};

// `start` is the tool position at the cycle block (point A). Grooves lie at A, A + step, ... on
// the step axis, the last one at end (nearer when the span is no multiple of step). Per groove:
// feed `peck` from the start level, rapid back `retract` (not beyond the start level), feed on
// to `peck` beyond the previous depth, ..., the last feed to the bottom; rapid `relief` away from
// the next groove (only when there are several grooves: a single groove or a drilled hole has
// no free side); rapid back to the start level; rapid along the step axis to the next groove.
// Moves that would not move are left out; the last move is a rapid to A. The moves are
// appended to `out`. Alarms (nothing is appended): 1152 the end point moves on the step axis
// but `step` is 0 (dafeng: "X/U given without P"), 1143 a negative amount or more than 100000
// pecks in all.
path::PathResult expand_peck_grooving(path::Point2 start, const PeckGrooving& cycle,
                                      path::PlanePath& out);

}  // namespace mcnc::interp::cycles
