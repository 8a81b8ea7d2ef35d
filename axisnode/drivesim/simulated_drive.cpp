#include "axisnode/drivesim/simulated_drive.hpp"

#include "canopen/sdo_abort.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace mcnc::drivesim {

using canopen::NmtCommand;
using canopen::NmtState;
using cia402::State;

SimulatedDrive::SimulatedDrive(const DriveParams& params, double cycle_s) noexcept
    : params_(params),
      cycle_s_(cycle_s),
      position_(params.initial_position),
      target_(params.initial_position),
      objects_(params.node_id) {
  previous_target_ = params.initial_position;
  objects_.live.rated_torque =
      static_cast<std::uint32_t>(std::lround(std::min(params.rated_torque * 1000.0, 4.0e9)));
  (void)apply_defaults();  // the simulator's shell checks them at start (apply_defaults)
}

std::uint32_t SimulatedDrive::apply_defaults(ObjectDefault* failed) noexcept {
  const auto write = [&](const ObjectDefault& d) -> std::uint32_t {
    canopen::SdoValue current;
    if (const std::uint32_t e = objects_.read(d.index, d.sub, current)) {
      return e;
    }
    // The value must fit the object (signed or unsigned, as the dictionary does not say).
    const std::int64_t bits = static_cast<std::int64_t>(current.size) * 8;
    if (current.size == 0 || current.size > 4 || d.value < -(std::int64_t{1} << (bits - 1)) ||
        d.value >= (std::int64_t{1} << bits)) {
      return canopen::sdo_abort::kInvalidValue;
    }
    std::array<std::uint8_t, 8> bytes{};
    const auto raw = static_cast<std::uint64_t>(d.value);
    for (std::size_t b = 0; b < current.size && b < bytes.size(); ++b) {
      bytes[b] = static_cast<std::uint8_t>(raw >> (8 * b));
    }
    return objects_.write(d.index, d.sub, bytes.data(), current.size);
  };
  const double counts = params_.quick_stop_decel * params_.counts_per_unit;
  const ObjectDefault decel{0x6085, 0,
                            static_cast<std::int64_t>(std::clamp(counts, 1.0, 4294967295.0))};
  // 0x6072: the drive's peak torque, until a master limits it. Rounded up, so that the whole
  // per mille never limits below torque_limit itself (10 N m at 3 N m rated is 3333.3 per
  // mille: 3333 would cap the torque at 9.999 N m and change every acceleration at the limit).
  const double peak = params_.torque_limit / std::max(params_.rated_torque, 1e-9) * 1000.0;
  const ObjectDefault max_torque{
      0x6072, 0, static_cast<std::int64_t>(std::clamp(std::ceil(peak), 0.0, 65535.0))};
  for (const ObjectDefault& d : {decel, max_torque}) {
    if (const std::uint32_t e = write(d)) {
      if (failed != nullptr) {
        *failed = d;
      }
      return e;
    }
  }
  for (std::size_t i = 0; i < params_.object_count && i < params_.objects.size(); ++i) {
    if (const std::uint32_t e = write(params_.objects[i])) {
      if (failed != nullptr) {
        *failed = params_.objects[i];
      }
      return e;
    }
  }
  return 0;
}

std::uint8_t SimulatedDrive::node_id() const noexcept {
  return params_.node_id;
}
NmtState SimulatedDrive::nmt_state() const noexcept {
  return nmt_;
}
State SimulatedDrive::state() const noexcept {
  return device_.state();
}
double SimulatedDrive::position() const noexcept {
  return position_;
}
double SimulatedDrive::velocity() const noexcept {
  return velocity_;
}
double SimulatedDrive::target() const noexcept {
  return target_;
}

void SimulatedDrive::power_on() noexcept {
  powered_ = true;
  nmt_ = NmtState::preoperational;
  device_.power_on();
}

