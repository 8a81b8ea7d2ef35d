#include "channel/interp/gcode_table.hpp"

namespace mcnc::interp {

namespace {

// Codes that system A and B write the same way.
GCodeInfo common_code(int code10) {
  switch (code10) {
    case 0:
      return {GFunction::rapid, 1};
    case 10:
      return {GFunction::linear, 1};
    case 20:
      return {GFunction::arc_cw, 1};
    case 30:
      return {GFunction::arc_ccw, 1};
    case 50:  // Dafeng lists G05 in its appendix only (L8086): taken as GSK's (gsk A.6.4)
      return {GFunction::arc_three_point, 1};
    case 40:
      return {GFunction::dwell, 0};
    case 41:
      return {GFunction::channel_sync, 0};
    case 90:
      return {GFunction::exact_stop, 0};
    case 100:
      return {GFunction::data_input, 0};
    case 109:
      return {GFunction::radius_switch, 0};
    case 220:
      return {GFunction::stroke_check_on, 9};
    case 230:
      return {GFunction::stroke_check_off, 9};
    case 401:
      return {GFunction::normal_off, 19};
    case 411:
      return {GFunction::normal_left, 19};
    case 421:
      return {GFunction::normal_right, 19};
    case 981:
      return {GFunction::chip_break_per_min, 0};
    case 991:
      return {GFunction::chip_break_per_rev, 0};
    case 71:
    case 1070:
      return {GFunction::cylindrical, 0};
    case 121:
      return {GFunction::polar_on, 21};
    case 131:
      return {GFunction::polar_off, 21};
    case 150:
      return {GFunction::polar_coords_off, 18};
    case 160:
      return {GFunction::polar_coords_on, 18};
    case 170:
      return {GFunction::plane_xy, 16};
    case 180:
      return {GFunction::plane_zx, 16};
    case 190:
      return {GFunction::plane_yz, 16};
    case 200:
      return {GFunction::inch, 6};
    case 210:
      return {GFunction::metric, 6};
    case 280:
      return {GFunction::reference_return, 0};
    case 300:
      return {GFunction::reference_2_4, 0};
    case 320:
      return {GFunction::thread, 1};
    case 330:
      return {GFunction::flexible_tap, 1};
    case 321:
      return {GFunction::thread_interpolated, 1};
    case 322:
      return {GFunction::thread_arc_cw, 1};
    case 323:
      return {GFunction::thread_arc_ccw, 1};
    case 340:
      return {GFunction::thread_variable, 1};
    case 400:
      return {GFunction::tnrc_cancel, 7};
    case 410:
      return {GFunction::tnrc_left, 7};
    case 420:
      return {GFunction::tnrc_right, 7};
    case 504:
      return {GFunction::axis_sync_off, 0};
    case 514:
      return {GFunction::axis_sync_on, 0};
    case 520:
      return {GFunction::local_system, 0};
    case 530:
      return {GFunction::machine_position, 0};
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
      return {GFunction::work_system, 14};
    case 541:
      return {GFunction::work_system_ext, 14};
    case 610:
      return {GFunction::exact_stop_mode, 15};
    case 640:
      return {GFunction::cutting_mode, 15};
    case 650:
      return {GFunction::macro_call, 0};
    case 660:
      return {GFunction::modal_call, 12};
    case 670:
      return {GFunction::modal_call_cancel, 12};
    case 680:
      return {GFunction::turret_mirror_on, 4};
    case 690:
      return {GFunction::turret_mirror_off, 4};
    case 681:
      return {GFunction::rotation_on, 17};
    case 691:
      return {GFunction::rotation_off, 17};
    case 511:
      return {GFunction::mirror_on, 22};
    case 501:
      return {GFunction::mirror_off, 22};
    case 700:
      return {GFunction::finishing_cycle, 0};
    case 710:
      return {GFunction::rough_turning, 0};
    case 720:
      return {GFunction::rough_facing, 0};
    case 730:
      return {GFunction::pattern_repeat, 0};
    case 740:
      return {GFunction::face_grooving, 0};
    case 750:
      return {GFunction::od_grooving, 0};
    case 760:
      return {GFunction::multiple_thread, 0};
    case 830:
    case 835:
    case 836:
    case 837:
      return {GFunction::drill_face, 10};
    case 870:
    case 875:
    case 876:
    case 877:
      return {GFunction::drill_side, 10};
    case 840:
    case 845:
    case 846:
      return {GFunction::tap_face, 10};
    case 880:
    case 885:
    case 886:
      return {GFunction::tap_side, 10};
    case 850:
      return {GFunction::bore_face, 10};
    case 890:
      return {GFunction::bore_side, 10};
    case 800:
      return {GFunction::drill_cancel, 10};
    case 960:
      return {GFunction::css_on, 2};
    case 970:
      return {GFunction::css_off, 2};
    case 1130:
      return {GFunction::spindle_sync_off, 0};
    case 1141:
      return {GFunction::spindle_sync_on, 0};
    case 1400:
      return {GFunction::axis_release, 0};
    case 1410:
      return {GFunction::axis_acquire, 0};
    case 1420:
      return {GFunction::axis_restore, 0};
    case 1440:
      return {GFunction::channel_call, 0};
    case 1450:
      return {GFunction::channel_release, 0};
    case 310:
      return {GFunction::skip, 0};
    case 318:
      return {GFunction::multi_skip, 0};
    case 1600:
      return {GFunction::torque_skip, 0};
    case 811:
      return {GFunction::oscillation_on, 0};
    case 801:
      return {GFunction::oscillation_off, 0};
    case 502:
      return {GFunction::polygon_off, 0};
    case 512:
      return {GFunction::polygon_on, 0};
    case 508:
      return {GFunction::cam_off, 0};
    case 518:
      return {GFunction::cam_on, 0};
    case 804:
      return {GFunction::egb_off, 0};
    case 814:
      return {GFunction::egb_on, 0};
    default:
      return {};
  }
}

// Seed 003's table (gsk B.1) and the runtime's multi-channel words, which a mill in a cell
// needs as much as a lathe; every other code is not a G code of the mill (B.2 rule 4).
GCodeInfo mill_code(int code10) {
  switch (code10) {
    case 270:
      return {GFunction::reference_check, 0};
    case 290:
      return {GFunction::return_from_reference, 0};
    case 430:
      return {GFunction::length_plus, 8};
    case 440:
      return {GFunction::length_minus, 8};
    case 490:
      return {GFunction::length_cancel, 8};
    case 600:
      return {GFunction::single_direction, 0};
    case 730:
      return {GFunction::mill_peck_high_speed, 10};
    case 740:
      return {GFunction::mill_tap_left, 10};
    case 760:
      return {GFunction::mill_fine_bore, 10};
    case 810:
      return {GFunction::mill_drill, 10};
    case 820:
      return {GFunction::mill_drill_dwell, 10};
    case 830:
      return {GFunction::mill_peck_deep, 10};
    case 840:
      return {GFunction::mill_tap, 10};
    case 850:
      return {GFunction::mill_bore, 10};
    case 860:
      return {GFunction::mill_bore_stop, 10};
    case 870:
      return {GFunction::mill_back_bore, 10};
    case 880:
      return {GFunction::mill_bore_manual, 10};
    case 890:
      return {GFunction::mill_bore_dwell, 10};
    case 900:
      return {GFunction::absolute, 3};
    case 910:
      return {GFunction::incremental, 3};
    case 920:
      return {GFunction::coordinate_set, 0};
    case 980:
      return {GFunction::return_initial, 11};
    case 990:
      return {GFunction::return_r_level, 11};
    case 0:
    case 10:
    case 20:
    case 30:
    case 40:
    case 90:
    case 170:
    case 180:
    case 190:
    case 280:
    case 300:
    case 400:
    case 410:
    case 420:
    case 401:  // G40.1-G42.1 normal direction control (FANUC 0i-MF, group 19)
    case 411:
    case 421:
    case 520:
    case 530:
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 610:
    case 640:
    case 650:
    case 660:
    case 670:
    case 800:
    // The runtime's multi-channel words (spec dafeng §3).
    case 41:
    case 504:
    case 514:
    case 1130:
    case 1141:
    case 1400:
    case 1410:
    case 1420:
    case 1440:
    case 1450:
      return common_code(code10);
    default:
      return {};
  }
}

}  // namespace

int mill_group(int slot) {
  switch (slot) {
    case 16:
      return 2;
    case 10:
      return 9;
    case 11:
      return 10;
    default:
      return slot;
  }
}

int mill_group_slot(int group) {
  switch (group) {
    case 1:
    case 3:
    case 5:
    case 6:
    case 7:
    case 8:
    case 12:
    case 14:
    case 15:
    case 19:
      return group;
    case 2:
      return 16;
    case 9:
      return 10;
    case 10:
      return 11;
    default:
      return -1;
  }
}

GCodeInfo lookup_gcode(int code10, GCodeSystem system, Dialect dialect) {
  if (dialect == Dialect::fanuc_mill) {
    return mill_code(code10);
  }
  if (dialect == Dialect::gsk && code10 == 51) {
    return {GFunction::arc_three_point_absolute, 1};  // gsk A.6.4; Dafeng has no G05.1
  }
  if (system == GCodeSystem::a) {
    switch (code10) {
      case 500:
        return {GFunction::coordinate_set, 0};
      case 503:
        return {GFunction::restore_origin, 0};
      case 900:
        return {GFunction::turning_cycle, 1};
      case 920:
        return {GFunction::thread_cycle, 1};
      // GSK's own: G92.1, the interpolated threading cycle (gsk A.6.29), and G78, the
      // extended multiple threading cycle (gsk A.6.33). Dafeng's system A has neither.
      case 921:
        return dialect == Dialect::gsk ? GCodeInfo{GFunction::thread_cycle_interpolated, 1}
                                       : GCodeInfo{};
      case 780:
        return dialect == Dialect::gsk ? GCodeInfo{GFunction::extended_thread, 0} : GCodeInfo{};
      case 940:
        return {GFunction::facing_cycle, 1};
      case 980:
        return {GFunction::feed_per_min, 5};
      case 990:
        return {GFunction::feed_per_rev, 5};
      default:
        return common_code(code10);
    }
  }
  switch (code10) {
    case 920:
      return {GFunction::coordinate_set, 0};
    case 921:
      return {GFunction::restore_origin, 0};
    case 770:
      return {GFunction::turning_cycle, 1};
    case 780:
      return {GFunction::thread_cycle, 1};
    case 790:
      return {GFunction::facing_cycle, 1};
    case 940:
      return {GFunction::feed_per_min, 5};
    case 950:
      return {GFunction::feed_per_rev, 5};
    case 900:
      return {GFunction::absolute, 3};
    case 910:
      return {GFunction::incremental, 3};
    // Canned-cycle return level: a group of its own (decision D13), 11 here.
    case 980:
      return {GFunction::return_initial, 11};
    case 990:
      return {GFunction::return_r_level, 11};
    default:
      return common_code(code10);
  }
}

}  // namespace mcnc::interp
