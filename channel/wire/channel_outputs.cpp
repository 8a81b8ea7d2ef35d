#include "channel/wire/channel_outputs.hpp"

#include "channel/wire/channel_mask.hpp"
#include "common/config/cyclic_routes.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

namespace mcnc::channel {

namespace {

::mcnc::ChannelState to_wire(ChannelState state) {
  static_assert(static_cast<int>(ChannelState::alarm) == static_cast<int>(CH_ALARM),
                "core and wire channel states must be in the same order");
  return static_cast<::mcnc::ChannelState>(static_cast<int>(state));
}

}  // namespace

ChannelOutputs::ChannelOutputs(process::ProcessNode& node, trace::TraceWriter& tracer,
                               const config::ChannelConfig& channel,
                               std::vector<std::string> channel_names,
                               std::vector<const config::AxisConfig*> axes,
                               std::vector<const config::AxisConfig*> spindles,
                               std::string program_name, SharedWriteLog& writes)
    : node_(node),
      tracer_(tracer),
      channel_(channel),
      axes_(std::move(axes)),
      spindles_(std::move(spindles)),
      program_name_(std::move(program_name)),
      status_(node.participant(), channel.name),
      events_(node.participant()),
      writes_(writes),
      channel_names_(std::move(channel_names)) {
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    c_slot_ = axes_[i]->spindle.empty() ? c_slot_ : i;
    axis_setpoints_.push_back(i == c_slot_ ? nullptr
                                           : std::make_unique<dds::Writer<AxisSetpoint>>(
                                                 node.participant(), config::node_key(*axes_[i])));
  }
  for (const config::AxisConfig* spindle : spindles_) {
    spindle_setpoints_.push_back(std::make_unique<dds::Writer<AxisSetpoint>>(
        node.participant(), config::node_key(*spindle)));
  }
  cam_event_.cam_lift().reserve(coordination::kMaxCamPoints);
  set_program_now(program_name_);
}

bool ChannelOutputs::setpoints_discovered() const noexcept {
  const auto matched = [](const auto& writer) {
    return writer == nullptr || writer->matched_readers() >= 1;
  };
  return std::all_of(axis_setpoints_.begin(), axis_setpoints_.end(), matched) &&
         std::all_of(spindle_setpoints_.begin(), spindle_setpoints_.end(), matched);
}

void ChannelOutputs::set_program(std::string name) noexcept {
  program_name_ = std::move(name);
  set_program_now(program_name_);
}

void ChannelOutputs::set_program_now(std::string_view name) noexcept {
  const std::size_t n = std::min(name.size(), program_now_.size() - 1);
  std::copy_n(name.begin(), n, program_now_.begin());
  program_now_[n] = '\0';
}

const char* ChannelOutputs::channel_name(std::uint32_t id) const {
  return id >= 1 && id <= channel_names_.size() ? channel_names_[id - 1].c_str() : "?";
}