void SimulatedDrive::on_nmt(NmtCommand command) noexcept {
  if (!powered_) {
    return;
  }
  const bool was_operational = nmt_ == NmtState::operational;
  switch (command) {
    case NmtCommand::start:
      nmt_ = NmtState::operational;
      break;
    case NmtCommand::stop:
      nmt_ = NmtState::stopped;
      break;
    case NmtCommand::enter_preoperational:
      nmt_ = NmtState::preoperational;
      break;
    case NmtCommand::reset_node:
      objects_ = DriveObjects(params_.node_id);
      (void)apply_defaults();
      device_ = cia402::DeviceStateMachine{};
      device_.power_on();
      latched_ = {};
      rpdo_since_sync_ = false;
      velocity_ = 0.0;
      target_ = position_;
      nmt_ = NmtState::preoperational;
      break;
    case NmtCommand::reset_communication:
      objects_.reset_communication();
      latched_ = {};
      rpdo_since_sync_ = false;
      nmt_ = NmtState::preoperational;
      break;
  }
  if (nmt_ == NmtState::operational) {
    out_of_operation_ = false;
  } else if (was_operational) {
    out_of_operation_ = true;
    wall_heartbeat_ms_ = 0;  // starts afresh: the first heartbeat at once
  }
}

void SimulatedDrive::on_rpdo(const canopen::RxPdoCsp& pdo) noexcept {
  if (nmt_ != NmtState::operational) {
    return;
  }
  RpdoValues values;
  values.controlword = pdo.controlword;
  values.target_position = pdo.target_position;
  values.has_controlword = true;
  values.has_target_position = true;
  on_rpdo(values);
}

void SimulatedDrive::on_rpdo(const RpdoValues& values) noexcept {
  if (nmt_ != NmtState::operational) {
    return;
  }
  latched_.merge(values);
  rpdo_since_sync_ = true;
}

