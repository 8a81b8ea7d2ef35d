#pragma once
// What passes between the axis node's core and its drive interface each cycle: the readings
// AxisNode::step() takes from a drive's sample, and the command it sends from the core's output.
// One translation, used by the node's cycle and its tests.
#include "axisnode/link/drive_interface.hpp"
#include "axisnode/node/axis_node.hpp"

namespace mcnc::axisnode {

inline DriveReadings readings_of(const DriveSample& sample) noexcept {
  DriveReadings drive;
  drive.have_tpdo = sample.fresh;
  drive.statusword = sample.feedback.statusword;
  drive.position_counts = sample.feedback.position_actual;
  drive.mode_display = sample.feedback.mode_display;
  drive.heartbeats = sample.heartbeats;
  drive.bus_off = sample.bus_off;
  drive.foreign_syncs = sample.foreign_syncs;
  drive.touch_probe_status = sample.feedback.touch_probe_status;
  drive.probe_positive = sample.feedback.probe_positive;
  drive.probe_negative = sample.feedback.probe_negative;
  drive.torque_actual = sample.feedback.torque_actual;
  return drive;
}

inline canopen::DriveCommand command_of(const AxisNodeOutput& out) noexcept {
  return canopen::DriveCommand{out.controlword,   out.target_counts,  out.target_velocity_counts,
                               out.mode,          out.touch_probe,    out.max_torque,
                               out.target_torque, out.max_motor_speed};
}

}  // namespace mcnc::axisnode
