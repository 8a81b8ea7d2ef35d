#pragma once
// The modal state of a program run: the G codes in force (one value per group, as #4001..
// reads them) and what the blocks act on from them: the motion, the plane, the feed mode and
// feed, the unit, exact stop, the turret mirror and system B's G91. A plain value; power_on()
// gives it as the control starts.
#include "channel/interp/command.hpp"
#include "channel/interp/gcode_table.hpp"
#include "channel/interp/interp_config.hpp"

#include <array>

namespace mcnc::interp::state {

struct ModalState {
  GFunction motion = GFunction::rapid;  // group 01
  Plane plane = Plane::zx;
  FeedMode feed_mode = FeedMode::per_min;
  bool metric = true;  // G21 (G20: inch)
  bool exact_stop = false;
  bool turret_mirror = false;
  bool incremental = false;                      // system B G91
  std::array<double, kModalGroups + 1> codes{};  // #4001.. (G value per group)
  double feed = 0.0;                             // F in force, in its unit

  // At power-on (spec dafeng §2.1, gsk B.1): G00, G97, G69, G98/G99 (by `feed_mode`), G21,
  // G40, G80, G67, G54, G64, G18, G69.1, G13.1, G50.1; system B adds G90 and G98 (return
  // level); the FANUC mill starts in G17 with G49 and has no G96/G97 nor G22/G23.
  [[nodiscard]] static ModalState power_on(GCodeSystem system, Dialect dialect,
                                           FeedMode feed_mode) noexcept;
};

}  // namespace mcnc::interp::state