canopen::TxPdoCsp SimulatedDrive::on_sync() noexcept {
  const State before = device_.state();
  // The controlword stays in the object dictionary, so it is evaluated again on every SYNC
  // (like a real drive, one transition per evaluation).
  device_.apply(latched_.controlword);
  const State now = device_.state();
  const std::int8_t mode_before = objects_.mode();
  if (latched_.has_mode && rpdo_since_sync_) {
    const auto value = static_cast<std::uint8_t>(latched_.mode);
    (void)objects_.write(0x6060, 0, &value, 1);  // a mode it does not have is not taken
  }
  if (latched_.has_touch_probe && rpdo_since_sync_) {
    const std::array<std::uint8_t, 2> value{static_cast<std::uint8_t>(latched_.touch_probe & 0xFFU),
                                            static_cast<std::uint8_t>(latched_.touch_probe >> 8)};
    (void)objects_.write(0x60B8, 0, value.data(), value.size());
  }
  if (latched_.has_max_torque && rpdo_since_sync_) {
    const std::array<std::uint8_t, 2> value{static_cast<std::uint8_t>(latched_.max_torque & 0xFFU),
                                            static_cast<std::uint8_t>(latched_.max_torque >> 8)};
    (void)objects_.write(0x6072, 0, value.data(), value.size());
  }
  if (latched_.has_target_torque && rpdo_since_sync_) {
    const auto raw = static_cast<std::uint16_t>(latched_.target_torque);
    const std::array<std::uint8_t, 2> value{static_cast<std::uint8_t>(raw & 0xFFU),
                                            static_cast<std::uint8_t>(raw >> 8)};
    (void)objects_.write(0x6071, 0, value.data(), value.size());
  }
  if (latched_.has_max_motor_speed && rpdo_since_sync_) {
    const std::uint32_t s = latched_.max_motor_speed;
    const std::array<std::uint8_t, 4> value{
        static_cast<std::uint8_t>(s & 0xFFU), static_cast<std::uint8_t>((s >> 8) & 0xFFU),
        static_cast<std::uint8_t>((s >> 16) & 0xFFU), static_cast<std::uint8_t>(s >> 24)};
    (void)objects_.write(0x6080, 0, value.data(), value.size());
  }

  const std::int8_t mode = objects_.mode();
  const bool homing_bit = (latched_.controlword & 0x0010U) != 0;
  if (mode != 6) {
    homing_attained_ = false;
  }
  if (now == State::operation_enabled && before == State::operation_enabled && rpdo_since_sync_) {
    if (mode == 9) {
      velocity_target_ = static_cast<double>(latched_.target_velocity) / params_.counts_per_unit;
    } else if (mode != 6) {
      // 32-bit positions wrap: the target is the one nearest the present position.
      const auto base =
          static_cast<std::int64_t>(std::llround(position_ * params_.counts_per_unit));
      const auto diff =
          static_cast<std::int32_t>(static_cast<std::uint32_t>(latched_.target_position) -
                                    static_cast<std::uint32_t>(base & 0xFFFFFFFFLL));
      target_ = static_cast<double>(base + diff) / params_.counts_per_unit;
      if (mode_before == 9) {
        // Into CSP while turning: the fine interpolation starts where the target was a cycle
        // ago at the present speed, not from a standstill.
        previous_target_ = target_ - velocity_ * cycle_s_;
      }
    }
  } else if (now != State::operation_enabled) {
    target_ = position_;
    velocity_target_ = 0.0;
  }
  if (mode == 6 && now == State::operation_enabled && homing_bit && !homing_bit_) {
    // Methods 35/37: here is home. The position value jumps, the motor does not move.
    position_ = static_cast<double>(objects_.home_offset()) / params_.counts_per_unit;
    target_ = position_;
    velocity_ = 0.0;
    homing_attained_ = true;
  }
  homing_bit_ = homing_bit;
  // On the SYNC that enables operation the target stays at the actual position: the latched
  // target was written while disabled and may be stale.
  rpdo_since_sync_ = false;

  const double from = position_;
  move_one_cycle();
  run_touch_probe(from);

  canopen::TxPdoCsp out;
  out.statusword = cia402::encode_statusword(now, target_reached());
  if (homing_attained_) {
    out.statusword |= 0x1000U;  // bit 12: homing attained
  }
  out.position_actual = position_counts(position_);
  objects_.live.statusword = out.statusword;
  objects_.live.position = out.position_actual;
  objects_.live.velocity = to_counts(velocity_);
  objects_.live.following_error = to_counts(target_ - position_);
  objects_.live.torque = static_cast<std::int16_t>(
      std::lround(std::clamp(torque_ / params_.rated_torque * 1000.0, -32768.0, 32767.0)));
  ++syncs_;
  if (fault_ != DriveFault::none && syncs_ == fault_at_) {
    if (fault_ == DriveFault::heartbeat_stop) {
      heartbeat_stopped_ = true;
    } else {
      // Error register 0x01 (generic) plus the class bit: current 0x02, or generic only.
      emcy_ = fault_ == DriveFault::overcurrent ? canopen::Emcy{0x2310, 0x03}
                                                : canopen::Emcy{0x8611, 0x01};
      device_.on_fault();
    }
  }
  return out;
}

bool SimulatedDrive::heartbeat(can::CanFrame& out) noexcept {
  if (heartbeat_stopped_) {
    return false;
  }
  if (objects_.heartbeat_ms() != heartbeat_ms_) {
    heartbeat_ms_ = objects_.heartbeat_ms();
    heartbeat_ = canopen::HeartbeatProducer(params_.node_id, heartbeat_ms_ * 1000ULL);
  }
  const auto now_us =
      static_cast<std::uint64_t>(std::llround(static_cast<double>(syncs_) * cycle_s_ * 1e6));
  return heartbeat_.due(now_us, nmt_, out);
}

bool SimulatedDrive::heartbeat_out_of_operation(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (!out_of_operation_ || heartbeat_stopped_ || objects_.heartbeat_ms() == 0) {
    return false;
  }
  if (objects_.heartbeat_ms() != wall_heartbeat_ms_) {
    wall_heartbeat_ms_ = objects_.heartbeat_ms();
    wall_heartbeat_ = canopen::HeartbeatProducer(params_.node_id, wall_heartbeat_ms_ * 1000ULL);
  }
  return wall_heartbeat_.due(now_us, nmt_, out);
}

