#pragma once
// G98.1 / G99.1 automatic chip breaking (spec dafeng L2548-2604): a cutting move split where
// the spindle has turned Q revolutions of feed since the last break, with the break after each
// split point: a dwell of P revolutions (P > 0) or a move back along the path for -P
// revolutions and forward again to the split point (P < 0). The count goes on from one move
// to the next.
#include "channel/interp/command.hpp"

#include <vector>

namespace mcnc::interp::cycles {

// Appends to `out` the pieces of the linear or arc move `c` (with its chip_* fields set) that
// starts at `from`, with the breaks between them. `revs` is the count of revolutions of feed
// since the last break, before and after the move. Pieces keep c's fields; only the last keeps
// its exact stop and barrier. A move back never goes back beyond the move's own start. The
// axes beside an arc's plane move in proportion (helical). False, with nothing appended, when
// the move would break more than kMaxChipBreaks times (a feed far below the spindle's turn).
inline constexpr double kMaxChipBreaks = 100'000;
bool split_for_chip_breaking(const Command& c, const AxisVector& from, std::size_t axes,
                             double& revs, std::vector<Command>& out);

}  // namespace mcnc::interp::cycles
