#pragma once
// An axis node's core in closed loop with a simulated drive, one SYNC a cycle, for the node's
// unit tests: what the node puts in its RPDOs (controlword, target position, modes of operation,
// max torque 0x6072, target torque 0x6071, max motor speed 0x6080, touch probe function 0x60B8)
// goes to the drive, and what the drive answers in its TPDOs (statusword, position, mode
// display, torque 0x6077, touch probe status and edge positions) is the node's input of the
// next cycle. The drive is started and the node has enabled it on construction.
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/drivesim/simulated_drive.hpp"
#include "canopen/cia402/drive_pdos.hpp"

#include <cstdint>

namespace mcnc::test {

struct NodeDriveLoop {
  axisnode::AxisNodeController node;
  drivesim::SimulatedDrive drive;
  canopen::TxPdoCsp tpdo{};
  std::int16_t torque = 0;  // the drive's last 0x6077
  bool have_tpdo = false;
  std::uint64_t cycle = 0;

  NodeDriveLoop(const axisnode::AxisNodeSetup& setup, const drivesim::DriveParams& params,
                double cycle_s)
      : node(setup), drive(params, cycle_s) {
    drive.power_on();
    drive.on_nmt(canopen::NmtCommand::start);
    for (int i = 0; i < 10 && !node.output().enabled; ++i) {
      axisnode::AxisNodeInput in;
      in.have_setpoint = true;
      step(in);
    }
  }

  // One cycle: the node's RPDOs to the drive, a SYNC, its TPDOs back.
  const axisnode::AxisNodeOutput& step(axisnode::AxisNodeInput in) {
    in.have_tpdo = have_tpdo;
    in.statusword = tpdo.statusword;
    in.position_counts = tpdo.position_actual;
    in.torque_actual = torque;
    in.mode_display = drive.objects().mode();
    in.touch_probe_status = drive.objects().live.touch_probe_status;
    in.probe_positive = drive.objects().live.probe_positive;
    in.probe_negative = drive.objects().live.probe_negative;
    const auto& out = node.cycle(cycle++, in);
    drivesim::RpdoValues v;
    v.controlword = out.controlword;
    v.has_controlword = true;
    v.target_position = out.target_counts;
    v.has_target_position = true;
    v.max_torque = out.max_torque;
    v.has_max_torque = true;
    v.mode = out.mode;
    v.has_mode = true;
    v.target_torque = out.target_torque;
    v.has_target_torque = true;
    v.max_motor_speed = out.max_motor_speed;
    v.has_max_motor_speed = true;
    v.touch_probe = out.touch_probe;
    v.has_touch_probe = true;
    drive.on_rpdo(v);
    tpdo = drive.on_sync();
    torque = drive.objects().live.torque;
    have_tpdo = true;
    return out;
  }
};

}  // namespace mcnc::test
