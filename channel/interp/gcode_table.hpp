#pragma once
// The G codes of the lathe dialect by G-code system (spec dafeng §2.0, appendix L8068-8307):
// what each code does and its modal group, numbered as the appendix numbers them so that #4001-
// #4030 read group n at #4000+n. Codes are handled as 10 x the written value (G04.1 -> 41).
#include "channel/interp/interp_config.hpp"

#include <cstdint>

namespace mcnc::interp {

// What a G code means, independent of how system A or B spells it.
enum class GFunction : std::uint8_t {
  unknown,
  not_in_this_version,  // a code of the spec whose turn has not come (canned cycles ...)
  rapid,
  linear,
  arc_cw,
  arc_ccw,
  arc_three_point,           // G05: the middle point relative to the start (gsk A.6.4)
  arc_three_point_absolute,  // G05.1 (GSK): the middle point absolute
  dwell,                     // G04
  channel_sync,              // G04.1
  exact_stop,                // G09
  data_input,                // G10
  radius_switch,             // G10.9
  stroke_check_on,           // G22 (group 09 as FANUC 0i-TF numbers it; Dafeng lists none)
  stroke_check_off,          // G23
  chip_break_per_min,        // G98.1: G98 with chip breaking (a mode, but one-shot here)
  chip_break_per_rev,        // G99.1: G99 with chip breaking
  normal_off,                // G40.1 (a private group, 19 here)
  normal_left,               // G41.1
  normal_right,              // G42.1
  oscillation_on,            // G81.1 (sine-profile oscillation of an axis)
  oscillation_off,           // G80.1
  skip,                      // G31
  multi_skip,                // G31.8
  torque_skip,               // G160
  plane_xy,
  plane_zx,
  plane_yz,
  inch,
  metric,
  reference_return,   // G28
  reference_2_4,      // G30
  tnrc_cancel,        // G40
  coordinate_set,     // G50 (A) / G92 (B), also the S clamp
  restore_origin,     // G50.3 (A) / G92.1 (B)
  local_system,       // G52
  machine_position,   // G53
  work_system,        // G54-G59
  work_system_ext,    // G54.1
  exact_stop_mode,    // G61
  cutting_mode,       // G64
  macro_call,         // G65
  modal_call,         // G66
  modal_call_cancel,  // G67
  turret_mirror_on,   // G68
  turret_mirror_off,  // G69
  rotation_on,        // G68.1 (group 17)
  rotation_off,       // G69.1
  mirror_on,          // G51.1 (group 22)
  mirror_off,         // G50.1
  polar_on,           // G12.1 (group 21)
  polar_off,          // G13.1
  polar_coords_on,    // G16 (group 18): polar coordinates in G12.1 (format 2)
  polar_coords_off,   // G15
  cylindrical,        // G07.1 / G107 (one-shot group, a mode until G07.1 C0)
  drill_cancel,       // G80
  css_on,             // G96
  css_off,            // G97
  feed_per_min,       // G98 (A) / G94 (B)
  feed_per_rev,       // G99 (A) / G95 (B)
  absolute,           // G90 (B)
  incremental,        // G91 (B)
  axis_sync_on,       // G51.4
  axis_sync_off,      // G50.4
  spindle_sync_off,   // G113
  spindle_sync_on,    // G114.1
  polygon_off,        // G50.2 (group 20)
  polygon_on,         // G51.2
  cam_off,            // G50.8
  cam_on,             // G51.8
  egb_off,            // G80.4
  egb_on,             // G81.4
  axis_release,       // G140
  axis_acquire,       // G141
  axis_restore,       // G142
  channel_call,       // G144
  channel_release,    // G145
  return_initial,     // G98 (B): canned-cycle return level
  return_r_level,     // G99 (B)
  // Threading (group 01).
  thread,               // G32
  thread_interpolated,  // G32.1
  thread_arc_cw,        // G32.2
  thread_arc_ccw,       // G32.3
  thread_variable,      // G34
  flexible_tap,         // G33 (GSK): tapping with a spindle stop and reversal
  // Single cycles (group 01): G90/G92/G94 in system A, G77/G78/G79 in B.
  turning_cycle,
  thread_cycle,
  thread_cycle_interpolated,  // GSK G92.1: the spindle interpolated with the feed (gsk A.6.29)
  facing_cycle,
  // Multiple repetitive cycles (group 00).
  finishing_cycle,  // G70
  rough_turning,    // G71
  rough_facing,     // G72
  pattern_repeat,   // G73
  face_grooving,    // G74
  od_grooving,      // G75
  multiple_thread,  // G76
  extended_thread,  // GSK G78: G76 with the infeed and entry chosen (gsk A.6.33)
  // Hole cycles (group 10, cancelled by G80 and by a group 01 code).
  drill_face,  // G83, .5 .6 .7
  drill_side,  // G87, .5 .6 .7
  tap_face,    // G84, .5 .6
  tap_side,    // G88, .5 .6
  bore_face,   // G85
  bore_side,   // G89
  // Tool-nose radius compensation (group 07); the mill's cutter radius compensation.
  tnrc_left,   // G41
  tnrc_right,  // G42
  // The mill (gsk Part B).
  reference_check,        // G27
  return_from_reference,  // G29
  single_direction,       // G60
  length_plus,            // G43 (group 08)
  length_minus,           // G44
  length_cancel,          // G49
  mill_drill,             // G81 (group 09 of the mill, slot 10 here)
  mill_drill_dwell,       // G82
  mill_peck_deep,         // G83
  mill_peck_high_speed,   // G73
  mill_tap,               // G84
  mill_tap_left,          // G74
  mill_bore,              // G85: feed in, feed out
  mill_bore_stop,         // G86: feed in, spindle stop, rapid out
  mill_back_bore,         // G87
  mill_bore_manual,       // G88
  mill_bore_dwell,        // G89: feed in, dwell, feed out
  mill_fine_bore,         // G76: feed in, orient, shift away, rapid out
};

struct GCodeInfo {
  GFunction function = GFunction::unknown;
  int group = 0;           // 0: one-shot (group 00)
  const char* topic = "";  // for not_in_this_version: what the code is
};

// `code10` = 10 x the G value (G01 -> 10, G54.1 -> 541). The mill dialect reads its own table
// (seed 003, gsk B.1), whose groups take the lathe's slots of the same meaning (the plane 16,
// the hole cycles 10, the return level 11; mill_group() gives the mill's own numbers).
GCodeInfo lookup_gcode(int code10, GCodeSystem system, Dialect dialect);

// The mill's number of the modal group in slot `slot` (plane 16 -> 02, hole cycles 10 -> 09,
// return level 11 -> 10), and the slot of mill group `group` (-1: none). #4001-#4030 and the
// alarms of the mill dialect use the mill's numbers (FANUC 0i-M).
int mill_group(int slot);
int mill_group_slot(int group);

inline constexpr int kModalGroups = 30;  // #4001-#4030

}  // namespace mcnc::interp
