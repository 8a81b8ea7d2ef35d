#pragma once
// A 1-D move from rest to rest with bounded velocity and acceleration: a trapezoid when the
// distance allows reaching the speed limit, otherwise a triangle. Pure math, no allocation.
namespace mcnc::motion {

struct ProfileSample {
  double s = 0.0;  // distance travelled
  double v = 0.0;  // velocity
  double a = 0.0;  // acceleration
};

class TrapezoidProfile {
 public:
  TrapezoidProfile() = default;
  // distance >= 0, v_max > 0, a_max > 0 (the caller checks).
  TrapezoidProfile(double distance, double v_max, double a_max) noexcept;

  // The state at time t after the start; before 0 it is the start, from duration() on the end.
  [[nodiscard]] ProfileSample at(double t) const noexcept;

  [[nodiscard]] double duration() const noexcept { return t_total_; }
  [[nodiscard]] double peak_velocity() const noexcept { return v_peak_; }
  [[nodiscard]] double accel_time() const noexcept { return t_accel_; }
  [[nodiscard]] double cruise_time() const noexcept { return t_cruise_; }
  [[nodiscard]] bool is_triangle() const noexcept { return t_cruise_ == 0.0; }

 private:
  double distance_ = 0.0;
  double accel_ = 0.0;
  double v_peak_ = 0.0;
  double t_accel_ = 0.0;
  double t_cruise_ = 0.0;
  double t_total_ = 0.0;
  double s_accel_ = 0.0;  // distance covered while accelerating
};

}  // namespace mcnc::motion
