#include "axisnode/control/axis_node_controller.hpp"

#include "axisnode/control/torque_units.hpp"
#include "canopen/cia402/drive_pdos.hpp"

#include <algorithm>
#include <cmath>

namespace mcnc::axisnode {

namespace {
constexpr std::uint16_t kHomingAttained = 0x1000;  // statusword bit 12 in homing mode
constexpr std::uint16_t kHomingStart = 0x0010;     // controlword bit 4 in homing mode
constexpr std::uint16_t kHomingError = 0x2000;     // statusword bit 13 in homing mode
constexpr std::uint16_t kTargetReached = 0x0400;   // statusword bit 10
}  // namespace

const char* mode_name(std::int8_t mode) noexcept {
  switch (mode) {
    case kModeCsp:
      return "csp";
    case kModeCsv:
      return "csv";
    case kModeHoming:
      return "homing";
    default:
      return "other";
  }
}

const char* to_text(AxisAlarm alarm) noexcept {
  switch (alarm) {
    case AxisAlarm::none:
      return "no alarm";
    case AxisAlarm::setpoint_deadline:
      return "no setpoint from the owner channel within the deadline: quick stop";
    case AxisAlarm::owner_lost:
      return "owner channel lost: quick stop";
    case AxisAlarm::drive_fault:
      return "drive fault";
    case AxisAlarm::drive_lost:
      return "drive does not answer SYNC: quick stop";
    case AxisAlarm::drive_startup:
      return "drive start-up failed";
    case AxisAlarm::heartbeat_lost:
      return "no heartbeat from the drive within the consumer time: quick stop";
    case AxisAlarm::bus_off:
      return "CAN bus off: the drive cannot be reached";
    case AxisAlarm::soft_limit:
      return "setpoint beyond the axis's soft limits: quick stop";
    case AxisAlarm::following_error:
      return "following error above its limit: quick stop";
    case AxisAlarm::homing_failed:
      return "homing failed (the drive reports a homing error, or it did not end in time)";
    case AxisAlarm::foreign_sync:
      return "a SYNC this node did not send: another SYNC producer on the bus: quick stop";
  }
  return "unknown alarm";
}

AxisNodeController::AxisNodeController(const AxisNodeSetup& setup) noexcept
    : setup_(setup),
      requested_mode_(setup.homing    ? kModeHoming
                      : setup.spindle ? kModeCsv
                                      : kModeCsp),
      heartbeat_(0, static_cast<std::uint64_t>(std::max(0, setup.heartbeat_cycles))) {
  out_.mode = requested_mode_;
  out_.mode_display = requested_mode_;  // what the start-up wrote
}

void AxisNodeController::raise(AxisAlarm alarm) noexcept {
  out_.quick_stop = true;
  const auto bit = static_cast<std::uint16_t>(1U << static_cast<unsigned>(alarm));
  if ((raised_ & bit) != 0) {
    return;
  }
  raised_ |= bit;
  if (out_.alarm == AxisAlarm::none) {
    out_.alarm = alarm;
  }
  if (out_.new_alarm == AxisAlarm::none) {
    out_.new_alarm = alarm;
  }
}

const AxisNodeOutput& AxisNodeController::cycle(std::uint64_t cycle,
                                                const AxisNodeInput& in) noexcept {
  out_.new_alarm = AxisAlarm::none;
  out_.drive_state_changed = false;
  out_.mode_changed = false;
  const std::uint64_t elapsed = cycle > last_cycle_ ? cycle - last_cycle_ : 1;
  last_cycle_ = cycle;
  const auto deadline = static_cast<std::uint64_t>(setup_.deadline_cycles);
  const auto drive_watch =
      in.paced_best_effort
          ? std::max(deadline, static_cast<std::uint64_t>(setup_.best_effort_watch_cycles))
          : deadline;

  // Drive side: what the drive reported for the last SYNC.
  if (in.have_tpdo) {
    last_tpdo_cycle_ = cycle;
    statusword_ = in.statusword;
    // The position actual value is 32 bits and wraps (a spindle after a few thousand turns):
    // the node counts on from the difference.
    if (have_position_) {
      counts_ += static_cast<std::int32_t>(static_cast<std::uint32_t>(in.position_counts) -
                                           static_cast<std::uint32_t>(last_counts_));
    } else {
      counts_ = in.position_counts;
    }
    last_counts_ = in.position_counts;
    const double act = static_cast<double>(counts_) / setup_.counts_per_unit;
    const cia402::State state = cia402::decode_statusword(in.statusword);
    // Homing attained (after the start this node gave, in operation): the position value
    // jumped to the home position; the motor did not move.
    const bool home_jump =
        setup_.homing && !homed_ && start_sent_cycle_ != 0 && cycle > start_sent_cycle_ &&
        state == cia402::State::operation_enabled && out_.mode_display == kModeHoming &&
        (in.statusword & kHomingAttained) != 0 && (in.statusword & kHomingError) == 0;
    out_.vel = have_position_ && !home_jump ? (act - out_.act) / setup_.cycle_s : 0.0;
    if (home_jump) {
      homed_ = true;
      out_.homed = true;
      requested_mode_ = kModeCsp;
    }
    if (setup_.homing && !homed_ && out_.mode_display == kModeHoming &&
        (in.statusword & kHomingError) != 0) {
      raise(AxisAlarm::homing_failed);
    }
    out_.act = act;
    have_position_ = true;
    out_.drive_state_changed = state != out_.drive_state;
    out_.drive_state = state;
    if ((setup_.spindle || setup_.homing || setup_.torque_mode) &&
        in.mode_display != out_.mode_display) {
      out_.mode_changed = true;
      out_.mode_display = in.mode_display;
      // Into CSP while turning: the position target takes over one cycle ahead of the actual
      // position at the actual speed, so the drive does not brake on the switch.
      out_.cmd = out_.act + out_.vel * setup_.cycle_s;
    }
  } else if (was_enabled_ && cycle - last_tpdo_cycle_ >= drive_watch) {
    raise(AxisAlarm::drive_lost);
  }

  // An operator reset waits until the drive is at rest: a quick stop or a fault reaction
  // finishes its ramp first (re-enabling a drive that still brakes would brake it at its
  // torque limit instead).
  if (reset_requested_ && drive_at_rest()) {
    reset_requested_ = false;
    raised_ = 0;
    out_.alarm = AxisAlarm::none;
    out_.quick_stop = false;
    following_ = false;
    resetting_ = out_.drive_state == cia402::State::fault;
    reset_cycle_ = cycle;
    last_tpdo_cycle_ = cycle;
    last_setpoint_cycle_ = cycle;
    homing_since_ = cycle;
    heartbeat_.restart(cycle);
  }
  // One fault reset per operator reset: it ends when the drive leaves fault (a fault after
  // that is a new one, alarmed at once) or when the drive stays in fault too long.
  if (resetting_ &&
      (out_.drive_state != cia402::State::fault ||
       cycle - reset_cycle_ >= static_cast<std::uint64_t>(setup_.fault_reset_cycles))) {
    resetting_ = false;
  }
  const bool faulted = out_.drive_state == cia402::State::fault ||
                       out_.drive_state == cia402::State::fault_reaction_active;
  if (faulted && !resetting_) {
    raise(AxisAlarm::drive_fault);
  }
  // Heartbeat consumer, in cycles: watched from the first heartbeat on (paced best effort: over
  // best_effort_watch_cycles at least).
  const std::uint64_t heartbeat_slack =
      in.paced_best_effort && setup_.best_effort_watch_cycles > setup_.heartbeat_cycles
          ? static_cast<std::uint64_t>(setup_.best_effort_watch_cycles - setup_.heartbeat_cycles)
          : 0;
  if (in.heartbeats != heartbeats_) {
    heartbeats_ = in.heartbeats;
    heartbeat_.heard(cycle);
  } else if (heartbeat_.on_time(cycle, heartbeat_slack) ==
             canopen::HeartbeatConsumer::Event::lost) {
    raise(AxisAlarm::heartbeat_lost);
  }

  if (in.bus_off) {
    raise(AxisAlarm::bus_off);
  }
  // The drives step on every SYNC: a second producer makes them step out of the machine's
  // cycle (and in lockstep out of its order).
  if (in.foreign_syncs > 0) {
    raise(AxisAlarm::foreign_sync);
  }
  if (in.emergency_stop) {
    out_.quick_stop = true;
  }
  if (in.owner_lost && was_enabled_) {
    raise(AxisAlarm::owner_lost);
  }

  const bool drive_operating = out_.drive_state == cia402::State::operation_enabled;
  if (drive_operating) {
    was_enabled_ = true;  // from here on the drive's answers and the owner are watched
  }
  if (setup_.homing && !homed_ && drive_operating && !homing_started_ && homing_since_ == 0) {
    homing_since_ = cycle;
  }
  if (setup_.homing && !homed_ && homing_since_ != 0 &&
      cycle - homing_since_ >= static_cast<std::uint64_t>(setup_.homing_timeout_cycles)) {
    raise(AxisAlarm::homing_failed);
  }
  // A homing axis is the owner's once it is homed and in CSP.
  const bool operating =
      drive_operating && (!setup_.homing || (homed_ && out_.mode_display == kModeCsp));
  if (operating && !following_) {
    out_.cmd = out_.act;  // take over where the drive stands: no jump on enable
  }
  following_ = operating;

  // A spindle: the mode its owner asks for goes out with the RPDO; the drive's display says
  // when it runs in it. The target velocity always says what the spindle should turn at, so
  // the frame that switches to CSV carries the right one.
  if (setup_.spindle && in.have_setpoint && in.setpoint_valid) {
    requested_mode_ = in.setpoint_velocity ? kModeCsv : kModeCsp;
  }
  // G10 L14 P10-P12: the mode the owner asks for goes out with the RPDO, with the torque and
  // the speed limit; the drive's display says when it runs in it.
  if (setup_.torque_mode && in.have_setpoint && in.setpoint_valid) {
    requested_mode_ = in.torque_mode ? kModeCst : kModeCsp;
    out_.target_torque =
        in.torque_mode
            ? static_cast<std::int16_t>(std::clamp(
                  std::lround(drive_permille(in.torque, setup_.torque_scale)), -10000L, 10000L))
            : std::int16_t{0};
    out_.max_motor_speed =
        in.torque_mode
            ? static_cast<std::uint32_t>(std::clamp(std::lround(in.torque_speed), 0L, 1000000L))
            : 0U;
  }
  out_.mode = requested_mode_;
  // In CST (and on the way into it) the drive has no position loop: the command follows it, so
  // that the frame that switches back to CSP holds where the motor stands.
  const bool torque_mode =
      setup_.torque_mode && (out_.mode_display == kModeCst || requested_mode_ == kModeCst);
  const bool velocity_mode = (setup_.spindle && out_.mode_display == kModeCsv) || torque_mode;
  if (setup_.spindle && following_ && !out_.quick_stop) {
    if (in.have_setpoint && in.setpoint_valid && in.setpoint_velocity) {
      out_.vel_cmd = in.setpoint_vel;
    } else if (!velocity_mode) {
      out_.vel_cmd = out_.vel;  // in CSP: what it turns at now
    }
  }

  // Owner side: follow, extrapolate a missing setpoint, or stop after the deadline.
  if (following_ && !out_.quick_stop) {
    if (in.have_setpoint) {
      owner_seen_ = true;
      last_setpoint_cycle_ = cycle;
      out_.missing_setpoints = 0;
      if (velocity_mode) {
        // CSV: the position is the drive's. Switching to CSP: the frame that carries the mode
        // carries the owner's position too, so the drive takes it at the switch.
        out_.cmd = in.setpoint_valid && !in.setpoint_velocity ? in.setpoint_pos : out_.act;
      } else if (in.setpoint_valid && in.setpoint_velocity) {
        out_.cmd += in.setpoint_vel * setup_.cycle_s;  // leaving CSP: keep turning meanwhile
      } else if (in.setpoint_valid && setup_.has_soft_limits &&
                 (in.setpoint_pos < setup_.soft_min || in.setpoint_pos > setup_.soft_max)) {
        raise(AxisAlarm::soft_limit);  // never commanded: the drive stops where it is
      } else if (in.setpoint_valid) {
        out_.cmd = in.setpoint_pos;
        last_setpoint_vel_ = in.setpoint_vel;
      } else {
        last_setpoint_vel_ = 0.0;
      }
    } else if (owner_seen_) {
      out_.missing_setpoints = static_cast<int>(cycle - last_setpoint_cycle_);
      // A late sample continues the motion (in CSV the drive keeps its velocity by itself), as
      // a stop at the axis's deceleration would: the owner planned its move within that limit,
      // so the move could not have ended sooner, and the axis never passes where the program
      // takes it (at the last velocity it overshot the end of a move in realtime under loss).
      for (std::uint64_t k = 0; !velocity_mode && k < elapsed; ++k) {
        const double braked =
            setup_.acceleration > 0.0
                ? std::copysign(std::max(0.0, std::abs(last_setpoint_vel_) -
                                                  setup_.acceleration * setup_.cycle_s),
                                last_setpoint_vel_)
                : last_setpoint_vel_;
        const double v0 = last_setpoint_vel_;
        // The time of this cycle until the stop, when it comes within it.
        const double t = setup_.acceleration > 0.0 && braked == 0.0
                             ? std::abs(v0) / setup_.acceleration
                             : setup_.cycle_s;
        out_.cmd += 0.5 * (v0 + braked) * t;
        last_setpoint_vel_ = braked;
      }
      if (cycle - last_setpoint_cycle_ >= deadline) {
        raise(AxisAlarm::setpoint_deadline);
      }
    }
  }
  if (!following_ || (velocity_mode && requested_mode_ == kModeCsv) || torque_mode) {
    // No position loop in CSV (no following error either); and a drive not yet the owner's
    // (enabling, homing) is told to stay where it is, whatever mode it switches to next.
    out_.cmd = out_.act;
  }
  if (in.have_setpoint) {  // G160's limit stands as long as the owner sends it, holding or not
    torque_limit_ = setup_.torque_skip ? in.torque_limit : 0.0;
    skip_deviation_ = torque_limit_ > 0.0 ? in.skip_deviation : 0.0;
  }
  if (following_ && !velocity_mode && !out_.quick_stop && setup_.following_error_limit > 0.0 &&
      std::abs(out_.cmd - out_.act) > following_error_allowed()) {
    raise(AxisAlarm::following_error);
  }
  if (out_.quick_stop || !following_) {
    out_.vel_cmd = 0.0;
  }
  if (out_.quick_stop) {
    out_.cmd = out_.act;  // the drive ramps down itself; the target follows it
  }
  out_.target_velocity_counts =
      static_cast<std::int32_t>(std::llround(out_.vel_cmd * setup_.counts_per_unit));

  const cia402::Goal goal = out_.quick_stop ? cia402::Goal::quick_stop : cia402::Goal::enabled;
  out_.controlword = cia402::next_controlword(out_.drive_state, goal, resetting_);
  // Homing: bit 4 rises once the drive is in operation in homing mode (CiA 402: homing
  // operation start on its rising edge).
  if (setup_.homing && !homed_ && drive_operating && out_.mode_display == kModeHoming &&
      !out_.quick_stop) {
    if (homing_started_) {
      out_.controlword |= kHomingStart;
      if (start_sent_cycle_ == 0) {
        start_sent_cycle_ = cycle;  // "attained" counts from the answer to this one on
      }
    }
    homing_started_ = true;
  }
  out_.enabled = operating && !out_.quick_stop;
  probe_cycle(in);
  torque_cycle(in);
  // The target in the drive's 32-bit counts, wrapping as the drive's position does.
  const auto target = static_cast<std::int64_t>(std::llround(out_.cmd * setup_.counts_per_unit));
  out_.target_counts = static_cast<std::int32_t>(
      static_cast<std::uint32_t>(static_cast<std::uint64_t>(target) & 0xFFFFFFFFULL));
  return out_;
}

void AxisNodeController::probe_cycle(const AxisNodeInput& in) noexcept {
  namespace tp = canopen::touch_probe;
  // What the drive says belongs to the function sent before: an edge's position counts only
  // while that edge is asked for and the drive reports the probe enabled.
  const std::uint16_t sent = out_.touch_probe;
  const bool rising = (sent & tp::kPositiveEdge) != 0;
  out_.probe = ProbeState::off;
  if ((sent & tp::kEnable) != 0 && (in.touch_probe_status & tp::kEnabled) != 0) {
    const bool stored =
        (in.touch_probe_status & (rising ? tp::kPositiveStored : tp::kNegativeStored)) != 0;
    out_.probe = stored ? ProbeState::latched : ProbeState::armed;
    // Counted on from the position actual value, as the position wraps.
    const std::int32_t raw = rising ? in.probe_positive : in.probe_negative;
    const std::int64_t counts =
        counts_ + static_cast<std::int32_t>(static_cast<std::uint32_t>(raw) -
                                            static_cast<std::uint32_t>(last_counts_));
    out_.probe_pos = stored ? static_cast<double>(counts) / setup_.counts_per_unit : 0.0;
  }
  // Continuous mode: every edge the drive counted since the last cycle is one more; the count
  // restarts with the probe (the drive clears it when disabled).
  if ((sent & tp::kContinuous) != 0 && out_.probe != ProbeState::off) {
    const auto bits = static_cast<std::uint16_t>((in.touch_probe_status & tp::kEdgeCountMask) >>
                                                 tp::kEdgeCountShift);
    out_.probe_count += static_cast<std::uint32_t>((bits - probe_edge_bits_) & 3U);
    probe_edge_bits_ = bits;
  } else {
    out_.probe_count = 0;
    probe_edge_bits_ = 0;
  }
  const bool every =
      in.probe == ProbeRequest::every_rising || in.probe == ProbeRequest::every_falling;
  const bool up = in.probe == ProbeRequest::rising || in.probe == ProbeRequest::every_rising;
  const bool asked = out_.enabled && (every || up || in.probe == ProbeRequest::falling);
  out_.touch_probe = asked
                         ? static_cast<std::uint16_t>(tp::kEnable | (every ? tp::kContinuous : 0U) |
                                                      (up ? tp::kPositiveEdge : tp::kNegativeEdge))
                         : std::uint16_t{0};
}

void AxisNodeController::torque_cycle(const AxisNodeInput& in) noexcept {
  const std::uint16_t sent = out_.max_torque;
  out_.max_torque = torque_limit_ > 0.0
                        ? static_cast<std::uint16_t>(std::clamp(
                              std::lround(drive_permille(torque_limit_, setup_.torque_scale)), 1L,
                              static_cast<long>(canopen::kNoTorqueLimit)))
                        : canopen::kNoTorqueLimit;
  const bool asked =
      setup_.torque_skip && out_.enabled && in.probe == ProbeRequest::torque && torque_limit_ > 0.0;
  if (!asked) {
    torque_latched_ = false;
  } else if (sent == out_.max_torque) {
    // The drive ran its last SYNC under this limit: the skip is armed. It latches where the
    // axis stands once it is held back (L5370-5374): the torque at the limit (within 3 %, as a
    // drive's torque actual value ripples) and the following error beyond the deviation, both
    // the way the owner moves the axis, so that a G160 away from what holds it (the retract of
    // L5406 and L5426) does not skip where it starts.
    const double error = sent_cmd_ - out_.act;
    const double torque = static_cast<double>(in.torque_actual);
    const bool held_back = in.setpoint_vel * error > 0.0 && torque * error > 0.0 &&
                           std::abs(torque) >= 0.97 * static_cast<double>(sent) &&
                           std::abs(error) > skip_deviation_;
    if (!torque_latched_ && held_back) {
      torque_latched_ = true;
      out_.probe_pos = out_.act;
    }
    out_.probe = torque_latched_ ? ProbeState::latched : ProbeState::armed;
    if (!torque_latched_) {
      out_.probe_pos = 0.0;
    }
  }
  sent_cmd_ = out_.cmd;
}

double AxisNodeController::following_error_allowed() const noexcept {
  return setup_.following_error_limit + (torque_limit_ > 0.0 ? skip_deviation_ : 0.0);
}

bool AxisNodeController::drive_at_rest() const noexcept {
  switch (out_.drive_state) {
    case cia402::State::fault_reaction_active:
      return false;  // it ends in fault at standstill
    case cia402::State::quick_stop_active:
      return (statusword_ & kTargetReached) != 0;  // CiA 402: bit 10 in quick stop is "halted"
    default:
      return true;
  }
}

bool AxisNodeController::ready_to_disable() const noexcept {
  switch (out_.drive_state) {
    case cia402::State::operation_enabled:
    case cia402::State::fault_reaction_active:
      return false;
    case cia402::State::quick_stop_active:
      return (statusword_ & kTargetReached) != 0;  // "halted"
    default:
      return true;
  }
}

}  // namespace mcnc::axisnode
