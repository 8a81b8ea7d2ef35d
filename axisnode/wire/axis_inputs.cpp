#include "axisnode/wire/axis_inputs.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace mcnc::axisnode {

namespace {

ownership::OwnershipRequestKind to_core(AxisRequestKind kind) {
  switch (kind) {
    case AXIS_RELEASE:
      return ownership::OwnershipRequestKind::release;
    case AXIS_ACQUIRE:
      return ownership::OwnershipRequestKind::acquire;
    case AXIS_RESTORE:
      return ownership::OwnershipRequestKind::restore;
    case AXIS_WITHDRAW:
      return ownership::OwnershipRequestKind::withdraw;
  }
  return ownership::OwnershipRequestKind::withdraw;
}

AxisNodeEvent to_core(const CoordinationEvent& e) {
  AxisNodeEvent out;
  switch (e.kind()) {
    case COORD_AXIS_REQUEST:
      out.kind = AxisNodeEvent::Kind::axis_request;
      break;
    case COORD_AXIS_SYNC:
      out.kind = AxisNodeEvent::Kind::axis_sync;
      break;
    case COORD_SPINDLE_SYNC:
      out.kind = AxisNodeEvent::Kind::spindle_sync;
      break;
    case COORD_POLYGON_SYNC:
      out.kind = AxisNodeEvent::Kind::polygon_sync;
      break;
    case COORD_CAM_SYNC:
      out.kind = AxisNodeEvent::Kind::cam_sync;
      out.cam =
          coupling::cam_profile_of(e.cam_shape(), e.cam_a(), e.cam_b(), e.sync_r(), e.cam_lift());
      break;
    case COORD_EGB_SYNC:
      out.kind = AxisNodeEvent::Kind::egb_sync;
      out.egb = coupling::GearBoxCommand{e.egb_teeth(),  e.egb_threads(), e.egb_helix(),
                                         e.egb_module(), e.egb_phase(),   e.sync_r()};
      // A value the wire does not know stops the gear box as G80.4 does.
      out.egb_off = e.egb_off() == 2   ? AxisNodeEvent::EgbOff::absorb
                    : e.egb_off() == 1 ? AxisNodeEvent::EgbOff::reset
                                       : AxisNodeEvent::EgbOff::stop;
      break;
    default:
      out.kind = AxisNodeEvent::Kind::other;
      break;
  }
  out.channel = e.channel();
  out.seq = e.seq();
  out.cycle = e.cycle();
  out.axis = e.axis();
  out.request = to_core(e.axis_request());
  out.force = e.force();
  out.sync_on = e.sync_on();
  out.sync_master = e.sync_master();
  out.sync_group = e.sync_group();
  out.spindle = coupling::SpindleCouplingCommand{static_cast<int>(e.sync_p()),
                                                 static_cast<int>(e.sync_q()), e.sync_r()};
  return out;
}

SetpointSample to_core(const AxisSetpoint& sp) {
  SetpointSample out{sp.cycle(), sp.pos(),   sp.vel(),
                     sp.acc(),   sp.valid(), sp.mode() == SP_VELOCITY};
  // A value the wire does not know is no request: the probe stays off.
  out.probe = sp.probe() <= 5 ? static_cast<ProbeRequest>(sp.probe()) : ProbeRequest::off;
  // A limit the wire cannot mean (not a number, negative) is none.
  out.torque_limit =
      sp.torque_limit() > 0.0 && sp.torque_limit() <= 1000.0 ? sp.torque_limit() : 0.0;
  out.skip_deviation = sp.skip_deviation() >= 0.0 ? sp.skip_deviation() : 0.0;
  // A torque or speed the wire cannot mean (not a number, beyond the rated range) is no torque
  // mode: the axis stays in position mode.
  const bool torque_known =
      std::fabs(sp.torque()) <= 1000.0 && sp.torque_speed() > 0.0 && sp.torque_speed() <= 100000.0;
  out.torque_mode = sp.torque_mode() && torque_known;
  out.torque = out.torque_mode ? sp.torque() : 0.0;
  out.torque_speed = out.torque_mode ? sp.torque_speed() : 0.0;
  return out;
}

std::vector<std::string> names_of(const config::MachineConfig& machine,
                                  const std::vector<std::uint32_t>& axes) {
  std::vector<std::string> names;
  names.reserve(axes.size());
  for (const std::uint32_t id : axes) {
    names.push_back(machine.axes[id - 1].name);
  }
  return names;
}

}  // namespace

