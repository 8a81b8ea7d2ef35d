#pragma once
// The hole cycles of spec dafeng §2.5 L1844-2198 and gsk A.6.34-A.6.35: drilling (G83/G87 and
// their .5/.6/.7 peck forms), tapping (G84/G88 with M29 rigid or M28 follow tapping, .5/.6
// peck forms) and boring (G85/G89), and the mill's G73-G89 (gsk B.1), expanded for one hole
// into steps along the drilling axis (the lathe: Z for G83/G84/G85, X for G87/G88/G89; the
// mill: the axis normal to the plane). The caller positions the other axes on the hole first
// and repeats the steps per hole (K, and the positioning-only blocks that follow).
#include "channel/interp/path/plane_path.hpp"

#include <vector>

namespace mcnc::interp::cycles {

enum class HoleKind : std::uint8_t {
  drill,  // G83/G87: feed in, optionally in pecks
  tap,    // G84/G88: feed in at the lead, spindle reversal, feed out at the lead
  bore,   // G85/G89: feed in, dwell, feed out
  // The mill's boring cycles (gsk B.1; FANUC 0i-M for what the seed leaves out):
  bore_stop,  // G86: feed in, dwell, spindle stop, rapid out, spindle restart
  fine_bore,  // G76: feed in, dwell, orient, shift off the wall, rapid out, shift back, restart
  // G87: orient and shift at the initial level, rapid past the hole to R, shift back, restart,
  // feed back to the bottom (the counterbore's far face), dwell, orient, shift, rapid to the
  // initial level, shift back, restart. R lies beyond the bottom seen from the initial level.
  back_bore,
};

enum class PeckMode : std::uint8_t {
  none,        // one feed to the bottom (Q omitted or 0)
  high_speed,  // .5: back off `retract` after each peck (param 5110 / 5211)
  deep,        // .6: back to the R level after each peck, then rapid to `clearance` short of
               // the last depth (param 5111)
  // .7: pecks as .5, and a full retract as .6 after the peck that completes
  // `full_retract_depth` of drilling since the last one (0: after every peck).
  high_speed_deep,
};

struct HoleCycle {
  HoleKind kind = HoleKind::drill;
  PeckMode peck_mode = PeckMode::none;
  double initial = 0.0;            // drilling-axis position when the cycle starts (initial level)
  double r_level = 0.0;            // R: absolute position of the R point, reached at rapid
  double bottom = 0.0;             // Z/W (X/U for the side forms): the hole bottom
  double peck = 0.0;               // Q: depth of one peck, >= 0 (0: no pecking)
  double retract = 0.0;            // high-speed back-off
  double clearance = 0.0;          // deep-hole stop short of the last depth
  double dwell_s = 0.0;            // P (ms in the program): dwell at the bottom
  double feed = 0.0;               // drill/bore feed (channel feed mode)
  double lead = 0.0;               // tap: F/I, mm/rev, < 0 for a left-hand tap
  int clamp_code = 0;              // Mxx before each hole, Mxx+1 after (0: none)
  bool return_to_initial = false;  // system B G98: back to `initial` instead of `r_level`
  double full_retract_depth = 0.0;  // .7: depth drilled between full retracts, >= 0
  double shift = 0.0;               // G76/G87: Q, how far the tool leaves the wall, >= 0
  // The mill: G98's level is where the cycle began, which the tool may have left (a G99 hole
  // before this one ends at R): the way back and G87 go to it instead of `initial`.
  bool has_initial_level = false;
  double initial_level = 0.0;
};

struct HoleStep {
  enum class Kind : std::uint8_t {
    rapid,         // to `to` on the drilling axis
    feed,          // to `to` at the cycle's feed
    tap,           // to `to` synchronised with the spindle at `lead` (in and out)
    dwell,         // `seconds`
    aux,           // M `code` (clamp before the hole, clamp + 1 after)
    reverse,       // tapping: reverse the spindle for the way out (follow tapping, M28)
    restore,       // tapping: the spindle's direction before the reversal; the mill's bores:
                   // the spindle turning again as before the stop or orientation
    spindle_stop,  // G86: the spindle stops at the bottom
    orient,        // G76/G87: the spindle stops oriented (M19)
    shift,         // G76/G87: the tool `to` off the hole's centre in the shift direction
  };
  Kind kind = Kind::rapid;
  double to = 0.0;
  double seconds = 0.0;
  int code = 0;
};

// One hole from `initial`: clamp, rapid to R, the in-feed (with pecks), dwell, the way out to
// R (or `initial`), unclamp. Pecks end at R + Q, R + 2Q, ..., the bottom; between them:
//   drill .5: rapid back `retract` (not beyond R); the next feed starts there.
//   drill .6: rapid to R, rapid to `clearance` short of the depth reached (not beyond R).
//   drill .7: as .5, or as .6 after the peck that completes `full_retract_depth`.
//   tap (any peck mode): reverse, tap back as the drill would move (.5 by `retract`, else to
//   R; never a rapid inside the thread), restore, tap on to the next depth.
//   bore: no pecks.
// .5 with `retract` 0 drills straight to the bottom (gsk A.6.34 rule 6). The way out: drill
// rapid, tap reverse / tap to R / restore, bore feed to R; with return_to_initial a rapid from
// R (the drill: from the bottom) to `initial`. Steps that would not move are left out; the
// steps are appended to `out`.
// The mill's bores: G86 spindle_stop and G76 orient and shift before the rapid out, restore
// after it (and shift back); G87 as HoleKind::back_bore says, always back to the initial level.
// Alarms (nothing is appended): 1143 a negative peck/retract/clearance/dwell/full-retract
// depth or shift, R at the bottom, R beyond the bottom seen from `initial` (the hole would be
// drilled backwards) or `initial` inside the hole, lead 0 for a tap, more than 100000 pecks.
path::PathResult expand_hole(const HoleCycle& cycle, std::vector<HoleStep>& out);

}  // namespace mcnc::interp::cycles
