#include "axisnode/coupling/spindle_coupling.hpp"

#include "axisnode/coupling/catch_up.hpp"

#include <cmath>

namespace mcnc::coupling {

double wrap_degrees(double angle) noexcept {
  double a = std::fmod(angle, 360.0);
  if (a <= -180.0) {
    a += 360.0;
  } else if (a > 180.0) {
    a -= 360.0;
  }
  return a;
}

SpindleCouplingCommand polygon_command(int p, int q, double master_start) noexcept {
  const double ratio = static_cast<double>(q) / static_cast<double>(p);
  return SpindleCouplingCommand{p, q, wrap_degrees(-master_start * ratio)};
}

void SpindleCoupling::couple(const SpindleCouplingCommand& command, double slave_pos,
                             double slave_vel) noexcept {
  command_ = command;
  active_ = true;
  locked_ = false;
  releasing_ = false;
  pos_ = slave_pos;
  vel_ = slave_vel;
}

SlaveTarget SpindleCoupling::step(double master_pos, double master_vel) noexcept {
  if (!active_) {
    return SlaveTarget{pos_, vel_, false};
  }
  if (releasing_) {
    return step_release();
  }
  const double ratio = static_cast<double>(command_.q) / static_cast<double>(command_.p);
  const double want_vel = master_vel * ratio;
  // Where the slave should be at this cycle, modulo a revolution: the nearest such position.
  const double target = master_pos * ratio + command_.r;
  if (locked_) {
    pos_ += wrap_degrees(target - pos_);  // follows exactly
    vel_ = want_vel;
    return SlaveTarget{pos_, vel_, true};
  }
  // Catch up on the phase modulo a revolution (where the slave would be at its present speed).
  const double dt = setup_.cycle_s;
  const double acc = catch_up_acceleration(wrap_degrees(target - (pos_ + vel_ * dt)),
                                           want_vel - vel_, dt, setup_.max_acceleration);
  vel_ += acc * dt;
  pos_ += vel_ * dt;
  const double after = wrap_degrees(target - pos_);
  if (std::fabs(after) <= setup_.lock_phase && std::fabs(want_vel - vel_) <= setup_.lock_speed) {
    locked_ = true;
  }
  return SlaveTarget{pos_, vel_, locked_};
}

SlaveTarget SpindleCoupling::step_release() noexcept {
  const double dv = setup_.max_acceleration * setup_.cycle_s;
  vel_ = std::fabs(vel_) <= dv ? 0.0 : vel_ - std::copysign(dv, vel_);
  pos_ += vel_ * setup_.cycle_s;
  locked_ = false;
  if (vel_ == 0.0) {
    active_ = false;  // at rest: the slave is its owner's again
    releasing_ = false;
  }
  return SlaveTarget{pos_, vel_, false};
}

}  // namespace mcnc::coupling
