#include "axisnode/node/axis_node.hpp"

#include <cmath>

namespace mcnc::axisnode {

namespace {

// The gate's inputs: the candidates, then (G114.1) the coupling channel and the master spindle.
std::size_t gate_inputs(const AxisNodeRoles& roles) {
  return roles.candidates.size() + (roles.sync_master != 0 ? 2 : 0);
}

// Long enough for a master that runs ahead of its slave's channel (a minute at 1 ms).
constexpr std::size_t kLeaderHistory = std::size_t{1} << 16;

// deg/s: a tool spindle slower than this stands (a reset's G81.4 lets go then, param 5320.4).
constexpr double kToolStands = 0.6;

}  // namespace

AxisNode::AxisNode(const AxisNodeRoles& roles)
    : roles_(roles),
      watches_events_(roles.exchangeable || roles.may_follow),
      gate_(gate_inputs(roles)),
      from_(cycle::tracked_inputs<SetpointSample>(0, roles.candidates.size())),
      sync_channel_(roles.candidates.size()),
      master_feedback_(roles.candidates.size() + 1),
      master_history_(roles.leaders, roles.may_follow || roles.egb_axial != 0 ? kLeaderHistory : 1),
      ownership_(roles.home),
      spindle_coupling_(roles.spindle_coupling),
      axis_coupling_(roles.cycle_s),
      cam_coupling_(roles.cam_coupling),
      gear_box_(roles.gear_box),
      controller_(roles.controller),
      owner_now_(roles.home),
      following_(0) {
  leader_writers_.reserve(roles.leaders.size());
  if (roles.power_on_master != 0) {
    axis_coupling_.couple(roles.power_on_master);  // a gantry from power-on
  }
}

int AxisNode::candidate_of(std::uint32_t channel) const noexcept {
  for (std::size_t k = 0; k < roles_.candidates.size(); ++k) {
    if (roles_.candidates[k] == channel) {
      return static_cast<int>(k);
    }
  }
  return -1;
}

void AxisNode::on_setpoint(std::uint32_t channel, std::uint32_t axis, const SetpointSample& sample,
                           std::uint64_t announced_event_seq, const WriterId& writer) noexcept {
  const int k = axis == roles_.axis ? candidate_of(channel) : -1;
  if (k < 0) {
    return;
  }
  from_[static_cast<std::size_t>(k)].on_sample(
      sample, sample.cycle, watches_events_ ? announced_event_seq : 0, writer, gate_);
}

void AxisNode::on_setpoint_writer_gone(const WriterId& writer) noexcept {
  for (std::size_t k = 0; k < from_.size(); ++k) {
    if (from_[k].on_unmatched(writer, gate_)) {
      owner_lost_ = owner_lost_ || roles_.candidates[k] == owner_now_;
    }
  }
}

void AxisNode::on_event(const AxisNodeEvent& e) noexcept {
  if (!hears_from(e.channel)) {
    return;
  }
  const int k = candidate_of(e.channel);
  const bool from_sync_channel = coupled_spindle() && e.channel == roles_.sync_channel;
  if (k >= 0 && watches_events_) {
    from_[static_cast<std::size_t>(k)].on_event(e.seq, gate_);
  }
  if (roles_.may_follow && e.kind == AxisNodeEvent::Kind::axis_sync && e.axis == roles_.axis &&
      e.channel == roles_.home) {
    (void)axis_syncs_.push(AxisSyncRequest{e.sync_on, e.sync_on ? e.sync_master : 0}, e.cycle);
  }
  if (from_sync_channel) {
    sync_channel_.on_event(e.seq, gate_);
    const bool polygon = e.kind == AxisNodeEvent::Kind::polygon_sync && roles_.polygon;
    if (e.kind == AxisNodeEvent::Kind::cam_sync && roles_.cam) {
      (void)cams_.push(CamRequest{e.sync_on, e.cam}, e.cycle);
    }
    if (e.kind == AxisNodeEvent::Kind::egb_sync && roles_.egb) {
      (void)egbs_.push(EgbRequest{e.sync_on, e.egb, e.egb_off}, e.cycle);
    }
    const bool spindle_sync =
        e.kind == AxisNodeEvent::Kind::spindle_sync && !roles_.polygon && !roles_.cam &&
        !roles_.egb && (e.sync_group == roles_.sync_group || (!e.sync_on && e.sync_group == 0));
    if (polygon || spindle_sync) {
      (void)spindle_syncs_.push(SpindleSyncRequest{e.sync_on, e.spindle}, e.cycle);
    }
  }
  if (k < 0 || !roles_.exchangeable || e.kind != AxisNodeEvent::Kind::axis_request ||
      (e.axis != roles_.axis && e.axis != 0)) {
    return;
  }
  if (!requests_.push(ownership::OwnershipRequest{e.request, e.channel, e.force, e.cycle},
                      e.cycle)) {
    ++requests_dropped_;
  }
}

void AxisNode::on_sync_channel_status(std::uint32_t channel, std::uint64_t cycle,
                                      std::uint64_t announced_event_seq,
                                      const WriterId& writer) noexcept {
  if (coupled_spindle() && channel == roles_.sync_channel) {
    sync_channel_.on_sample(cycle, cycle, announced_event_seq, writer, gate_);
  }
}

void AxisNode::on_sync_channel_gone(const WriterId& writer) noexcept {
  (void)sync_channel_.on_unmatched(writer, gate_);  // the coupling stays as it is
}

void AxisNode::on_master_feedback(std::uint32_t axis, std::uint64_t cycle, double act, double vel,
                                  double cmd, const WriterId& writer) noexcept {
  if (coupled_spindle() && axis == roles_.sync_master) {
    master_feedback_.on_sample(MasterSample{act, vel, cmd}, cycle, 0, writer, gate_);
  }
}

void AxisNode::on_master_gone(const WriterId& writer) noexcept {
  (void)master_feedback_.on_unmatched(writer, gate_);
}

void AxisNode::on_leader_feedback(std::uint32_t axis, std::uint64_t cycle, double cmd,
                                  bool operating, const WriterId& writer) noexcept {
  if (!master_history_.may_lead(axis)) {
    return;
  }
  master_history_.put(axis, cycle, cmd, operating);
  for (const LeaderWriter& w : leader_writers_) {
    if (w.axis == axis) {
      return;
    }
  }
  if (leader_writers_.size() < roles_.leaders.size()) {
    leader_writers_.push_back(LeaderWriter{writer, axis});
  }
}

void AxisNode::on_leader_gone(const WriterId& writer) noexcept {
  for (const LeaderWriter& w : leader_writers_) {
    if (w.writer == writer) {
      master_history_.gone(w.axis);
    }
  }
}

std::uint32_t AxisNode::axis_master_at(std::uint64_t cycle) const noexcept {
  std::uint32_t m = axis_coupling_.master();
  axis_syncs_.peek_due(cycle, [&](const AxisSyncRequest& r) { m = r.on ? r.master : 0; });
  return m;
}

bool AxisNode::ready(std::uint64_t cycle) const noexcept {
  if (cycle == 0) {
    return true;
  }
  if (!gate_.may_run(cycle)) {
    return false;
  }
  if (waits_for_axial(cycle)) {
    return false;
  }
  const std::uint32_t m = roles_.may_follow ? axis_master_at(cycle) : 0;
  return m == 0 ||
         master_history_.at(m, cycle - 1).lookup != coupling::MasterHistory::Lookup::not_yet;
}

bool AxisNode::waits_for_axial(std::uint64_t cycle) const noexcept {
  if (roles_.egb_axial == 0 || cycle == 0 ||
      master_history_.at(roles_.egb_axial, cycle - 1).lookup !=
          coupling::MasterHistory::Lookup::not_yet) {
    return false;
  }
  bool on = gear_box_.active();
  egbs_.peek_due(cycle, [&](const EgbRequest& r) { on = on || r.on; });
  return on;
}

std::optional<AxisNode::InputWait> AxisNode::input_wait(std::uint64_t cycle) const noexcept {
  if (cycle == 0) {
    return std::nullopt;
  }
  if (const auto g = gate_.wait(cycle)) {
    InputWait w;
    w.gate = *g;
    if (g->input < roles_.candidates.size()) {
      w.id = roles_.candidates[g->input];
    } else if (g->input == roles_.candidates.size()) {
      w.from = InputWait::From::coupling_channel;
      w.id = roles_.sync_channel;
    } else {
      w.from = InputWait::From::master;
      w.id = roles_.sync_master;
    }
    return w;
  }
  if (ready(cycle)) {
    return std::nullopt;
  }
  InputWait w;
  w.from = InputWait::From::leader;
  w.id = waits_for_axial(cycle) ? roles_.egb_axial : axis_master_at(cycle);
  return w;
}

const SetpointSample* AxisNode::setpoint_of(std::uint32_t channel, std::uint64_t cycle,
                                            bool lockstep) const noexcept {
  const int k = candidate_of(channel);
  if (k < 0 || cycle == 0) {
    return nullptr;
  }
  const cycle::TrackedInput<SetpointSample>& c = from_[static_cast<std::size_t>(k)];
  if (const SetpointSample* s = c.for_cycle(cycle, true)) {
    return s;
  }
  // Realtime: the latest only while it is no older than the last cycle's.
  const SetpointSample* latest = c.latest();
  return !lockstep && latest != nullptr && latest->cycle >= cycle - 1 ? latest : nullptr;
}

void AxisNode::happened(const AxisNodeHappening& h) noexcept {
  if (happened_count_ < happened_.size()) {
    happened_[happened_count_++] = h;
  }
}

ownership::OwnershipChange AxisNode::decide_owner(std::uint64_t cycle, bool lockstep) noexcept {
  ownership::OwnershipChange change;
  if (roles_.exchangeable) {
    // Every request sent before this cycle, whatever order they arrived in (the core puts them
    // in decision order).
    requests_.take_due(cycle, [&](const ownership::OwnershipRequest& r) {
      if (!ownership_.request(r)) {
        ++requests_dropped_;
      }
    });
    for (std::size_t k = 0; k < from_.size(); ++k) {
      if (from_[k].lost()) {
        ownership_.channel_gone(roles_.candidates[k]);
      }
    }
    // At rest: the owner commands no motion and the axis stands in position (a forced G141 or a
    // G142 waits for the owner's move to end). An owner that is gone is not at rest: its axis
    // is stopped by the node's safety and nobody takes it over.
    const int owner_k = candidate_of(ownership_.owner());
    const bool owner_gone = owner_k >= 0 && from_[static_cast<std::size_t>(owner_k)].lost();
    const SetpointSample* current = setpoint_of(ownership_.owner(), cycle, lockstep);
    const AxisNodeOutput& last = controller_.output();
    const bool at_rest =
        !owner_gone &&
        (current == nullptr || !current->valid || (current->vel == 0.0 && current->acc == 0.0)) &&
        std::abs(last.cmd - last.act) <= roles_.in_position;
    change = ownership_.decide(at_rest);
    owner_now_ = ownership_.owner();
    const int k = candidate_of(owner_now_);
    owner_lost_ = k >= 0 && from_[static_cast<std::size_t>(k)].lost();
  }
  SetpointSample sp;
  bool have = false;
  if (owner_now_ == 0) {
    have = true;  // released: nobody commands the axis, it holds where it is
  } else if (const SetpointSample* s = setpoint_of(owner_now_, cycle, lockstep)) {
    sp = *s;
    have = true;
  }
  in_.have_setpoint = have;
  in_.setpoint_pos = sp.pos;
  in_.setpoint_vel = sp.vel;
  // A new owner's setpoint from before it knew is not followed (it holds, too).
  in_.setpoint_valid = sp.valid && !change.changed && owner_now_ != 0;
  in_.setpoint_velocity = sp.velocity;
  in_.probe = in_.setpoint_valid ? sp.probe : ProbeRequest::off;
  in_.torque_limit = sp.torque_limit;
  in_.skip_deviation = sp.skip_deviation;
  in_.torque_mode = sp.torque_mode;
  in_.torque = sp.torque;
  in_.torque_speed = sp.torque_speed;
  in_.owner_lost = owner_lost_;
  return change;
}

void AxisNode::apply_spindle_sync(std::uint64_t cycle, bool lockstep) noexcept {
  using Kind = AxisNodeHappening::Kind;
  spindle_syncs_.take_due(cycle, [&](const SpindleSyncRequest& r) {
    if (r.on) {
      const coupling::SpindleCouplingCommand c =
          roles_.polygon ? coupling::polygon_command(r.command.p, r.command.q, r.command.r)
                         : r.command;
      spindle_coupling_.couple(c, controller_.output().act, controller_.output().vel);
      happened(AxisNodeHappening{roles_.polygon ? Kind::polygon_coupled : Kind::spindle_coupled, 0,
                                 0, false, roles_.sync_master, r.command});
    } else if (roles_.polygon) {
      spindle_coupling_.release();  // told once the axis stands
    } else if (spindle_coupling_.active()) {
      spindle_coupling_.decouple();
      happened(AxisNodeHappening{Kind::spindle_decoupled, 0, 0, false, roles_.sync_master, {}});
    }
  });
  if (!spindle_coupling_.active()) {
    return;
  }
  // While coupled, the slave follows its master whatever its owner sends; without its master
  // it holds where it is. A polygon axis being released slows down without it.
  const MasterSample* m = master_feedback_.for_cycle(cycle, lockstep);
  const bool have_master = m != nullptr && !master_feedback_.lost();
  const bool releasing = spindle_coupling_.releasing();
  in_.have_setpoint = true;
  in_.setpoint_valid = have_master || releasing;
  in_.setpoint_velocity = false;
  if (have_master || releasing) {
    // The master's position of this cycle, from its feedback of the last one.
    const coupling::SlaveTarget t =
        have_master ? spindle_coupling_.step(m->act + m->vel * roles_.cycle_s, m->vel)
                    : spindle_coupling_.step(0.0, 0.0);
    in_.setpoint_pos = t.pos;
    in_.setpoint_vel = t.vel;
  }
  if (releasing && !spindle_coupling_.active()) {
    happened(AxisNodeHappening{Kind::polygon_decoupled, 0, 0, false, roles_.sync_master, {}});
  }
}

void AxisNode::apply_axis_sync(std::uint64_t cycle, bool lockstep) noexcept {
  axis_syncs_.take_due(cycle, [&](const AxisSyncRequest& r) {
    const std::uint32_t before = axis_coupling_.master();
    const std::uint32_t after = r.on && master_history_.may_lead(r.master) ? r.master : 0;
    if (after == before) {
      return;
    }
    if (before != 0) {
      axis_coupling_.decouple();
      happened(AxisNodeHappening{AxisNodeHappening::Kind::axis_decoupled, 0, 0, false, before, {}});
    }
    if (after != 0) {
      axis_coupling_.couple(after);
      happened(AxisNodeHappening{AxisNodeHappening::Kind::axis_coupled, 0, 0, false, after, {}});
    }
  });
  if (!axis_coupling_.active()) {
    return;
  }
  // While coupled, the slave copies its master's increments while both are in operation;
  // otherwise it holds, and starts again from where both stand.
  const coupling::MasterHistory::Sample m =
      master_history_.estimate(axis_coupling_.master(), cycle, lockstep);
  in_.have_setpoint = true;
  in_.setpoint_velocity = false;
  in_.setpoint_valid = false;
  if (m.lookup == coupling::MasterHistory::Lookup::found && m.operating &&
      controller_.output().enabled) {
    const coupling::AxisTarget t = axis_coupling_.step(m.cmd, controller_.output().cmd);
    in_.setpoint_pos = t.pos;
    in_.setpoint_vel = t.vel;
    in_.setpoint_valid = true;
  } else {
    axis_coupling_.rebase();
  }
}

void AxisNode::apply_cam(std::uint64_t cycle, bool lockstep) noexcept {
  using Kind = AxisNodeHappening::Kind;
  cams_.take_due(cycle, [&](const CamRequest& r) {
    if (!r.on) {
      cam_coupling_.release();  // told once the lift is off
    } else if (coupling::cam_profile_error(r.profile) != nullptr) {
      happened(AxisNodeHappening{Kind::cam_refused, 0, 0, false, roles_.sync_master, {}});
    } else {
      cam_coupling_.couple(r.profile);
      happened(AxisNodeHappening{Kind::cam_coupled, 0, 0, false, roles_.sync_master, {}});
    }
  });
  // The lift is laid over what the owner commands, while it commands the axis: a setpoint that
  // holds (a reset, an alarm) holds the lift where it is too.
  if (!cam_coupling_.active() || !in_.have_setpoint || !in_.setpoint_valid ||
      in_.setpoint_velocity) {
    return;
  }
  const MasterSample* m = master_feedback_.for_cycle(cycle, lockstep);
  // The master's angle of this cycle, from its feedback of the last one.
  const coupling::CamOffset o = m != nullptr && !master_feedback_.lost()
                                    ? cam_coupling_.step(m->act + m->vel * roles_.cycle_s)
                                    : cam_coupling_.step_without_master();
  in_.setpoint_pos += o.pos;
  in_.setpoint_vel += o.vel;
  if (!cam_coupling_.active()) {
    happened(AxisNodeHappening{Kind::cam_decoupled, 0, 0, false, roles_.sync_master, {}});
  }
}

void AxisNode::stop_egb(AxisNodeHappening::EgbStop why) noexcept {
  if (gear_box_.active() && !gear_box_.releasing()) {
    egb_stopping_ = why;
    gear_box_.release();
  }
}

void AxisNode::apply_egb(std::uint64_t cycle, bool lockstep) noexcept {
  using Kind = AxisNodeHappening::Kind;
  using Stop = AxisNodeHappening::EgbStop;
  // The tool spindle's angle of this cycle, from its feedback of the last one: its actual
  // angle (follow mode), or its commanded one (synchronous mode, param 5320.1; in speed mode the
  // two are one).
  const MasterSample* m = master_feedback_.for_cycle(cycle, lockstep);
  const bool have_tool = m != nullptr && !master_feedback_.lost();
  const double tool_vel = have_tool ? m->vel : 0.0;
  const double tool_deg =
      have_tool ? (roles_.egb_synchronous ? m->cmd : m->act) + m->vel * roles_.cycle_s : 0.0;
  // The axial axis's commanded position of this cycle and its speed, as a G51.4 leader's.
  double axial = 0.0;
  double axial_vel = 0.0;
  if (roles_.egb_axial != 0 && cycle > 0) {
    const auto now = master_history_.estimate(roles_.egb_axial, cycle, lockstep);
    const auto before = master_history_.estimate(roles_.egb_axial, cycle - 1, lockstep);
    if (now.lookup == coupling::MasterHistory::Lookup::found) {
      axial = now.cmd;
      axial_vel = before.lookup == coupling::MasterHistory::Lookup::found
                      ? (now.cmd - before.cmd) / roles_.cycle_s
                      : 0.0;
    }
  }
  const bool commanded = in_.have_setpoint && in_.setpoint_valid && !in_.setpoint_velocity;
  if (commanded) {
    egb_base_ = in_.setpoint_pos;
  }
  egbs_.take_due(cycle, [&](const EgbRequest& r) {
    if (r.on && coupling::gear_box_command_error(r.command) != nullptr) {
      happened(AxisNodeHappening{Kind::egb_refused, 0, 0, false, roles_.sync_master, {}});
    } else if (r.on) {
      gear_box_.couple(r.command, tool_deg, axial, egb_base_);
      egb_release_when_tool_stands_ = false;
      happened(AxisNodeHappening{Kind::egb_coupled, 0, 0, false, roles_.sync_master, {}});
    } else if (r.off == AxisNodeEvent::EgbOff::absorb) {
      if (!gear_box_.active() && gear_box_.offset() != 0.0) {
        gear_box_.absorb();
        happened(AxisNodeHappening{Kind::egb_absorbed, 0, 0, false, roles_.sync_master, {}});
      }
    } else if (r.off == AxisNodeEvent::EgbOff::reset && !roles_.egb_reset_at_once) {
      // Param 5320.4 = 0: the gear holds until the tool spindle stands, then lets go.
      egb_release_when_tool_stands_ = gear_box_.active();
    } else {
      stop_egb(r.off == AxisNodeEvent::EgbOff::reset ? Stop::reset : Stop::program);
    }
  });
  if (!gear_box_.active()) {
    // Stopped: the offset stays laid over the channel's setpoint until it takes it over.
    if (commanded) {
      in_.setpoint_pos += gear_box_.offset();
    }
    return;
  }
  // A missing setpoint is the node's deadline's business: the gear box waits for it.
  if (!in_.have_setpoint || in_.setpoint_velocity) {
    return;
  }
  if (egb_release_when_tool_stands_ && std::fabs(tool_vel) < kToolStands) {
    stop_egb(Stop::reset);
  }
  if (!have_tool) {
    stop_egb(Stop::tool_lost);
  }
  const bool was_releasing = gear_box_.releasing();
  const coupling::GearBoxOffset o = have_tool ? gear_box_.step(tool_deg, tool_vel, axial, axial_vel)
                                              : gear_box_.step_without_master();
  if (!was_releasing && gear_box_.deviation_alarm()) {
    egb_stopping_ = Stop::deviation;  // the coupling stops itself (5336/5337)
  }
  // The gear box runs on whatever the channel does: a reset's hold keeps its last setpoint.
  in_.setpoint_valid = true;
  in_.setpoint_pos = egb_base_ + o.pos;
  in_.setpoint_vel = (commanded ? in_.setpoint_vel : 0.0) + o.vel;
  if (!gear_box_.active()) {
    AxisNodeHappening h{Kind::egb_stopped, 0, 0, false, roles_.sync_master, {}};
    h.egb_stop = egb_stopping_;
    h.at = gear_box_.offset();
    happened(h);
  }
}

void AxisNode::take_inputs(std::uint64_t cycle, bool lockstep) noexcept {
  happened_count_ = 0;
  in_ = AxisNodeInput{};
  const ownership::OwnershipChange change = decide_owner(cycle, lockstep);
  if (coupled_spindle() && !roles_.cam && !roles_.egb) {
    apply_spindle_sync(cycle, lockstep);
  }
  if (roles_.may_follow) {
    apply_axis_sync(cycle, lockstep);
  }
  if (roles_.cam) {
    apply_cam(cycle, lockstep);
  }
  if (roles_.egb) {
    apply_egb(cycle, lockstep);
  }
  // The owner's change is told after the couplings' (the order the trace has always had).
  if (change.changed) {
    happened(AxisNodeHappening{
        AxisNodeHappening::Kind::owner, change.owner, change.previous, change.forced, 0, {}});
  }
  const std::uint32_t follows = in_.have_setpoint && in_.setpoint_valid ? owner_now_ : 0;
  if (follows != following_) {
    following_ = follows;
    happened(AxisNodeHappening{AxisNodeHappening::Kind::follows, follows, 0, false, 0, {}});
  }
}

std::uint32_t AxisNode::commanding_channel() const noexcept {
  return owner_now_ != 0 ? owner_now_ : roles_.home;
}

const AxisNodeOutput& AxisNode::step(std::uint64_t cycle, const DriveReadings& drive,
                                     bool emergency_stop, bool paced_best_effort) noexcept {
  in_.have_tpdo = drive.have_tpdo;
  in_.statusword = drive.statusword;
  in_.position_counts = drive.position_counts;
  in_.mode_display = drive.mode_display;
  in_.heartbeats = drive.heartbeats;
  in_.bus_off = drive.bus_off;
  in_.foreign_syncs = drive.foreign_syncs;
  in_.touch_probe_status = drive.touch_probe_status;
  in_.probe_positive = drive.probe_positive;
  in_.probe_negative = drive.probe_negative;
  in_.torque_actual = drive.torque_actual;
  in_.emergency_stop = emergency_stop;
  in_.paced_best_effort = paced_best_effort;
  return controller_.cycle(cycle, in_);
}

AxisNodeStanding AxisNode::standing() const noexcept {
  AxisNodeStanding s;
  s.owner = owner_now_;
  s.released_by = ownership_.released_by();
  s.coupled_to = spindle_coupling_.active() || cam_coupling_.active() || gear_box_.active()
                     ? roles_.sync_master
                     : axis_coupling_.master();
  s.coupling_locked = spindle_coupling_.locked() || axis_coupling_.active() ||
                      cam_coupling_.locked() || gear_box_.locked();
  s.refused_channels = ownership_.refused_channels();
  s.full_channels = ownership_.full_channels();
  return s;
}

}  // namespace mcnc::axisnode
