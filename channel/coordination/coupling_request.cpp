#include "channel/coordination/coupling_request.hpp"

#include <cmath>

namespace mcnc::coordination {

namespace {

// deg/s: a spindle (a polygon axis, a tool spindle) slower than this stands (a tenth of a
// revolution per minute).
constexpr double kSpindleAtRest = 0.6;

// A coupling of a slave to its master spindle (G51.2, G51.8) has answered: `on`, the slave at
// `view` follows `master` locked (in phase, on its lift); off, it follows nothing.
bool slave_answered(std::span<const AxisFeedbackView> feedback, std::size_t view,
                    std::uint32_t master, bool on) noexcept {
  if (view >= feedback.size()) {
    return false;
  }
  const AxisFeedbackView& slave = feedback[view];
  return on ? slave.coupled_to == master && slave.coupling_locked : slave.coupled_to == 0;
}

}  // namespace

void CouplingRequest::begin_spindle(const SpindleSyncOut& sync) noexcept {
  kind_ = CouplingKind::spindle;
  spindle_ = sync;
  sent_ = false;
  change_ = {};
}

void CouplingRequest::begin_axis(bool on, std::uint32_t master, std::uint32_t slave) noexcept {
  kind_ = CouplingKind::axis;
  axis_sync_ = AxisSyncOut{on, 0, master};
  slave_ = slave;
  sent_ = false;
  change_ = {};
}

void CouplingRequest::begin_polygon(const PolygonOut& polygon) noexcept {
  kind_ = CouplingKind::polygon;
  polygon_ = polygon;
  sent_ = false;
  change_ = {};
}

void CouplingRequest::begin_cam(const CamOut& cam) noexcept {
  kind_ = CouplingKind::cam;
  cam_ = cam;
  sent_ = false;
  change_ = {};
}

void CouplingRequest::begin_egb(const EgbOut& egb) noexcept {
  kind_ = CouplingKind::egb;
  egb_ = egb;
  sent_ = false;
  change_ = {};
}

CouplingStep CouplingRequest::step(const CouplingInputs& in) noexcept {
  if (!sent_) {
    const Start start = kind_ == CouplingKind::axis      ? start_axis(in)
                        : kind_ == CouplingKind::polygon ? start_polygon(in)
                        : kind_ == CouplingKind::cam     ? start_cam(in)
                        : kind_ == CouplingKind::egb     ? start_egb(in)
                                                         : start_spindle();
    if (start == Start::refused) {
      return CouplingStep::alarm;
    }
    if (start == Start::send) {
      polygon_asked_ = kind_ == CouplingKind::polygon ? polygon_.on : polygon_asked_;
      cam_asked_ = kind_ == CouplingKind::cam ? cam_.on : cam_asked_;
      if (kind_ == CouplingKind::egb) {
        egb_asked_ = egb_.on;
        egb_sent_cycle_ = in.cycle;
      }
      if (kind_ == CouplingKind::polygon) {
        polygon_lock_due_ = polygon_.on && setup_.polygon.no_wait
                                ? std::optional<std::uint64_t>(in.cycle)
                                : std::nullopt;
      } else if (kind_ == CouplingKind::egb) {
        egb_lock_due_ =
            egb_.on && setup_.egb.no_wait ? std::optional<std::uint64_t>(in.cycle) : std::nullopt;
      }
      sent_ = true;
      sent_cycle_ = in.cycle;
      return CouplingStep::send;
    }
    return CouplingStep::done;
  }
  if (kind_ == CouplingKind::polygon && !polygon_.on && !polygon_.wait &&
      !setup_.polygon.slave_axis) {
    // G50.2 P0: the program goes on while the spindle slows down. A servo polygon axis is
    // waited for: the program goes on from where it stands (decision 158).
    return CouplingStep::done;
  }
  if (kind_ == CouplingKind::egb && egb_.on && setup_.egb.no_wait) {
    return CouplingStep::done;  // param 5320.5 = 1: the program goes on while it locks
  }
  if (kind_ == CouplingKind::polygon && polygon_.on && setup_.polygon.no_wait) {
    return CouplingStep::done;  // param 5300.5 = 1: the program goes on while it locks
  }
  const bool done = kind_ == CouplingKind::axis      ? axis_done(in)
                    : kind_ == CouplingKind::polygon ? polygon_done(in)
                    : kind_ == CouplingKind::cam     ? cam_done(in)
                    : kind_ == CouplingKind::egb     ? egb_done(in)
                                                     : spindle_done(in);
  if (!answer_visible(sent_cycle_, in.cycle) || !done) {
    return CouplingStep::waiting;
  }
  return CouplingStep::done;
}

CouplingRequest::Start CouplingRequest::start_polygon(const CouplingInputs& in) noexcept {
  const PolygonSetup& s = setup_.polygon;
  const AxisFeedbackView none{};
  const AxisFeedbackView& slave =
      s.slave_view < in.feedback.size() ? in.feedback[s.slave_view] : none;
  const SlotUse use = s.slave_axis && s.slave_view < in.slot_use.size() ? in.slot_use[s.slave_view]
                                                                        : SlotUse::commanded;
  if (!polygon_.on) {
    if (s.master != 0 && slave.coupled_to != 0) {
      return Start::send;
    }
    if (use == SlotUse::follows) {
      // Let go already (a reset's release ended): the program goes on from where it stands.
      change_ = SlotChange{SlotChange::To::commanded, s.slave_view, slave.cmd};
    }
    return Start::nothing_to_do;
  }
  if (s.master == 0) {
    alarm_.set(kAlarmPolygon,
               "G51.2: this channel has no polygon axis (polygon in the machine file, parameters "
               "5310/5311)");
    return Start::refused;
  }
  if (slave.coupled_to != 0) {
    alarm_.set(kAlarmPolygon, "G51.2: the polygon axis follows its master already: G50.2 first");
    return Start::refused;
  }
  if (use != SlotUse::commanded) {
    alarm_.set(kAlarmPolygon, "G51.2: the polygon axis is not this channel's now (G141 first)");
    return Start::refused;
  }
  if (std::fabs(slave.vel) > kSpindleAtRest) {
    alarm_.set(kAlarmPolygon,
               "G51.2: the polygon axis turns at %.1f rpm: stop its spindle (M05) before G51.2",
               slave.vel / 6.0);
    return Start::refused;
  }
  const AxisFeedbackView& master =
      s.master_view < in.feedback.size() ? in.feedback[s.master_view] : none;
  const double speed = std::fabs(master.vel * polygon_.q / polygon_.p);
  if (speed > s.max_speed) {
    alarm_.set(kAlarmPolygon,
               "G51.2 P%d Q%d: the polygon axis would turn at %.0f rpm, above its %.0f rpm "
               "(parameter 5312: polygon max_rpm)",
               polygon_.p, polygon_.q, speed / 6.0, s.max_speed / 6.0);
    return Start::refused;
  }
  if (s.slave_axis) {
    // A servo polygon axis is its master's from the cycle its node takes G51.2 in.
    change_ = SlotChange{SlotChange::To::follows, s.slave_view, 0.0};
  }
  return Start::send;
}

bool CouplingRequest::polygon_done(const CouplingInputs& in) noexcept {
  // G51.2 ends once the axis is in phase (param 5300.5 = 0); G50.2 once it stands free.
  const PolygonSetup& s = setup_.polygon;
  if (!slave_answered(in.feedback, s.slave_view, s.master, polygon_.on)) {
    return false;
  }
  if (s.slave_axis) {
    // After G50.2 the program goes on from where a servo polygon axis stands.
    change_ = polygon_.on ? SlotChange{SlotChange::To::follows, s.slave_view, 0.0}
                          : SlotChange{SlotChange::To::commanded, s.slave_view,
                                       in.feedback[s.slave_view].cmd};
  }
  return true;
}

std::optional<PolygonOut> CouplingRequest::polygon_on_reset(
    std::span<const AxisFeedbackView> feedback) noexcept {
  const PolygonSetup& s = setup_.polygon;
  const bool follows = s.slave_view < feedback.size() && feedback[s.slave_view].coupled_to != 0;
  if (s.master == 0 || (!follows && !polygon_asked_)) {
    return std::nullopt;
  }
  polygon_asked_ = false;
  polygon_lock_due_.reset();
  return PolygonOut{false, 1, 1, 0.0, false};
}

bool CouplingRequest::lock_pending(const CouplingInputs& in) noexcept {
  const PolygonSetup& p = setup_.polygon;
  if (polygon_lock_due_ && answer_visible(*polygon_lock_due_, in.cycle) &&
      slave_answered(in.feedback, p.slave_view, p.master, true)) {
    polygon_lock_due_.reset();
  }
  if (egb_lock_due_ && answer_visible(*egb_lock_due_, in.cycle) &&
      slave_answered(in.feedback, setup_.egb.work_slot, setup_.egb.tool, true)) {
    egb_lock_due_.reset();
  }
  return polygon_lock_due_ || egb_lock_due_;
}

CouplingRequest::Start CouplingRequest::start_cam(const CouplingInputs& in) noexcept {
  const CamSetup& s = setup_.cam;
  if (!cam_.on) {
    const bool runs = s.master != 0 && s.slave_slot < in.feedback.size() &&
                      in.feedback[s.slave_slot].coupled_to != 0;
    return runs || cam_asked_ ? Start::send : Start::nothing_to_do;
  }
  if (s.master == 0) {
    alarm_.set(kAlarmCam,
               "G51.8: this channel has no electronic cam (cam in the machine file, parameters "
               "5350/5351)");
    return Start::refused;
  }
  return Start::send;
}

bool CouplingRequest::cam_done(const CouplingInputs& in) const noexcept {
  // G51.8 ends once the slave is on its lift ("moves incrementally to the table value for the
  // current master angle", L3052); G50.8 once the lift is off it.
  return slave_answered(in.feedback, setup_.cam.slave_slot, setup_.cam.master, cam_.on);
}

bool CouplingRequest::cam_on_reset(std::span<const AxisFeedbackView> feedback) noexcept {
  const CamSetup& s = setup_.cam;
  const bool runs = s.slave_slot < feedback.size() && feedback[s.slave_slot].coupled_to != 0;
  if (s.master == 0 || (!runs && !cam_asked_)) {
    return false;
  }
  cam_asked_ = false;
  cam_.on = false;
  return true;
}

CouplingRequest::Start CouplingRequest::start_egb(const CouplingInputs& in) noexcept {
  const EgbSetup& s = setup_.egb;
  const AxisFeedbackView none{};
  const AxisFeedbackView& work =
      s.tool != 0 && s.work_slot < in.feedback.size() ? in.feedback[s.work_slot] : none;
  if (!egb_.on) {
    // G80.4 stops a gear box that runs, and hands over the angle a stopped one left.
    return work.coupled_to != 0 || work.superimposed != 0.0 || egb_asked_ ? Start::send
                                                                          : Start::nothing_to_do;
  }
  if (s.tool == 0) {
    alarm_.set(kAlarmEgb,
               "G81.4: this channel has no electronic gear box (egb in the machine file, "
               "parameters 5330/5331)");
    return Start::refused;
  }
  if (work.coupled_to != 0 || egb_asked_) {
    alarm_.set(kAlarmEgb, "G81.4: the gear box is on already: G80.4 first");
    return Start::refused;
  }
  if (egb_.helix != 0.0 && !s.axial) {
    alarm_.set(kAlarmEgb,
               "G81.4 P%.3f: a helical gear needs the axial feed axis (egb axial in the machine "
               "file, parameter 5332)",
               egb_.helix);
    return Start::refused;
  }
  const double tool_vel = s.tool_view < in.feedback.size() ? in.feedback[s.tool_view].vel : 0.0;
  if (!egb_.phase && std::fabs(tool_vel) > kSpindleAtRest) {
    // Without R nothing is matched: the axes were positioned with the tool at rest (L3372).
    alarm_.set(kAlarmEgb,
               "G81.4 without R: the tool spindle turns at %.1f rpm; without phase matching it "
               "must stand (M05 before G81.4), or give R",
               tool_vel / 6.0);
    return Start::refused;
  }
  return Start::send;
}

bool CouplingRequest::egb_done(const CouplingInputs& in) noexcept {
  const EgbSetup& s = setup_.egb;
  if (egb_.on) {
    // G81.4 ends once the work axis is locked to the tool spindle (param 5320.5 = 0).
    return slave_answered(in.feedback, s.work_slot, s.tool, true);
  }
  if (!slave_answered(in.feedback, s.work_slot, s.tool, false)) {
    return false;
  }
  // G80.4: the work axis stands where it reached; the program goes on from there (P0 waits
  // too: the channel can take the angle only once the axis stands).
  const std::optional<SlotChange> change = egb_hand_over(in.feedback);
  change_ = change ? *change : SlotChange{};
  return true;
}

std::optional<SlotChange> CouplingRequest::egb_hand_over(
    std::span<const AxisFeedbackView> feedback) noexcept {
  const EgbSetup& s = setup_.egb;
  if (s.tool == 0 || s.work_slot >= feedback.size() || feedback[s.work_slot].coupled_to != 0 ||
      feedback[s.work_slot].superimposed == 0.0) {
    return std::nullopt;
  }
  egb_ = EgbOut{};
  egb_.on = false;
  egb_.off = EgbOut::Off::absorb;
  return SlotChange{SlotChange::To::commanded, s.work_slot, feedback[s.work_slot].cmd};
}

bool CouplingRequest::egb_on_reset(std::span<const AxisFeedbackView> feedback) noexcept {
  const EgbSetup& s = setup_.egb;
  const bool runs = s.work_slot < feedback.size() && feedback[s.work_slot].coupled_to != 0;
  if (s.tool == 0 || (!runs && !egb_asked_)) {
    return false;
  }
  egb_asked_ = false;
  egb_lock_due_.reset();
  egb_ = EgbOut{};
  egb_.on = false;
  egb_.off = EgbOut::Off::reset;
  return true;
}

bool CouplingRequest::egb_lost(const CouplingInputs& in) noexcept {
  const EgbSetup& s = setup_.egb;
  if (!egb_asked_ || !answer_visible(egb_sent_cycle_, in.cycle) ||
      s.work_slot >= in.feedback.size() || in.feedback[s.work_slot].coupled_to != 0) {
    return false;
  }
  egb_asked_ = false;
  egb_lock_due_.reset();
  alarm_.set(kAlarmEgb,
             "G81.4: the work axis stopped %.3f deg off the channel's position: off the gear's "
             "ratio too long (parameters 5336/5337) or the tool spindle lost",
             in.feedback[s.work_slot].superimposed);
  return true;
}

CouplingRequest::Start CouplingRequest::start_spindle() noexcept {
  bool known = !spindle_.on;  // G113 cancels whatever this channel's groups have
  for (const SpindleGroupSetup& g : setup_.spindle_groups) {
    known = known || g.group == spindle_.group;
  }
  if (!known) {
    alarm_.set(kAlarmSyncGroup,
               "G114.1 K%d: no synchronisation group %d has this channel's spindle as master",
               spindle_.group, spindle_.group);
    return Start::refused;
  }
  return Start::send;
}

bool CouplingRequest::spindle_done(const CouplingInputs& in) const noexcept {
  for (const SpindleGroupSetup& g : setup_.spindle_groups) {
    if (spindle_.on && g.group != spindle_.group) {
      continue;
    }
    const AxisFeedbackView none{};
    const AxisFeedbackView& slave =
        g.slave_view < in.feedback.size() ? in.feedback[g.slave_view] : none;
    const bool done =
        spindle_.on ? slave.coupled_to != 0 && slave.coupling_locked : slave.coupled_to == 0;
    if (!done) {
      return false;  // G114.1 ends once the slave is at speed and in phase
    }
  }
  return true;
}

CouplingRequest::Start CouplingRequest::start_axis(const CouplingInputs& in) noexcept {
  const char* g = axis_sync_.on ? "G51.4" : "G50.4";
  std::size_t s = setup_.slots.size();
  for (std::size_t i = 0; i < setup_.slots.size() && i < setup_.axis_count; ++i) {
    s = setup_.slots[i].id == slave_ && !setup_.slots[i].exchange_slot ? i : s;
  }
  const SlotUse use = s < in.slot_use.size() ? in.slot_use[s] : SlotUse::away;
  if (s == setup_.slots.size() || (use != SlotUse::commanded && use != SlotUse::follows)) {
    alarm_.set(kAlarmAxisSync,
               "%s Q%u: axis %u is not this channel's (the channel that commands it programs it)",
               g, slave_, slave_);
    return Start::refused;
  }
  const AxisSlot& slot = setup_.slots[s];
  if (!slot.may_follow) {
    alarm_.set(kAlarmAxisSync,
               "%s Q%u: %c cannot follow another axis (parameter 5600.1: axis_sync)", g, slave_,
               slot.address);
    return Start::refused;
  }
  axis_sync_.slot = s;
  const std::uint32_t coupled_to = s < in.feedback.size() ? in.feedback[s].coupled_to : 0;
  if (!axis_sync_.on) {
    return use == SlotUse::follows || coupled_to != 0 ? Start::send : Start::nothing_to_do;
  }
  const std::uint32_t master = axis_sync_.master != 0 ? axis_sync_.master : slot.default_master;
  if (master == 0) {
    alarm_.set(kAlarmAxisSync,
               "G51.4 Q%u: no P, and %c has no default master (parameter 5610: axis_sync master)",
               slave_, slot.address);
    return Start::refused;
  }
  const MachineAxis* m =
      master <= setup_.machine_axes.size() ? &setup_.machine_axes[master - 1] : nullptr;
  const MachineAxisKind kind = slot.id >= 1 && slot.id <= setup_.machine_axes.size()
                                   ? setup_.machine_axes[slot.id - 1].kind
                                   : MachineAxisKind::linear;
  if (m == nullptr || m->kind != kind || m->may_follow) {
    alarm_.set(kAlarmAxisSync, "G51.4 P%u: %s", master,
               m == nullptr      ? "the machine has no such axis"
               : m->kind != kind ? "the master is not of the same kind as the slave"
                                 : "the axis may follow another itself (5600.1), it cannot lead");
    return Start::refused;
  }
  if (use == SlotUse::follows || coupled_to != 0) {
    if (coupled_to == master) {
      change_ = SlotChange{SlotChange::To::follows, s, 0.0};
      return Start::nothing_to_do;
    }
    alarm_.set(kAlarmAxisSync, "G51.4 Q%u: %c already follows axis %u: G50.4 Q%u first", slave_,
               slot.address, coupled_to, slave_);
    return Start::refused;
  }
  axis_sync_.master = master;
  return Start::send;
}

bool CouplingRequest::axis_done(const CouplingInputs& in) noexcept {
  const std::size_t s = axis_sync_.slot;
  if (s >= in.feedback.size()) {
    return false;
  }
  const AxisFeedbackView& f = in.feedback[s];
  if (axis_sync_.on) {
    if (f.coupled_to != axis_sync_.master) {
      return false;
    }
    change_ = SlotChange{SlotChange::To::follows, s, 0.0};  // the program no longer moves it
    return true;
  }
  if (f.coupled_to != 0) {
    return false;
  }
  // The axis stands where its master took it: the program goes on from there.
  change_ = SlotChange{SlotChange::To::commanded, s, f.cmd};
  return true;
}

}  // namespace mcnc::coordination
