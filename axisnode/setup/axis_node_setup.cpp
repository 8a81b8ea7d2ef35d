#include "axisnode/setup/axis_node_setup.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::axisnode {

canopen::NodeStartupConfig drive_startup_of(const config::AxisConfig& axis) {
  canopen::NodeStartupConfig startup;
  startup.node = static_cast<std::uint8_t>(axis.node_id);
  startup.bootup_attempts = 20;  // 20 x 500 ms
  if (axis.type == config::AxisType::spindle) {
    startup.pdos = canopen::spindle_pdos();
    startup.mode = kModeCsv;
  } else if (axis.has_homing) {
    startup.pdos = canopen::homing_axis_pdos();
    startup.mode = kModeHoming;
    startup.homing_method = static_cast<std::int8_t>(axis.homing_method);
    startup.home_offset =
        static_cast<std::int32_t>(std::llround(axis.home_offset * axis.counts_per_unit));
  }
  startup.heartbeat_ms = static_cast<std::uint16_t>(axis.heartbeat_ms);
  startup.quick_stop_deceleration =
      static_cast<std::uint32_t>(std::llround(axis.quick_stop_deceleration * axis.counts_per_unit));
  canopen::PdoMapping& tpdo2 = startup.pdos.tpdo2;
  if (axis.tpdo2_velocity) {
    tpdo2.objects[tpdo2.count++] = canopen::MappedObject{0x606C, 0, 32};
  }
  if (axis.tpdo2_following_error) {
    tpdo2.objects[tpdo2.count++] = canopen::MappedObject{0x60F4, 0, 32};
  }
  if (axis.tpdo2_torque) {
    tpdo2.objects[tpdo2.count++] = canopen::MappedObject{0x6077, 0, 16};
  }
  if (axis.probe_input > 0) {
    canopen::add_touch_probe(startup.pdos);
  }
  if (axis.torque_skip) {
    canopen::add_torque_limit(startup.pdos);
  }
  if (axis.torque_mode) {
    canopen::add_torque_mode(startup.pdos);  // after add_torque_limit's 0x6072
  }
  return startup;
}

