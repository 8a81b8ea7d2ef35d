#include "channel/setup/controller_setup.hpp"

#include <algorithm>

namespace mcnc::channel {

ControllerLayout controller_layout_for(const config::MachineConfig& machine,
                                       const config::ChannelConfig& ch) {
  ControllerLayout layout;
  std::vector<const config::AxisConfig*>& axes = layout.axes;
  ChannelSetup& setup = layout.setup;
  for (const std::string& name : ch.program_axes()) {
    const config::AxisConfig* a = machine.find_axis(name);
    if (!a->spindle.empty()) {
      setup.spindle_c_slot = axes.size();
    }
    axes.push_back(a);
    setup.in_position.push_back(a->in_position);
    setup.probe_inputs.push_back(a->probe_input);
    setup.torque_axes.push_back(a->torque_skip);
    setup.torque_mode_axes.push_back(a->torque_mode);
    setup.torque_mode_speeds.push_back(a->torque_mode_speed);
    const bool exchange_slot = axes.size() > ch.axes.size() && a->spindle.empty();
    setup.slots.push_back(AxisSlot{
        a->address, exchange_slot, static_cast<std::uint32_t>(machine.find_channel(a->channel)->id),
        static_cast<std::uint32_t>(a->id), a->sync_slave,
        static_cast<std::uint32_t>(a->sync_master), a->sync_at_power_on && !exchange_slot});
  }
  for (const config::AxisConfig& a : machine.axes) {
    setup.machine_axes.push_back(
        MachineAxis{a.type == config::AxisType::spindle  ? MachineAxisKind::spindle
                    : a.type == config::AxisType::rotary ? MachineAxisKind::rotary
                                                         : MachineAxisKind::linear,
                    a.sync_slave});
  }
  for (const std::string& name : ch.spindles) {
    layout.spindles.push_back(machine.find_axis(name));
  }
  setup.axis_count = axes.size();
  setup.spindle_count = ch.spindles.size();
  setup.cycle_s = machine.cycle_s();
  setup.channel_id = static_cast<std::uint32_t>(ch.id);
  setup.plc = machine.plc.present;
  for (const config::PlcSignal& s : machine.plc.signals) {
    if (!s.output && s.port > 0) {
      setup.input_ports.resize(
          std::max<std::size_t>(setup.input_ports.size(), static_cast<std::size_t>(s.port) + 1),
          -1);
      setup.input_ports[static_cast<std::size_t>(s.port)] = s.index;
    }
    if (!s.output && s.skip > 0) {
      setup.skip_signals[static_cast<std::size_t>(s.skip - 1)] = s.index;
    }
  }
  setup.speed_arrival_rpm = ch.speed_arrival_rpm;
  setup.reset_leaves_torque_mode = ch.reset_leaves_torque_mode;
  setup.speed_arrival_timeout_s = ch.speed_arrival_timeout_s;
  setup.call_wait_cycles = machine.cycles_of(machine.call_wait_timeout_ms);
  // The slaves of the G114.1 groups this channel commands (its spindle is their master): their
  // feedback follows the channel's spindles' (their slots come last, as config::fed_axes has
  // them); G114.1 ends when they are in phase.
  std::size_t sync_slaves = 0;
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    setup.spindle_may_follow =
        setup.spindle_may_follow ||
        (!ch.spindles.empty() && machine.find_axis(ch.spindles.front())->id == g.slave);
  }
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    if (g.channel == ch.id) {
      setup.spindle_groups.push_back(
          SpindleGroupSetup{g.group, axes.size() + ch.spindles.size() + sync_slaves++});
    }
  }
  // G51.8: the cam's slave is one of the channel's own axes (check_cam), its slot its index.
  if (ch.cam_master != 0) {
    for (std::size_t k = 0; k < axes.size(); ++k) {
      if (axes[k]->id == ch.cam_slave) {
        setup.cam = coordination::CamSetup{static_cast<std::uint32_t>(ch.cam_master), k};
      }
    }
  }
  // G81.4: the work axis is one of the channel's own axes, the tool one of its spindles
  // (check_egb), its feedback after the axes.
  if (ch.egb_tool != 0) {
    for (std::size_t k = 0; k < axes.size(); ++k) {
      if (axes[k]->id == ch.egb_work) {
        setup.egb.work_slot = k;
      }
    }
    for (std::size_t k = 0; k < layout.spindles.size(); ++k) {
      if (layout.spindles[k]->id == ch.egb_tool) {
        setup.egb.tool_view = axes.size() + k;
      }
    }
    setup.egb.tool = static_cast<std::uint32_t>(ch.egb_tool);
    setup.egb.axial = ch.egb_axial != 0;
    setup.egb.no_wait = ch.egb_no_wait;
  }
  // G51.2: the master spindle is a spindle of the channel, its feedback after the channel's
  // axes; the polygon axis another spindle, or one of its own rotary axes, its slot its index
  // (check_polygon).
  if (ch.polygon_master != 0) {
    const auto view_of = [&](int id) {
      for (std::size_t k = 0; k < layout.spindles.size(); ++k) {
        if (layout.spindles[k]->id == id) {
          return axes.size() + k;
        }
      }
      return axes.size() + layout.spindles.size();
    };
    setup.polygon = coordination::PolygonSetup{static_cast<std::uint32_t>(ch.polygon_master),
                                               view_of(ch.polygon_master),
                                               view_of(ch.polygon_slave), ch.polygon_max_rpm * 6.0};
    setup.polygon.no_wait = ch.polygon_no_wait;
    for (std::size_t k = 0; k < ch.axes.size() && k < axes.size(); ++k) {
      if (axes[k]->id == ch.polygon_slave) {
        setup.polygon.slave_view = k;
        setup.polygon.slave_axis = true;
        setup.slots[k].polygon = true;
      }
    }
  }
  return layout;
}

}  // namespace mcnc::channel