void SimulatedDrive::run_loops(Loop loop, double dt) noexcept {
  constexpr double kTwoPi = 6.283185307179586;
  // At least 8 steps per cycle, and enough that the explicit integration of the velocity loop
  // and of the friction stays stable (each step well under their time constants) at any cycle
  // and tuning the machine file allows.
  const double stiffest = std::max(kTwoPi * params_.velocity_bandwidth_hz,
                                   params_.friction / std::max(params_.inertia, 1e-12));
  const int steps = static_cast<int>(std::clamp(std::ceil(2.0 * stiffest * dt), 8.0, 4096.0));
  const double h = dt / steps;
  const double rad_per_unit = kTwoPi / params_.units_per_rev;
  const double j = params_.inertia;
  const double kv = j * kTwoPi * params_.velocity_bandwidth_hz;  // N m per rad/s
  const double ki = kv * kTwoPi * params_.velocity_bandwidth_hz / 4.0;
  const double kp = 1.0 / std::max(params_.time_constant_s, dt);
  const double t_max = std::min(params_.torque_limit, static_cast<double>(objects_.max_torque()) /
                                                          1000.0 * params_.rated_torque);
  for (int i = 0; i < steps; ++i) {
    double command = 0.0;       // units/s
    double feed_forward = 0.0;  // N m: the torque a known acceleration takes
    double direct = 0.0;        // N m: CST's torque, no velocity loop
    switch (loop) {
      case Loop::position: {
        // Fine interpolation, as CSP drives do: the target moves from the last SYNC's to this
        // one's in even steps over the cycle.
        const double fraction = static_cast<double>(i + 1) / steps;
        const double target = previous_target_ + (target_ - previous_target_) * fraction;
        command =
            std::clamp((target - position_) * kp, -params_.max_velocity, params_.max_velocity);
        break;
      }
      case Loop::velocity:
        command = std::clamp(velocity_target_, -params_.max_velocity, params_.max_velocity);
        break;
      case Loop::torque: {
        // CST: the torque is the target 0x6071. The speed limit 0x6080 (and the drive's
        // max_velocity) bounds the motor the way it turns, as a drive's speed limiting does:
        // a proportional velocity loop toward the limit takes over where it asks for less.
        const double set =
            static_cast<double>(objects_.target_torque()) / 1000.0 * params_.rated_torque;
        const double rpm = static_cast<double>(objects_.max_motor_speed());
        const double limit =
            rpm > 0.0 ? std::min(rpm / 60.0 * params_.units_per_rev, params_.max_velocity)
                      : params_.max_velocity;
        const double to_limit = kv * (std::copysign(limit, set) - velocity_) * rad_per_unit;
        direct = set >= 0.0 ? std::min(set, to_limit) : std::max(set, to_limit);
        integral_ = 0.0;  // back in CSP, the velocity loop starts afresh
        break;
      }
      case Loop::ramp_down: {
        // 0x6085, as the master configured it (or the drive's default).
        const double step =
            static_cast<double>(objects_.quick_stop_deceleration()) / params_.counts_per_unit * h;
        const double before = ramp_;
        ramp_ = std::abs(ramp_) <= step ? 0.0 : ramp_ - std::copysign(step, ramp_);
        command = ramp_;
        feed_forward = j * (ramp_ - before) / h * rad_per_unit;  // the drive knows its ramp
        break;
      }
    }
    const double w = velocity_ * rad_per_unit;
    const double error = (command - velocity_) * rad_per_unit;
    double torque = loop == Loop::torque ? direct : kv * error + integral_ + feed_forward;
    if (std::abs(torque) > t_max) {
      torque = std::copysign(t_max, torque);  // saturated: the integral holds (anti-windup)
    } else if (loop != Loop::torque) {
      integral_ = std::clamp(integral_ + ki * error * h, -t_max, t_max);
    }
    torque_ = torque;
    const double w_next = w + (torque - params_.friction * w) / j * h;
    velocity_ = w_next / rad_per_unit;
    position_ += velocity_ * h;
    if (params_.contact_side != 0 &&
        (position_ - params_.contact_at) * params_.contact_side > 0.0) {
      position_ = params_.contact_at;  // the contact holds the load: it stands there
      velocity_ = 0.0;
    }
  }
}