void ChannelOutputs::publish(std::uint64_t cycle, const ChannelController& controller,
                             const CycleOutput& out, std::span<const AxisFeedbackView> views,
                             std::uint32_t block_total, bool program_loaded) {
  // Shared variable writes first: a partner that sees this cycle's arrival has them.
  writes_.drain(
      [&](const SharedWrite& w) {
        CoordinationEvent e = event(cycle, COORD_VAR_WRITE);
        e.var(w.number);
        e.value(w.value.number());
        e.value_null(w.value.is_null());
        events_.write(e);
      },
      SharedWriteLog::kSentPerCycle);
  if (out.arrival_due) {
    CoordinationEvent e = event(cycle, COORD_SYNC_ARRIVE);
    e.p(out.arrival.p);
    e.generation(out.arrival.generation);
    e.all_channels(out.arrival.all_active);
    e.channels(to_mask(out.arrival.participants));
    events_.write(e);
  }
  if (out.call_due) {
    CoordinationEvent e = event(cycle, COORD_SUBCALL);
    e.call_id(out.call.call_id);
    e.caller(out.call.caller);
    e.target(out.call.target);
    e.program(out.call.program);
    e.wait(out.call.wait);
    e.repeat(out.call.repeat);
    for (std::size_t i = 0; i < out.call.args.size(); ++i) {
      e.args()[i] = out.call.args[i];
    }
    e.args_given(out.call.args_given);
    events_.write(e);
  }
  for (std::size_t r = 0; r < out.release_count; ++r) {
    CoordinationEvent e = event(cycle, COORD_SUBCALL_RELEASE);
    e.call_id(out.releases[r].call_id);
    e.caller(out.releases[r].caller);
    e.target(out.releases[r].target);
    e.outcome(static_cast<::mcnc::CallOutcome>(static_cast<int>(out.releases[r].outcome)));
    events_.write(e);
  }
  for (std::size_t r = 0; r < out.axis_request_count; ++r) {
    const AxisRequestOut& q = out.axis_requests[r];
    CoordinationEvent e = event(cycle, COORD_AXIS_REQUEST);
    e.axis_request(static_cast<::mcnc::AxisRequestKind>(static_cast<int>(q.kind)));
    e.axis(q.slot < axes_.size() ? static_cast<std::uint32_t>(axes_[q.slot]->id) : 0);
    e.force(q.force);
    events_.write(e);
    const bool one = q.slot < axes_.size();  // else every axis (G142)
    tracer_.emit(cycle, "axis_request",
                 "\"ch\":\"%s\",\"axis\":%s%s%s,\"request\":\"%s\",\"force\":%s",
                 channel_.name.c_str(), one ? "\"" : "", one ? axes_[q.slot]->name.c_str() : "null",
                 one ? "\"" : "", to_string(q.kind), q.force ? "true" : "false");
  }
  if (out.aux_due) {
    CoordinationEvent e = event(cycle, COORD_AUX_REQUEST);
    e.aux_id(out.aux.id);
    e.aux_kind(out.aux.kind == AuxKind::t_code ? AUX_T : AUX_M);
    e.aux_code(out.aux.code);
    const bool start = out.aux.kind == AuxKind::m_code && (out.aux.code == 3 || out.aux.code == 4);
    e.aux_spindle(start && !spindles_.empty() ? static_cast<std::uint32_t>(spindles_[0]->id) : 0);
    events_.write(e);
  }
  if (out.spindle_sync_due) {
    CoordinationEvent e = event(cycle, COORD_SPINDLE_SYNC);
    e.sync_on(out.spindle_sync.on);
    e.sync_group(out.spindle_sync.group);
    e.sync_p(out.spindle_sync.p);
    e.sync_q(out.spindle_sync.q);
    e.sync_r(out.spindle_sync.r);
    events_.write(e);
  }
  if (out.polygon_sync_due) {
    CoordinationEvent e = event(cycle, COORD_POLYGON_SYNC);
    e.sync_on(out.polygon_sync.on);
    e.sync_p(out.polygon_sync.p);
    e.sync_q(out.polygon_sync.q);
    e.sync_r(out.polygon_sync.r);
    events_.write(e);
  }
  if (out.cam_sync != nullptr) {
    const CamOut& cam = *out.cam_sync;
    CoordinationEvent& e = cam_event_;
    e.channel(static_cast<std::uint32_t>(channel_.id));
    e.seq(++event_seq_);
    e.cycle(cycle);
    e.kind(COORD_CAM_SYNC);
    e.sync_on(cam.on);
    e.sync_r(cam.r);
    e.cam_shape(cam.shape);
    e.cam_a(cam.a);
    e.cam_b(cam.b);
    e.cam_lift().assign(cam.lift.begin(),
                        cam.lift.begin() + static_cast<std::ptrdiff_t>(cam.points));
    events_.write(e);
  }
  if (out.egb_sync_due) {
    const EgbOut& g = out.egb_sync;
    CoordinationEvent e = event(cycle, COORD_EGB_SYNC);
    e.sync_on(g.on);
    e.sync_r(g.r);
    e.egb_teeth(g.teeth);
    e.egb_threads(g.threads);
    e.egb_helix(g.helix);
    e.egb_module(g.module);
    e.egb_phase(g.phase);
    e.egb_off(static_cast<std::uint8_t>(g.off));  // 0 G80.4, 1 a reset, 2 the hand-over
    events_.write(e);
  }
  if (out.axis_sync_due && out.axis_sync.slot < axes_.size()) {
    CoordinationEvent e = event(cycle, COORD_AXIS_SYNC);
    e.axis(static_cast<std::uint32_t>(axes_[out.axis_sync.slot]->id));
    e.sync_on(out.axis_sync.on);
    e.sync_master(out.axis_sync.master);
    events_.write(e);
  }
  // The setpoints after the events they announce: an axis node applies a G141 from the cycle
  // after it was sent, once it holds every event the setpoint announces.
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    if (i == c_slot_) {
      continue;  // the spindle's C axis: the spindle's setpoint below carries it
    }
    AxisSetpoint sp;
    sp.axis(static_cast<std::uint32_t>(axes_[i]->id));
    sp.channel(static_cast<std::uint32_t>(channel_.id));
    sp.cycle(cycle);
    sp.event_seq(event_seq_);
    sp.pos(out.setpoints[i].pos);
    sp.vel(out.setpoints[i].vel);
    sp.acc(out.setpoints[i].acc);
    sp.valid(out.setpoints[i].valid);
    sp.probe(static_cast<std::uint8_t>(out.setpoints[i].probe));
    sp.torque_limit(out.setpoints[i].torque_limit);
    sp.skip_deviation(out.setpoints[i].skip_deviation);
    sp.torque_mode(out.setpoints[i].torque_mode);
    sp.torque(out.setpoints[i].torque);
    sp.torque_speed(out.setpoints[i].torque_speed);
    axis_setpoints_[i]->write(sp);
  }
  const double rpm = out.spindle_rpm * out.spindle_direction;
  for (std::size_t i = 0; i < spindles_.size(); ++i) {
    AxisSetpoint sp;
    sp.axis(static_cast<std::uint32_t>(spindles_[i]->id));
    sp.channel(static_cast<std::uint32_t>(channel_.id));
    sp.cycle(cycle);
    sp.event_seq(event_seq_);
    if (i == 0 && out.spindle_position && c_slot_ < axes_.size()) {
      const CommandedAxis& c = out.setpoints[c_slot_];  // M18: C, in the spindle's degrees
      sp.pos(c.pos);
      sp.vel(c.vel);
      sp.acc(c.acc);
      sp.valid(c.valid);
      sp.mode(SP_POSITION);
    } else {
      sp.vel(i == 0 ? rpm * 6.0 : 0.0);  // rpm to degrees per second
      sp.valid(true);
      sp.mode(SP_VELOCITY);
    }
    spindle_setpoints_[i]->write(sp);
  }
  if (!spindles_.empty() && out.spindle_position != spindle_position_) {
    spindle_position_ = out.spindle_position;
    tracer_.emit(cycle, "spindle_mode", "\"ch\":\"%s\",\"spindle\":\"%s\",\"mode\":\"%s\"",
                 channel_.name.c_str(), spindles_[0]->name.c_str(),
                 spindle_position_ ? "position" : "speed");
  }
  if (!spindles_.empty() && rpm != spindle_rpm_) {
    spindle_rpm_ = rpm;
    tracer_.emit(cycle, "spindle", "\"ch\":\"%s\",\"spindle\":\"%s\",\"rpm\":%.3f",
                 channel_.name.c_str(), spindles_[0]->name.c_str(), rpm);
  }
  ::mcnc::ChannelStatus status;
  status.channel(static_cast<std::uint32_t>(channel_.id));
  status.call_id(controller.serving_call());
  status.call_caller(controller.serving_caller());
  status.cycle(cycle);
  status.event_seq(event_seq_);
  const coordination::SyncArrival& mark = controller.sync().current();
  status.sync_p(mark.p);
  status.sync_generation(mark.generation);
  status.sync_all(mark.all_active);
  status.sync_channels(to_mask(mark.participants));
  status.sync_waiting_for(out.state == ChannelState::waiting && controller.sync().waiting()
                              ? to_mask(controller.sync().missing())
                              : 0);
  status.state(to_wire(out.state));
  status.block(static_cast<std::uint32_t>(out.block));
  status.block_total(block_total);
  status.line(out.line);
  status.alarms(static_cast<std::uint32_t>(controller.alarm_count()));
  status.program_loaded(program_loaded);
  status.program_end(out.program_end);
  status.end_code(out.end_code);
  status.run_start_cycle(out.run_start_cycle);
  status.end_cycle(out.end_cycle);
  status.feed_override(controller.feed_override() * 100.0);
  status.rapid_override(controller.rapid_override() * 100.0);
  status.spindle_override(controller.spindle_override() * 100.0);
  status.single_block(controller.single_block());
  status.spindle_rpm(rpm);
  status.call_waiting_for(controller.waiting_for_call());
  const AuxRequestOut* fin = controller.waiting_for_fin();
  status.waiting_m(fin != nullptr && fin->kind == AuxKind::m_code ? fin->code : -1);
  status.waiting_t(fin != nullptr && fin->kind == AuxKind::t_code ? fin->code : -1);
  const ChannelController::ExchangeWait exchange = controller.waiting_for_exchange();
  status.waiting_exchange(static_cast<std::int16_t>(exchange.g));
  status.waiting_axis(exchange.g != 0 && exchange.slot < axes_.size()
                          ? static_cast<std::uint32_t>(axes_[exchange.slot]->id)
                          : 0);
  std::copy(out.modal.g.begin(), out.modal.g.end(), status.modal_g().begin());
  status.modal_feed(out.modal.feed);

  out_call_ = out.call;
  for (std::size_t e = 0; e < out.event_count; ++e) {
    record(cycle, controller, out.events[e], views);
  }
  status.program(program_now_);  // after the records: this cycle's block's file
  status_.write(status);
}

