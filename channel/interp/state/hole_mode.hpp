#pragma once
// The modal hole cycle (group 10) of a program run: its code and the amounts the blocks after
// the cycle's first one keep (lathe G83-G89, mill G73-G89). A plain value: a group 01 code or
// G80 replaces it with HoleMode{}.
#include "channel/interp/gcode_table.hpp"

namespace mcnc::interp::state {

struct HoleMode {
  GFunction function = GFunction::unknown;
  int code10 = 0;
  bool has_r = false;
  double r_level = 0.0;  // physical, on the drilling axis (machine)
  bool has_bottom = false;
  double bottom = 0.0;
  double peck = 0.0;
  double retract = -1.0;  // gsk R: the high-speed back-off (-1: the parameter)
  int peck_type = -1;     // gsk J: 0 high-speed, 1 deep (-1: by the code)
  double dwell_s = 0.0;
  double lead = 0.0;
  int clamp = 0;
  int repeat = 1;
  // The mill: the initial level (where the drilling axis stood when the cycle began, G98's
  // return level) and Q of G76/G87, the shift off the wall.
  bool has_initial = false;
  double initial = 0.0;
  double shift = 0.0;

  // A hole cycle is modal: a block without a group 10 code may still drill.
  [[nodiscard]] bool active() const noexcept { return function != GFunction::unknown; }
};

}  // namespace mcnc::interp::state
