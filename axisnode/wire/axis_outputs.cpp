#include "axisnode/wire/axis_outputs.hpp"

#include "axisnode/control/torque_units.hpp"
#include "canopen/emcy_codes.hpp"
#include "common/config/cyclic_routes.hpp"

#include <cstdio>

namespace mcnc::axisnode {

namespace {

DriveState to_wire(cia402::State state) {
  static_assert(static_cast<int>(cia402::State::fault) == static_cast<int>(DRIVE_FAULT),
                "core and wire drive states must be in the same order");
  return static_cast<DriveState>(static_cast<int>(state));
}

}  // namespace

AxisOutputs::AxisOutputs(process::ProcessNode& node, const config::MachineConfig& machine,
                         const config::AxisConfig& axis, trace::TraceWriter& tracer,
                         int trace_pos_every)
    : node_(node),
      machine_(machine),
      axis_(axis),
      tracer_(tracer),
      trace_pos_every_(trace_pos_every),
      fed_channels_(static_cast<int>(config::channels_fed_by(machine, axis.name))),
      feedback_(node.participant(), axis.name) {}

bool AxisOutputs::discovered() const {
  return feedback_.matched_readers() >= fed_channels_;
}

const char* AxisOutputs::channel_name(std::uint32_t id) const noexcept {
  const config::ChannelConfig* channel = machine_.channel_by_id(id);
  return channel != nullptr ? channel->name.c_str() : "";
}

namespace {

const char* egb_stop_name(AxisNodeHappening::EgbStop why) {
  switch (why) {
    case AxisNodeHappening::EgbStop::program:
      return "G80.4";
    case AxisNodeHappening::EgbStop::reset:
      return "reset";
    case AxisNodeHappening::EgbStop::deviation:
      return "deviation";
    case AxisNodeHappening::EgbStop::tool_lost:
      return "tool_lost";
  }
  return "G80.4";
}

}  // namespace

const char* AxisOutputs::axis_name(std::uint32_t id) const noexcept {
  const config::AxisConfig* axis = machine_.axis_by_id(id);
  return axis != nullptr ? axis->name.c_str() : "";
}

void AxisOutputs::trace_start(const AxisNode& core) noexcept {
  const AxisNodeRoles& roles = core.roles();
  tracer_.emit(0, "owner", "\"axis\":\"%s\",\"owner\":\"%s\"", axis_.name.c_str(),
               channel_name(roles.home));
  if (roles.power_on_master != 0) {
    tracer_.emit(0, "couple", "\"kind\":\"axis\",\"master\":\"%s\",\"slave\":\"%s\"",
                 axis_name(roles.power_on_master), axis_.name.c_str());
  }
}

void AxisOutputs::trace_decisions(std::uint64_t cycle, const AxisNode& core) noexcept {
  const char* self = axis_.name.c_str();
  for (std::size_t i = 0; i < core.happening_count(); ++i) {
    const AxisNodeHappening& h = core.happenings()[i];
    switch (h.kind) {
      case AxisNodeHappening::Kind::spindle_coupled:
      case AxisNodeHappening::Kind::polygon_coupled:
        tracer_.emit(cycle, "couple",
                     "\"kind\":\"%s\",\"master\":\"%s\",\"slave\":\"%s\",\"p\":%d,\"q\":%d,"
                     "\"r\":%.3f",
                     h.kind == AxisNodeHappening::Kind::polygon_coupled ? "polygon" : "spindle",
                     axis_name(h.master), self, h.spindle.p, h.spindle.q, h.spindle.r);
        break;
      case AxisNodeHappening::Kind::spindle_decoupled:
      case AxisNodeHappening::Kind::polygon_decoupled:
        tracer_.emit(cycle, "decouple", "\"kind\":\"%s\",\"master\":\"%s\",\"slave\":\"%s\"",
                     h.kind == AxisNodeHappening::Kind::polygon_decoupled ? "polygon" : "spindle",
                     axis_name(h.master), self);
        break;
      case AxisNodeHappening::Kind::cam_coupled:
      case AxisNodeHappening::Kind::cam_refused:
        tracer_.emit(cycle, "couple",
                     "\"kind\":\"cam\",\"master\":\"%s\",\"slave\":\"%s\",\"refused\":%s",
                     axis_name(h.master), self,
                     h.kind == AxisNodeHappening::Kind::cam_refused ? "true" : "false");
        break;
      case AxisNodeHappening::Kind::cam_decoupled:
        tracer_.emit(cycle, "decouple", "\"kind\":\"cam\",\"master\":\"%s\",\"slave\":\"%s\"",
                     axis_name(h.master), self);
        break;
      case AxisNodeHappening::Kind::egb_coupled:
      case AxisNodeHappening::Kind::egb_refused:
        tracer_.emit(cycle, "couple",
                     "\"kind\":\"egb\",\"master\":\"%s\",\"slave\":\"%s\",\"refused\":%s",
                     axis_name(h.master), self,
                     h.kind == AxisNodeHappening::Kind::egb_refused ? "true" : "false");
        break;
      case AxisNodeHappening::Kind::egb_stopped:
        tracer_.emit(cycle, "decouple",
                     "\"kind\":\"egb\",\"master\":\"%s\",\"slave\":\"%s\",\"why\":\"%s\","
                     "\"offset\":%.6f",
                     axis_name(h.master), self, egb_stop_name(h.egb_stop), h.at);
        break;
      case AxisNodeHappening::Kind::egb_absorbed:
        tracer_.emit(cycle, "absorb", "\"kind\":\"egb\",\"axis\":\"%s\"", self);
        break;
      case AxisNodeHappening::Kind::axis_coupled:
        tracer_.emit(cycle, "couple", "\"kind\":\"axis\",\"master\":\"%s\",\"slave\":\"%s\"",
                     axis_name(h.master), self);
        break;
      case AxisNodeHappening::Kind::axis_decoupled:
        tracer_.emit(cycle, "decouple", "\"kind\":\"axis\",\"master\":\"%s\",\"slave\":\"%s\"",
                     axis_name(h.master), self);
        break;
      case AxisNodeHappening::Kind::owner:
        if (h.channel == 0) {
          tracer_.emit(cycle, "owner", "\"axis\":\"%s\",\"owner\":null,\"previous\":\"%s\"", self,
                       channel_name(h.previous));
        } else {
          tracer_.emit(
              cycle, "owner", "\"axis\":\"%s\",\"owner\":\"%s\",\"previous\":%s%s%s,\"forced\":%s",
              self, channel_name(h.channel), h.previous == 0 ? "null" : "\"",
              channel_name(h.previous), h.previous == 0 ? "" : "\"", h.forced ? "true" : "false");
        }
        break;
      case AxisNodeHappening::Kind::follows:
        if (h.channel == 0) {
          tracer_.emit(cycle, "follow", "\"axis\":\"%s\",\"ch\":null", self);
        } else {
          tracer_.emit(cycle, "follow", "\"axis\":\"%s\",\"ch\":\"%s\"", self,
                       channel_name(h.channel));
        }
        break;
    }
  }
}

void AxisOutputs::trace_reset(std::uint64_t cycle) noexcept {
  tracer_.emit(cycle, "operator", "\"axis\":\"%s\",\"action\":\"reset\"", axis_.name.c_str());
}

void AxisOutputs::publish(std::uint64_t cycle, const AxisNode& core, const DriveSample& drive,
                          bool in_run) noexcept {
  const canopen::DriveFeedback& tpdo = drive.feedback;
  const std::uint16_t last_emcy = drive.last_emcy;
  const AxisNodeOutput& out = core.output();
  const AxisNodeStanding standing = core.standing();
  AxisFeedback fb;
  fb.axis(core.roles().axis);
  fb.owner(standing.owner);
  fb.released_by(standing.released_by);
  fb.coupled_to(standing.coupled_to);
  fb.coupling_locked(standing.coupling_locked);
  fb.refused_channels(standing.refused_channels);
  fb.full_channels(standing.full_channels);
  fb.cycle(cycle);
  fb.cmd(out.cmd);
  fb.act(out.act);
  // The drive's own velocity and following error when TPDO2 carries them.
  fb.vel(axis_.tpdo2_velocity ? tpdo.velocity_actual / axis_.counts_per_unit : out.vel);
  fb.statusword(tpdo.statusword);
  fb.drive_state(to_wire(out.drive_state));
  fb.enabled(out.enabled);
  fb.following_error(axis_.tpdo2_following_error ? tpdo.following_error / axis_.counts_per_unit
                                                 : out.cmd - out.act);
  fb.last_emcy(last_emcy);
  const bool torque = axis_.tpdo2_torque || axis_.torque_skip;  // 0x6077 in TPDO2
  fb.load_known(torque);
  fb.load(torque ? rated_percent(tpdo.torque_actual, axis_.torque_scale) : 0.0);  // param 5522
  fb.mode_display(out.mode_display);
  fb.alarm(out.alarm != AxisAlarm::none);
  fb.probe(static_cast<std::uint8_t>(out.probe));
  fb.probe_pos(out.probe_pos);
  fb.probe_count(out.probe_count);
  fb.superimposed(core.superimposed());
  feedback_.write(fb);
  if (!in_run) {
    return;
  }

  const char* self = axis_.name.c_str();
  if (out.mode_changed) {
    tracer_.emit(cycle, "mode", "\"axis\":\"%s\",\"mode\":\"%s\"", self,
                 mode_name(out.mode_display));
  }
  if (out.drive_state_changed) {
    tracer_.emit(cycle, "drive", "\"axis\":\"%s\",\"state\":\"%s\"", self,
                 cia402::to_string(out.drive_state));
  }
  if (out.new_alarm != AxisAlarm::none) {
    const int number = kAlarmBase + static_cast<int>(out.new_alarm);
    const char* text = to_text(out.new_alarm);
    char with_emcy[160];
    if (out.new_alarm == AxisAlarm::drive_fault && last_emcy != 0) {
      std::snprintf(with_emcy, sizeof with_emcy, "drive fault: EMCY 0x%04X %s", last_emcy,
                    canopen::emcy_text(last_emcy));
      text = with_emcy;
    }
    tracer_.emit(cycle, "alarm", "\"number\":%d,\"text\":\"%s\",\"axis\":\"%s\"", number, text,
                 self);
    node_.raise_alarm(static_cast<std::uint32_t>(number), text, cycle, 0, axis_.id);
  }
  if (cycle % static_cast<std::uint64_t>(trace_pos_every_) == 0) {
    tracer_.emit(cycle, "pos", "\"axis\":\"%s\",\"cmd\":%.6f,\"act\":%.6f", self, out.cmd, out.act);
  }
}

void AxisOutputs::trace_tick(std::uint64_t cycle, std::int64_t due_ns, std::int64_t woke_ns,
                             const SentSync* sync) noexcept {
  if (cycle % static_cast<std::uint64_t>(trace_pos_every_) != 0) {
    return;
  }
  if (sync == nullptr) {
    tracer_.emit(
        cycle, "tick", "\"axis\":\"%s\",\"due_ns\":%lld,\"offset_ns\":%lld,\"late_ns\":%lld",
        axis_.name.c_str(), static_cast<long long>(due_ns),
        static_cast<long long>(node_.clock_offset_ns()), static_cast<long long>(woke_ns - due_ns));
    return;
  }
  tracer_.emit(cycle, "tick",
               "\"axis\":\"%s\",\"due_ns\":%lld,\"offset_ns\":%lld,\"late_ns\":%lld,"
               "\"sync_cycle\":%llu,\"sync_due_ns\":%lld,\"sync_late_ns\":%lld",
               axis_.name.c_str(), static_cast<long long>(due_ns),
               static_cast<long long>(node_.clock_offset_ns()),
               static_cast<long long>(woke_ns - due_ns),
               static_cast<unsigned long long>(sync->index), static_cast<long long>(sync->due_ns),
               static_cast<long long>(sync->late_ns));
}

}  // namespace mcnc::axisnode