AxisInputs::AxisInputs(process::ProcessNode& node, const config::MachineConfig& machine,
                       const config::AxisConfig& axis, AxisNode& core)
    : node_(node),
      core_(core),
      setpoints_(
          node.participant(), dds::Keys::of({axis.name}),
          [this](const AxisSetpoint& sp, const dds::WriterId& writer) {
            const SetpointSample sample = to_core(sp);
            node_.wakeup().update([&] {
              core_.on_setpoint(sp.channel(), sp.axis(), sample, sp.event_seq(), writer);
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              node_.wakeup().update([&] { core_.on_setpoint_writer_gone(writer); });
            }
          }) {
  const AxisNodeRoles& roles = core.roles();
  if (!roles.leaders.empty()) {  // G51.4's masters, or G81.4's axial axis
    leaders_.emplace(
        node.participant(), dds::Keys::of(names_of(machine, roles.leaders)),
        [this](const AxisFeedback& fb, const dds::WriterId& writer) {
          node_.wakeup().update([&] {
            core_.on_leader_feedback(fb.axis(), fb.cycle(), fb.cmd(), fb.enabled(), writer);
          });
        },
        [this](const dds::WriterId& writer, bool matched) {
          if (!matched) {
            node_.wakeup().update([&] { core_.on_leader_gone(writer); });
          }
        });
  }
  if (roles.sync_master != 0) {
    sync_channel_.emplace(
        node.participant(), dds::Keys::of({machine.channels[roles.sync_channel - 1].name}),
        [this](const ChannelStatus& s, const dds::WriterId& writer) {
          node_.wakeup().update(
              [&] { core_.on_sync_channel_status(s.channel(), s.cycle(), s.event_seq(), writer); });
        },
        [this](const dds::WriterId& writer, bool matched) {
          if (!matched) {
            node_.wakeup().update([&] { core_.on_sync_channel_gone(writer); });
          }
        });
    sync_master_.emplace(
        node.participant(), dds::Keys::of({machine.axes[roles.sync_master - 1].name}),
        [this](const AxisFeedback& fb, const dds::WriterId& writer) {
          node_.wakeup().update([&] {
            core_.on_master_feedback(fb.axis(), fb.cycle(), fb.act(), fb.vel(), fb.cmd(), writer);
          });
        },
        [this](const dds::WriterId& writer, bool matched) {
          if (!matched) {
            node_.wakeup().update([&] { core_.on_master_gone(writer); });
          }
        });
  }
  if (core.hears_events()) {
    events_.emplace(node.participant(), [this](const CoordinationEvent& e, const dds::WriterId&) {
      if (!core_.hears_from(e.channel())) {
        return;  // most events are other channels' business: no lock for them
      }
      const AxisNodeEvent event = to_core(e);
      node_.wakeup().update([&] { core_.on_event(event); });
    });
  }
}

bool AxisInputs::discovered() const {
  const AxisNodeRoles& roles = core_.roles();
  const auto candidates = static_cast<int>(roles.candidates.size());
  return setpoints_.matched_writers() >= candidates &&
         (!sync_channel_ || sync_channel_->matched_writers() >= 1) &&
         (!sync_master_ || sync_master_->matched_writers() >= 1) &&
         (!leaders_ || leaders_->matched_writers() >= static_cast<int>(roles.leaders.size())) &&
         (!events_ || events_->matched_writers() >= candidates);
}

}  // namespace mcnc::axisnode