void SimulatedDrive::move_one_cycle() noexcept {
  const double dt = cycle_s_;
  const State state = device_.state();
  if (state != State::quick_stop_active && state != State::fault_reaction_active) {
    ramp_ = velocity_;  // a quick stop ramps down from wherever it finds the motor
  }
  switch (state) {
    case State::operation_enabled: {
      if (objects_.mode() == 9) {
        run_loops(Loop::velocity, dt);
        target_ = position_;
        break;
      }
      if (objects_.mode() == 10) {
        run_loops(Loop::torque, dt);
        target_ = position_;  // back in CSP, the position loop starts where the motor is
        break;
      }
      if (objects_.mode() == 6) {
        velocity_ = 0.0;  // homing by method 35/37 does not move
        integral_ = 0.0;
        torque_ = 0.0;
        break;
      }
      run_loops(Loop::position, dt);
      break;
    }
    case State::quick_stop_active:
    case State::fault_reaction_active: {
      run_loops(Loop::ramp_down, dt);
      target_ = position_;
      if (ramp_ == 0.0 && std::abs(velocity_) * params_.counts_per_unit < 0.5 / dt) {
        velocity_ = 0.0;  // standing still (under an increment per cycle): the brake holds
        integral_ = 0.0;
        torque_ = 0.0;
        if (state == State::fault_reaction_active) {
          device_.on_fault_reaction_done();
        }
      }
      break;
    }
    default:
      velocity_ = 0.0;
      integral_ = 0.0;
      torque_ = 0.0;
      target_ = position_;
      break;
  }
  previous_target_ = target_;
}

bool SimulatedDrive::target_reached() const noexcept {
  switch (device_.state()) {
    case State::operation_enabled:
      // Within half an increment: what the drive can resolve.
      return std::abs(target_ - position_) * params_.counts_per_unit <= 0.5;
    case State::quick_stop_active:
      return velocity_ == 0.0;  // CiA 402: in quick stop, bit 10 means "halted"
    default:
      return false;
  }
}

std::int32_t SimulatedDrive::position_counts(double units) const noexcept {
  // Modulo 2^32, as a drive's position actual value wraps (a spindle after many turns).
  const double counts = std::round(units * params_.counts_per_unit);
  if (!std::isfinite(counts)) {
    return 0;
  }
  const double wrapped = std::fmod(counts, 4294967296.0);
  const auto u = static_cast<std::uint32_t>(static_cast<std::int64_t>(wrapped) & 0xFFFFFFFFLL);
  return static_cast<std::int32_t>(u);
}

std::int32_t SimulatedDrive::to_counts(double units) const noexcept {
  const double counts = std::round(units * params_.counts_per_unit);
  constexpr double kMin = std::numeric_limits<std::int32_t>::min();
  constexpr double kMax = std::numeric_limits<std::int32_t>::max();
  if (!(counts >= kMin)) {  // also catches NaN
    return std::numeric_limits<std::int32_t>::min();
  }
  if (counts > kMax) {
    return std::numeric_limits<std::int32_t>::max();
  }
  return static_cast<std::int32_t>(counts);
}

bool SimulatedDrive::probe_input(double position) const noexcept {
  const double d =
      params_.probe_side > 0 ? position - params_.probe_at : params_.probe_at - position;
  if (!(d >= 0.0)) {
    return false;
  }
  if (params_.probe_pitch <= 0.0) {
    return true;  // one part face: on at or beyond it
  }
  const double k = std::floor(d / params_.probe_pitch);
  return k < params_.probe_count && d - k * params_.probe_pitch < params_.probe_width;
}

