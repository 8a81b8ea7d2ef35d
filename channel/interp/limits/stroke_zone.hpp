#pragma once
// The stored stroke check 2 (G22/G23, spec dafeng L2393-2435, gsk A.6.17): per axis a + and a
// - limit in machine coordinates, and whether the box they make is forbidden inside (FANUC's
// default, GSK №172.2 = 0) or outside (the limits as travel limits). Pure: the interpreter asks
// whether a move would enter the forbidden area before the move leaves it.
#include "channel/interp/command.hpp"

#include <array>
#include <limits>

namespace mcnc::interp::limits {

inline constexpr double kUnlimited = std::numeric_limits<double>::infinity();
// A move that only touches a limit does not enter the area beyond it.
inline constexpr double kBoundaryTolerance = 1e-9;  // mm
// Arcs are checked along chords that leave the arc by at most this much.
inline constexpr double kChordTolerance = 1e-3;  // mm

struct StrokeZone {
  std::array<double, kMaxChannelAxes> minus;  // physical mm (degrees on a rotary axis)
  std::array<double, kMaxChannelAxes> plus;
  bool inside_forbidden = true;
  StrokeZone() {
    minus.fill(-kUnlimited);
    plus.fill(kUnlimited);
  }
  // No axis has a limit: nothing is forbidden (inside) or everything allowed (outside).
  bool unlimited() const;
};

// Whether point `p` (the first `axes` axes) lies in the forbidden area.
bool forbidden(const StrokeZone& zone, const AxisVector& p, std::size_t axes);

// Whether the motion command `c` (rapid, linear, thread or arc) from `from` passes through the
// forbidden area; an arc is followed along chords within kChordTolerance.
bool enters(const StrokeZone& zone, const AxisVector& from, const Command& c, std::size_t axes);

}  // namespace mcnc::interp::limits