CoordinationEvent ChannelOutputs::event(std::uint64_t cycle, CoordinationKind kind) {
  CoordinationEvent e;
  e.channel(static_cast<std::uint32_t>(channel_.id));
  e.seq(++event_seq_);
  e.cycle(cycle);
  e.kind(kind);
  return e;
}

void ChannelOutputs::record(std::uint64_t cycle, const ChannelController& controller,
                            const ChannelEvent& event, std::span<const AxisFeedbackView> views) {
  const char* ch = channel_.name.c_str();
  switch (event.kind) {
    case ChannelEventKind::state_changed:
      tracer_.emit(cycle, "state", "\"ch\":\"%s\",\"state\":\"%s\"", ch, to_string(event.state));
      break;
    case ChannelEventKind::block_started: {
      // The block's line as the interpreter read it; a block of another file (a subprogram
      // from the program directory, MDI blocks) with that file's name. Nothing is read or
      // built here: a block start is in the cycle.
      std::string_view name = program_name_;
      if (event.file != nullptr && *event.file != program_name_) {
        name = *event.file;
        name.remove_prefix(std::min(name.size(), name.find_last_of('/') + 1));
      }
      trace::json_escape(event.text, escaped_, sizeof escaped_);
      // A selected program's name comes from the operator: escaped like the text.
      trace::json_escape(name, escaped_name_, sizeof escaped_name_);
      tracer_.emit(cycle, "block", "\"ch\":\"%s\",\"prog\":\"%s\",\"line\":%d,\"text\":\"%s\"", ch,
                   escaped_name_, event.line, escaped_);
      set_program_now(name);
      break;
    }
    case ChannelEventKind::block_ended:
      for (std::size_t i = 0; i < axes_.size(); ++i) {
        const double base = i == c_slot_ ? controller.spindle_c_base() : 0.0;
        tracer_.emit(cycle, "pos", "\"axis\":\"%s\",\"cmd\":%.6f,\"act\":%.6f",
                     axes_[i]->name.c_str(), event.pos[i],
                     i < views.size() ? views[i].act - base : 0.0);
      }
      break;
    case ChannelEventKind::alarm: {
      const ChannelAlarm& alarm = controller.last_alarm();
      trace::json_escape(alarm.text.data(), escaped_, sizeof escaped_);
      // `axis` counts the channel's axes, then its spindles.
      const auto index = static_cast<std::size_t>(alarm.axis > 0 ? alarm.axis - 1 : 0);
      const config::AxisConfig* axis = alarm.axis <= 0        ? nullptr
                                       : index < axes_.size() ? axes_[index]
                                       : index - axes_.size() < spindles_.size()
                                           ? spindles_[index - axes_.size()]
                                           : nullptr;
      // An alarm in a program names its file as a block does (`prog`), and its column when
      // known; the wire carries the file as the channel read it (a called program's path).
      const char* file = alarm.file[0] != '\0' ? alarm.file.data() : program_name_.c_str();
      const std::string_view name(file);
      char place[sizeof escaped_name_ + 48] = {};
      if (alarm.line > 0) {
        trace::json_escape(name.substr(std::min(name.size(), name.find_last_of('/') + 1)),
                           escaped_name_, sizeof escaped_name_);
        const int used = std::snprintf(place, sizeof place, ",\"prog\":\"%s\"", escaped_name_);
        if (alarm.column > 0 && used > 0 && static_cast<std::size_t>(used) < sizeof place) {
          std::snprintf(place + used, sizeof place - static_cast<std::size_t>(used), ",\"col\":%d",
                        alarm.column);
        }
      }
      // The alarm's source is the event's own "src".
      if (axis != nullptr) {
        tracer_.emit(cycle, "alarm",
                     "\"number\":%d,\"text\":\"%s\",\"ch\":\"%s\",\"axis\":\"%s\",\"line\":%d%s",
                     alarm.number, escaped_, ch, axis->name.c_str(), alarm.line, place);
      } else {
        tracer_.emit(cycle, "alarm", "\"number\":%d,\"text\":\"%s\",\"ch\":\"%s\",\"line\":%d%s",
                     alarm.number, escaped_, ch, alarm.line, place);
      }
      node_.raise_alarm(static_cast<std::uint32_t>(alarm.number), alarm.text.data(), cycle,
                        channel_.id, axis != nullptr ? axis->id : 0, alarm.line, alarm.column,
                        alarm.line > 0 ? file : nullptr);
      break;
    }
    case ChannelEventKind::sync_arrive: {
      const coordination::SyncArrival& a = controller.sync().current();
      char list[4 * coordination::kMaxChannels + 1] = {};
      std::size_t used = 0;
      for (std::uint32_t c = 1; c <= coordination::kMaxChannels; ++c) {
        if (a.participants.test(c) && used + 4 < sizeof list) {
          used += static_cast<std::size_t>(
              std::snprintf(list + used, sizeof list - used, used == 0 ? "%u" : ",%u", c));
        }
      }
      tracer_.emit(cycle, "sync_arrive",
                   "\"ch\":\"%s\",\"p\":%d,\"channels\":[%s],\"all\":%s,\"gen\":%llu", ch, a.p,
                   list, a.all_active ? "true" : "false",
                   static_cast<unsigned long long>(a.generation));
      break;
    }
    case ChannelEventKind::sync_release: {
      const coordination::SyncArrival& a = controller.sync().current();
      tracer_.emit(cycle, "sync_release", "\"ch\":\"%s\",\"p\":%d,\"gen\":%llu", ch, a.p,
                   static_cast<unsigned long long>(a.generation));
      break;
    }
    case ChannelEventKind::subcall: {
      const CallRequest& call = out_call_;
      tracer_.emit(cycle, "subcall",
                   "\"caller\":\"%s\",\"target\":\"%s\",\"program\":%d,\"call_id\":%llu,"
                   "\"wait\":%s",
                   ch, channel_name(call.target), call.program,
                   static_cast<unsigned long long>(call.call_id), call.wait ? "true" : "false");
      break;
    }
    case ChannelEventKind::subcall_release:
      tracer_.emit(cycle, "subcall_release", "\"ch\":\"%s\",\"call_id\":%llu,\"outcome\":\"%s\"",
                   ch, static_cast<unsigned long long>(event.call_id),
                   to_string(event.call_outcome));
      break;
    case ChannelEventKind::mdi_end:
      tracer_.emit(cycle, "mdi_end", "\"ch\":\"%s\",\"code\":%d", ch, event.end_code);
      break;
    case ChannelEventKind::program_end:
      tracer_.emit(cycle, "end", "\"ch\":\"%s\",\"code\":%d", ch, event.end_code);
      spdlog::debug("program end M{:02d} at cycle {}", event.end_code, cycle);
      break;
  }
}

}  // namespace mcnc::channel