namespace {

// The input's edges in one cycle's travel, along d (the distance beyond the probe's position on
// its side): how many went on and off, and the first and last of each, in travel order.
struct ProbeEdges {
  int on = 0;
  int off = 0;
  double first_on = 0.0;
  double last_on = 0.0;
  double first_off = 0.0;
  double last_off = 0.0;

  void add(bool going_on, double b) noexcept {
    int& n = going_on ? on : off;
    (going_on ? last_on : last_off) = b;
    if (n++ == 0) {
      (going_on ? first_on : first_off) = b;
    }
  }
};

}  // namespace

void SimulatedDrive::run_touch_probe(double from) noexcept {
  namespace tp = canopen::touch_probe;
  const std::uint16_t function = objects_.touch_probe();
  if (params_.probe_side == 0 || (function & tp::kEnable) == 0) {
    probe_status_ = 0;  // disabling clears what was stored, and the edge count
    objects_.live.touch_probe_status = probe_status_;
    return;
  }
  probe_status_ |= tp::kEnabled;
  const double side = params_.probe_side > 0 ? 1.0 : -1.0;
  const double d0 = side * (from - params_.probe_at);
  const double d1 = side * (position_ - params_.probe_at);
  // Each window [k pitch, k pitch + width) of d switches the input at its two bounds (one
  // bound, 0, without teeth); the bounds crossed in travel order, nearest d0 first.
  ProbeEdges edges;
  const bool up = d1 > d0;
  const auto cross = [&](double b, bool window_start) {
    if ((d0 < b) != (d1 < b)) {
      edges.add(window_start == up, b);
    }
  };
  if (params_.probe_pitch <= 0.0) {
    cross(0.0, true);
  } else {
    const double lo = std::min(d0, d1);
    const double hi = std::max(d0, d1);
    const int k_low = std::max(0, static_cast<int>(std::floor(lo / params_.probe_pitch)) - 1);
    const int k_high = std::min(params_.probe_count - 1,
                                static_cast<int>(std::floor(hi / params_.probe_pitch)) + 1);
    for (int i = 0; i <= k_high - k_low; ++i) {
      const int k = up ? k_low + i : k_high - i;
      const double start = k * params_.probe_pitch;
      const double end = start + params_.probe_width;
      if (up) {
        cross(start, true);
        cross(end, false);
      } else {
        cross(end, false);
        cross(start, true);
      }
    }
  }
  // A drive latches its encoder at the edge, between two cycles' positions. First event: the
  // first edge of its kind and none after; continuous: the last one, the count on by each.
  const bool continuous = (function & tp::kContinuous) != 0;
  int latched = 0;
  const auto latch = [&](int n, double first, double last, std::uint16_t stored,
                         std::int32_t& value) {
    if (n == 0 || (!continuous && (probe_status_ & stored) != 0)) {
      return;
    }
    probe_status_ |= stored;
    value = position_counts(params_.probe_at + side * (continuous ? last : first));
    latched += continuous ? n : 0;
  };
  if ((function & tp::kPositiveEdge) != 0) {
    latch(edges.on, edges.first_on, edges.last_on, tp::kPositiveStored,
          objects_.live.probe_positive);
  }
  if ((function & tp::kNegativeEdge) != 0) {
    latch(edges.off, edges.first_off, edges.last_off, tp::kNegativeStored,
          objects_.live.probe_negative);
  }
  const auto count = static_cast<std::uint16_t>(
      ((probe_status_ >> tp::kEdgeCountShift) + static_cast<unsigned>(latched)) & 3U);
  probe_status_ = static_cast<std::uint16_t>((probe_status_ & ~tp::kEdgeCountMask) |
                                             (count << tp::kEdgeCountShift));
  objects_.live.touch_probe_status = probe_status_;
}

}  // namespace mcnc::drivesim