AxisNodeRoles roles_of(const config::MachineConfig& machine, const config::AxisConfig& axis,
                       const canopen::NodeStartupConfig& startup) {
  AxisNodeRoles roles;
  roles.axis = static_cast<std::uint32_t>(axis.id);
  roles.home = static_cast<std::uint32_t>(machine.find_channel(axis.channel)->id);
  roles.candidates.push_back(roles.home);
  for (const config::ChannelConfig& c : machine.channels) {
    if (std::find(c.exchange_axes.begin(), c.exchange_axes.end(), axis.name) !=
        c.exchange_axes.end()) {
      roles.candidates.push_back(static_cast<std::uint32_t>(c.id));
    }
  }
  roles.exchangeable = axis.exchange != 0;
  roles.may_follow = axis.sync_slave;
  for (const config::AxisConfig& a : machine.axes) {
    if (roles.may_follow && a.id != axis.id && a.type == axis.type && !a.sync_slave) {
      roles.leaders.push_back(static_cast<std::uint32_t>(a.id));
    }
  }
  roles.power_on_master = axis.sync_at_power_on ? static_cast<std::uint32_t>(axis.sync_master) : 0;
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    if (g.slave == axis.id) {
      roles.sync_group = static_cast<std::uint32_t>(g.group);
      roles.sync_master = static_cast<std::uint32_t>(g.master);
      roles.sync_channel = static_cast<std::uint32_t>(g.channel);
    }
  }
  for (const config::ChannelConfig& ch : machine.channels) {
    if (ch.polygon_slave == axis.id) {  // never also a G114.1 slave (check_polygon)
      roles.polygon = true;
      roles.sync_master = static_cast<std::uint32_t>(ch.polygon_master);
      roles.sync_channel = static_cast<std::uint32_t>(ch.id);
    }
  }
  for (const config::ChannelConfig& ch : machine.channels) {
    if (ch.cam_slave == axis.id) {  // one of the channel's own axes, never a spindle (check_cam)
      roles.cam = true;
      roles.sync_master = static_cast<std::uint32_t>(ch.cam_master);
      roles.sync_channel = static_cast<std::uint32_t>(ch.id);
    }
  }
  for (const config::ChannelConfig& ch : machine.channels) {
    if (ch.egb_work == axis.id) {  // one of the channel's own rotary axes (check_egb)
      roles.egb = true;
      roles.sync_master = static_cast<std::uint32_t>(ch.egb_tool);
      roles.sync_channel = static_cast<std::uint32_t>(ch.id);
      roles.egb_axial = static_cast<std::uint32_t>(ch.egb_axial);
      roles.egb_synchronous = ch.egb_synchronous;
      roles.egb_reset_at_once = ch.egb_reset_at_once;
      if (ch.egb_axial != 0) {
        roles.leaders.push_back(roles.egb_axial);  // the work axis follows no other (G51.4)
      }
      coupling::GearBoxSetup& g = roles.gear_box;
      g.cycle_s = machine.cycle_s();
      g.max_acceleration = axis.acceleration;  // param 5313, as the polygon axis's
      g.stop_time_s = ch.egb_stop_time_s;
      // 5336 in rpm of the work axis (decision 135), watched in follow mode only (5320.1 = 0).
      g.max_deviation = ch.egb_synchronous ? 0.0 : ch.egb_deviation_rpm * 6.0;
      g.deviation_time_s = ch.egb_deviation_time_s;
      g.reverse = ch.egb_reverse;
      g.helix_reverse = ch.egb_helix_reverse;
    }
  }
  roles.in_position = axis.in_position;
  roles.cycle_s = machine.cycle_s();

  AxisNodeSetup& setup = roles.controller;
  setup.counts_per_unit = axis.counts_per_unit;
  setup.cycle_s = machine.cycle_s();
  setup.deadline_cycles = machine.deadline_cycles;
  setup.has_soft_limits = axis.has_soft_limits;
  setup.soft_min = axis.soft_limit_min;
  setup.soft_max = axis.soft_limit_max;
  setup.following_error_limit = axis.following_error_limit;
  setup.acceleration = axis.acceleration;
  // Heartbeat consumer time: 1.5 producer times (CiA 301 practice), in cycles. At least one
  // cycle: a heartbeat faster than the cycle is still watched.
  setup.heartbeat_cycles =
      startup.heartbeat_ms == 0
          ? 0
          : std::max(1, static_cast<int>(1.5 * startup.heartbeat_ms * 1000 / machine.cycle_us));
  // Half a second: a lockstep node that paces itself once its axis is stopped may step slower
  // than real time for a while (decision 127).
  setup.best_effort_watch_cycles =
      std::max(machine.deadline_cycles, static_cast<int>(machine.cycles_of(500)));
  setup.spindle = axis.type == config::AxisType::spindle;
  setup.homing = axis.has_homing;
  setup.torque_skip = axis.torque_skip;
  setup.torque_mode = axis.torque_mode;
  setup.torque_scale = axis.torque_scale;
  roles.spindle_coupling =
      coupling::SpindleCouplingSetup{machine.cycle_s(), axis.acceleration, 0.05, 1.0};
  // G51.8's lift moves no faster than the axis's rapid rate, with its acceleration.
  roles.cam_coupling =
      coupling::CamCouplingSetup{machine.cycle_s(), axis.rapid_rate / 60.0, axis.acceleration};
  return roles;
}

std::vector<std::uint8_t> other_nodes_on_bus(const config::MachineConfig& machine,
                                             const config::AxisConfig& axis) {
  std::vector<std::uint8_t> nodes;
  for (const config::AxisConfig& other : machine.axes) {
    if (other.bus == axis.bus && other.name != axis.name) {
      nodes.push_back(static_cast<std::uint8_t>(other.node_id));
    }
  }
  return nodes;
}

}  // namespace mcnc::axisnode
