#include "channel/control/read_ahead_stop.hpp"

#include "channel/coordination/coordination_alarm.hpp"

#include <algorithm>

namespace mcnc::channel {
namespace {

HeldBlock held(const interp::Command& c) noexcept {
  return HeldBlock{c.n, c.line, c.file, c.block_text, false, c.modal};
}

// The next spindle direction after `c` (the first spindle's, as M03/M04/M05 leave it).
int spindle_after(const interp::Command& c, int queued) noexcept {
  if (c.op != interp::Op::spindle || c.channel != 0 || c.spindle > 1) {
    return queued;
  }
  switch (c.spindle_direction) {
    case interp::SpindleDirection::cw:
      return 1;
    case interp::SpindleDirection::ccw:
      return -1;
    case interp::SpindleDirection::keep:
      return queued;
    default:
      return 0;
  }
}

}  // namespace

ReadAheadStop read_ahead_stop(const interp::Command& c, const StopRules& rules, int& spindle_queued,
                              std::optional<interp::ProgramAlarm>& alarm) {
  using interp::Op;
  using interp::SpindleDirection;
  switch (c.op) {
    case Op::sync: {
      // The interpreter evaluates nothing after the mark until the channel pulls past it.
      SyncStop s{held(c), c.has_p, c.p, {}, c.all_channels};
      for (std::uint32_t ch = 1; ch <= coordination::kMaxChannels; ++ch) {
        s.participants.set(ch, c.has_channel(static_cast<int>(ch)));
      }
      return s;
    }
    case Op::subcall: {
      CallStop s{held(c), {}};
      s.call.caller = rules.channel_id;
      s.call.target = static_cast<std::uint32_t>(c.channel);
      s.call.program = c.program;
      s.call.wait = c.wait;
      s.call.repeat = c.repeat;
      for (const auto& [var, value] : c.args) {
        if (var >= 1 && var <= interp::kSubcallArgs) {
          s.call.args[static_cast<std::size_t>(var - 1)] = value;
          s.call.args_given |= 1U << (var - 1);
        }
      }
      return s;
    }
    case Op::subcall_release:
      return ReleaseStop{held(c)};
    case Op::axis_release:
    case Op::axis_acquire:
    case Op::axis_restore: {
      ExchangeStop s{held(c),
                     c.op == Op::axis_release   ? coordination::AxisRequestKind::release
                     : c.op == Op::axis_acquire ? coordination::AxisRequestKind::acquire
                                                : coordination::AxisRequestKind::restore,
                     0, c.force};
      if (c.op != Op::axis_restore) {
        s.slot = rules.slots.size();
        for (std::size_t i = 0; i < rules.slots.size(); ++i) {
          s.slot = rules.slots[i].address == c.axis ? i : s.slot;
        }
        if (s.slot == rules.slots.size()) {
          alarm = interp::ProgramAlarm{
              coordination::kAlarmNotOwner,
              std::string("axis ") + c.axis + " of this channel is not exchanged", "", c.line, 0};
          return std::monostate{};
        }
      }
      return s;
    }
    case Op::spindle_sync:
    case Op::spindle_unsync: {
      const bool on = c.op == Op::spindle_sync;
      return CouplingStop{held(c), false, {on, on ? c.sync_k : 0, c.sync_p, c.sync_q, c.sync_r},
                          false,   0,     0,
                          false,   {},    false,
                          {},      false, {}};
    }
    case Op::polygon:
    case Op::polygon_off: {
      CouplingStop s{held(c), false, {}, false, 0, 0, true, {}, false, {}, false, {}};
      s.polygon_sync = coordination::PolygonOut{c.op == Op::polygon, c.sync_p, c.sync_q, c.sync_r,
                                                c.op == Op::polygon || c.wait};
      return s;
    }
    case Op::cam:
    case Op::cam_off: {
      CouplingStop s{held(c), false, {}, false, 0, 0, false, {}, true, {}, false, {}};
      coordination::CamOut& cam = s.cam_sync;
      cam.on = c.op == Op::cam;
      cam.shape = static_cast<std::uint8_t>(c.cam_shape);
      cam.a = c.cam_a;
      cam.b = c.cam_b;
      cam.r = c.sync_r;
      cam.points = std::min(c.cam_lift.size(), cam.lift.size());  // the interpreter's #1-#999
      std::copy_n(c.cam_lift.begin(), cam.points, cam.lift.begin());
      return s;
    }
    case Op::egb:
    case Op::egb_off: {
      CouplingStop s{held(c), false, {}, false, 0, 0, false, {}, false, {}, true, {}};
      coordination::EgbOut& egb = s.egb_sync;
      egb.on = c.op == Op::egb;
      egb.teeth = c.egb_teeth;
      egb.threads = c.egb_threads;
      egb.helix = c.egb_helix;
      egb.module = c.egb_module;
      egb.phase = c.egb_phase;
      egb.r = c.sync_r;
      return s;
    }
    case Op::spindle_mode:
      return ModeStop{held(c), c.position_control};
    case Op::axis_couple:
    case Op::axis_decouple:
      return CouplingStop{held(c),
                          true,
                          {},
                          c.op == Op::axis_couple,
                          static_cast<std::uint32_t>(c.master),
                          static_cast<std::uint32_t>(c.slave),
                          false,
                          {},
                          false,
                          {},
                          false,
                          {}};
    case Op::wait_input:
    case Op::wait_spindle: {
      const coordination::ConditionSpec spec{c.op == Op::wait_input,
                                             c.input,
                                             c.input_on,
                                             c.timeout_s,
                                             c.width_s,
                                             c.spindle,
                                             c.rpm,
                                             c.dwell_s};
      return WaitStop{held(c), coordination::ConditionBlock(spec, rules.conditions)};
    }
    case Op::torque_limit:
    case Op::load_watch:
      return TorqueDataStop{held(c),
                            c.op == Op::torque_limit,
                            c.torque_data_axes,
                            c.torque_data,
                            c.every_move,
                            c.filter_s,
                            c.load_timer};
    case Op::torque_mode:
      return TorqueModeStop{held(c), c.torque_mode_p, c.torque_data_axes, c.torque_data};
    case Op::load_timer_check:
      return LoadTimerStop{held(c),       c.load_timer,         c.timer_longer, c.torque_data_axes,
                           c.torque_data, c.timer_variable != 0};
    default:
      break;
  }
  const bool spindle_start =
      c.op == Op::spindle &&
      ((c.spindle_direction == SpindleDirection::cw && spindle_queued != 1) ||
       (c.spindle_direction == SpindleDirection::ccw && spindle_queued != -1));
  spindle_queued = spindle_after(c, spindle_queued);
  if ((rules.plc && (c.op == Op::aux || c.op == Op::tool)) ||
      (spindle_start && (rules.plc || rules.spindle_may_follow))) {
    // Sent when every block before it ended; the next block waits for the answer.
    const int code = c.op == Op::tool ? c.tool * 100 + c.offset
                     : spindle_start  ? (c.spindle_direction == SpindleDirection::cw ? 3 : 4)
                                      : c.code;
    return AuxStop{held(c),
                   c.op == Op::tool ? coordination::AuxKind::t_code : coordination::AuxKind::m_code,
                   code, spindle_start, c};
  }
  if (c.overload_axes != 0 && c.moves()) {  // G10 L14 P7/P8: a watched in-feed
    OverloadStop s;
    s.command = c;
    return s;
  }
  // G31 (P98/P99 on the load too), G160 (P-1 only moves).
  if (c.skip || c.load_skip || (c.torque_skip && c.torque_limit > 0.0)) {
    SkipStop s;
    s.command = c;
    s.arm = !c.skip        ? ProbeArm::torque
            : c.multi_skip ? (c.input_on ? ProbeArm::every_rising : ProbeArm::every_falling)
            : c.input_on   ? ProbeArm::rising
                           : ProbeArm::falling;
    return s;
  }
  return std::monostate{};
}

}  // namespace mcnc::channel
