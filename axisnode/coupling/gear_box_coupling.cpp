#include "axisnode/coupling/gear_box_coupling.hpp"

#include "axisnode/coupling/catch_up.hpp"

#include <cmath>
#include <numbers>

namespace mcnc::coupling {

const char* gear_box_command_error(const GearBoxCommand& c) noexcept {
  if (c.teeth < 1) {
    return "T (the work's teeth) must be 1 or more";
  }
  if (c.threads == 0) {
    return "L (the hob's threads) must not be 0";
  }
  if (!(c.helix >= -90.0 && c.helix <= 90.0)) {
    return "P (the helix angle) must be -90 to 90 degrees";
  }
  if (c.helix != 0.0 && !(std::fabs(c.module) >= 0.1 && std::fabs(c.module) <= 25.0)) {
    return "a helical gear needs Q (the module), 0.1-25 mm";
  }
  if (c.phase && !(c.r >= 0.0 && c.r < 360.0)) {
    return "R (the work's phase) must be 0-359.999 degrees";
  }
  return nullptr;
}

double gear_box_ratio(const GearBoxCommand& c, bool reverse) noexcept {
  const double ratio = static_cast<double>(c.threads) / static_cast<double>(c.teeth);
  return reverse ? -ratio : ratio;
}

double helical_angle(const GearBoxCommand& c, double axial_travel, bool helix_reverse) noexcept {
  if (c.helix == 0.0 || c.module == 0.0) {
    return 0.0;
  }
  const double angle = axial_travel * std::sin(c.helix * std::numbers::pi / 180.0) /
                       (std::numbers::pi * static_cast<double>(c.teeth) * c.module) * 360.0;
  return helix_reverse ? -angle : angle;
}

void GearBoxCoupling::couple(const GearBoxCommand& command, double tool_deg, double axial,
                             double work_setpoint) noexcept {
  command_ = command;
  ratio_ = gear_box_ratio(command, setup_.reverse);
  axial_start_ = axial;
  if (command.phase) {
    // The work axis's angle is ratio x tool + R modulo one period: the nearest such target.
    const double period = 360.0 * std::fabs(ratio_);
    const double base = command.r - work_setpoint;
    const double at_start = ratio_ * tool_deg + base;
    target_base_ = base - period * std::round((at_start - pos_) / period);
  } else {
    target_base_ = pos_ - ratio_ * tool_deg;  // the phase it has now
  }
  if (!active_) {
    vel_ = 0.0;
  }
  active_ = true;
  releasing_ = false;
  locked_ = false;
  locked_once_ = false;
  deviation_s_ = 0.0;
  deviation_alarm_ = false;
  worst_deviation_ = 0.0;
}

void GearBoxCoupling::release() noexcept {
  if (!active_ || releasing_) {
    return;
  }
  releasing_ = true;
  locked_ = false;
  release_deceleration_ = setup_.stop_time_s > 0.0 ? std::fabs(vel_) / setup_.stop_time_s : 0.0;
}

void GearBoxCoupling::absorb() noexcept {
  if (!active_) {
    pos_ = 0.0;
  }
}

GearBoxOffset GearBoxCoupling::step(double tool_deg, double tool_vel, double axial,
                                    double axial_vel) noexcept {
  if (!active_) {
    return GearBoxOffset{pos_, 0.0, false};
  }
  if (releasing_) {
    return step_release();
  }
  const bool reverse = setup_.helix_reverse;
  const double target =
      ratio_ * tool_deg + helical_angle(command_, axial - axial_start_, reverse) + target_base_;
  const double want_vel = ratio_ * tool_vel + helical_angle(command_, axial_vel, reverse);
  const double dt = setup_.cycle_s;
  const double max_dv = setup_.max_acceleration * dt;
  if (locked_ && std::fabs(want_vel - vel_) <= max_dv * (1.0 + 1e-9)) {
    pos_ = target;  // on the ratio, within the work axis's acceleration: follows exactly
    vel_ = want_vel;
    watch_deviation(0.0);
    return GearBoxOffset{pos_, vel_, true};
  }
  locked_once_ = locked_once_ || locked_;
  locked_ = false;
  vel_ += catch_up_acceleration(target - (pos_ + vel_ * dt), want_vel - vel_, dt,
                                setup_.max_acceleration) *
          dt;
  pos_ += vel_ * dt;
  locked_ = std::fabs(target - pos_) <= setup_.lock_phase &&
            std::fabs(want_vel - vel_) <= setup_.lock_speed;
  // Only a coupling that had locked can fall behind: the catch-up after G81.4 is not a deviation.
  if (locked_once_) {
    watch_deviation(std::fabs(want_vel - vel_));
  }
  if (deviation_alarm_) {
    release();
  }
  return GearBoxOffset{pos_, vel_, locked_};
}

GearBoxOffset GearBoxCoupling::step_without_master() noexcept {
  release();
  return step(0.0, 0.0, 0.0, 0.0);
}

GearBoxOffset GearBoxCoupling::step_release() noexcept {
  const double dv = release_deceleration_ * setup_.cycle_s;
  vel_ = std::fabs(vel_) <= dv ? 0.0 : vel_ - std::copysign(dv, vel_);
  pos_ += vel_ * setup_.cycle_s;
  if (vel_ == 0.0) {
    active_ = false;  // at rest where it reached: the channel takes the offset over
    releasing_ = false;
  }
  return GearBoxOffset{pos_, vel_, false};
}

void GearBoxCoupling::watch_deviation(double deviation) noexcept {
  worst_deviation_ = std::fmax(worst_deviation_, deviation);
  if (setup_.max_deviation <= 0.0 || deviation <= setup_.max_deviation) {
    deviation_s_ = 0.0;
    return;
  }
  deviation_s_ += setup_.cycle_s;
  deviation_alarm_ = deviation_alarm_ || deviation_s_ > setup_.deviation_time_s;
}

}  // namespace mcnc::coupling
