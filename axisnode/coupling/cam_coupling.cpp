#include "axisnode/coupling/cam_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::coupling {

namespace {

// `deg` folded into [0, 360).
double turn_fraction_deg(double deg) noexcept {
  double a = std::fmod(deg, 360.0);
  if (a < 0.0) {
    a += 360.0;
  }
  return a >= 360.0 ? 0.0 : a;
}

double table_lift(const CamProfile& p, double angle) noexcept {
  const double step = 360.0 / static_cast<double>(p.points);
  const double at = angle / step;
  auto i = static_cast<std::size_t>(at);
  if (i >= p.points) {
    i = p.points - 1;
  }
  const double f = at - static_cast<double>(i);
  const double next = p.lift[i + 1 < p.points ? i + 1 : 0];
  return p.lift[i] + (next - p.lift[i]) * f;
}

// The fastest relative velocity from which `gap` can still be closed in whole cycles without
// passing it, at `acc` (the discrete form of sqrt(2 acc gap)).
double closing_speed(double gap, double acc, double dt) noexcept {
  const double step = acc * dt * dt;
  return acc * dt * (std::sqrt(0.25 + 2.0 * std::fabs(gap) / step) - 0.5);
}

}  // namespace

const char* cam_profile_error(const CamProfile& p) noexcept {
  if (!(p.start >= 0.0 && p.start <= 360.0)) {
    return "the start angle R must be 0-360 degrees";
  }
  switch (p.shape) {
    case CamShape::table:
      if (p.points == 0 || p.points > kMaxCamPoints) {
        return "a cam table has 1-999 points";
      }
      for (std::size_t i = 0; i < p.points; ++i) {
        if (!std::isfinite(p.lift[i])) {
          return "a lift value is not a number";
        }
      }
      return nullptr;
    case CamShape::ellipse:
      return p.a > 0.0 && p.b > 0.0 && std::isfinite(p.a) && std::isfinite(p.b)
                 ? nullptr
                 : "the semi-axes A and B must be greater than 0";
    case CamShape::eccentric:
      if (!(p.a > 0.0 && std::isfinite(p.a))) {
        return "the circle's diameter D must be greater than 0";
      }
      return p.b >= 0.0 && p.b < p.a ? nullptr
                                     : "the eccentricity P must be 0 or more and below D/2";
  }
  return "unknown cam shape";
}

double cam_lift(const CamProfile& p, double master_deg) noexcept {
  const double angle = turn_fraction_deg(master_deg - p.start);
  const double th = angle * std::numbers::pi / 180.0;
  const double c = std::cos(th);
  const double s = std::sin(th);
  switch (p.shape) {
    case CamShape::table:
      return p.points == 0 ? 0.0 : table_lift(p, angle);
    case CamShape::ellipse:
      // The radius of the ellipse in direction th, a along th = 0.
      return p.a * p.b / std::sqrt(p.b * p.b * c * c + p.a * p.a * s * s) - p.a;
    case CamShape::eccentric:
      // The circle's edge in direction th from the spindle's axis, the centre at +b.
      return p.b * c + std::sqrt(p.a * p.a - p.b * p.b * s * s) - (p.a + p.b);
  }
  return 0.0;
}

CamProfile cam_profile_of(std::uint8_t shape, double first, double second, double start,
                          std::span<const double> lift) noexcept {
  CamProfile p;
  p.start = start;
  if (shape == 1) {
    p.shape = CamShape::ellipse;
    p.a = first;
    p.b = second;
  } else if (shape == 2) {
    p.shape = CamShape::eccentric;
    p.a = first / 2.0;
    p.b = second;
  } else if (shape == 0) {
    p.points = std::min(lift.size(), kMaxCamPoints);
    std::copy_n(lift.begin(), p.points, p.lift.begin());
  }
  return p;
}

void CamCoupling::couple(const CamProfile& profile) noexcept {
  profile_ = profile;
  if (!active_) {
    pos_ = 0.0;
    vel_ = 0.0;
  }
  active_ = true;
  releasing_ = false;
  locked_ = false;
  have_target_ = false;
}

CamOffset CamCoupling::step(double master_deg) noexcept {
  if (!active_) {
    return {};
  }
  return track(releasing_ ? 0.0 : cam_lift(profile_, master_deg));
}

CamOffset CamCoupling::step_without_master() noexcept {
  if (!active_) {
    return {};
  }
  if (releasing_) {
    return track(0.0);
  }
  vel_ = 0.0;  // no angle to follow: the lift stands where it is
  have_target_ = false;
  locked_ = false;
  return CamOffset{pos_, 0.0, false};
}

CamOffset CamCoupling::track(double target) noexcept {
  const double dt = setup_.cycle_s;
  const double acc = setup_.max_acceleration;
  // The lift's own velocity, and how far the offset is from where the lift was: the part of
  // the motion that catches up, limited so it can end without passing the lift.
  const double target_vel = have_target_ ? (target - target_) / dt : 0.0;
  const double gap = (have_target_ ? target_ : target) - pos_;
  const double closes = closing_speed(gap, acc, dt);
  const bool closes_now = std::fabs(gap) / dt <= closes;
  const double wanted = target_vel + (closes_now ? gap / dt : std::copysign(closes, gap));
  double v = std::clamp(wanted, vel_ - acc * dt, vel_ + acc * dt);
  v = std::clamp(v, -setup_.max_velocity, setup_.max_velocity);
  // On the lift this cycle, with neither limit in the way: locked.
  locked_ = closes_now && v == wanted;
  pos_ = locked_ ? target : pos_ + v * dt;
  vel_ = v;
  target_ = target;
  have_target_ = true;
  if (releasing_ && locked_ && std::fabs(vel_) <= acc * dt) {
    active_ = false;  // back at 0 and standing: the cam has ended
    releasing_ = false;
    pos_ = 0.0;
    vel_ = 0.0;
    return CamOffset{0.0, 0.0, false};
  }
  return CamOffset{pos_, vel_, locked_};
}

}  // namespace mcnc::coupling
