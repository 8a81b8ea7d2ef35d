#pragma once
// A thread's path position as a function of the spindle's revolutions since the thread's start
// angle. The ramp-in and ramp-out are jerk-limited S-curves laid out in revolutions (planned
// once from the commanded spindle speed), so the whole thread is a fixed function of the
// spindle angle: every pass of a cycle cuts the same helix whatever the spindle's actual speed,
// and between the ramps the lead is exact while the speed varies. Pure math.
#include "channel/motion/speed_transition.hpp"

namespace mcnc::motion {

struct ThreadGeometry {
  double length = 0.0;       // path length of the threaded move
  double path_lead = 0.0;    // path travel per revolution at the start (> 0)
  double path_change = 0.0;  // change of path_lead per revolution (G34)
  bool ramp_in = true;       // false: already at speed (the next block of a continuous thread)
  bool ramp_out = true;      // false: the next block goes on at speed
};

// Position along the thread (s), ds/du and d2s/du2, u in revolutions.
struct ThreadSample {
  double s = 0.0;
  double ds_du = 0.0;
  double d2s_du2 = 0.0;
};

class ThreadFollower {
 public:
  // rev_per_s: the spindle speed the ramps are planned for; limits: the path's acceleration
  // and jerk the ramps may use at that speed. False when the geometry is unusable.
  bool plan(const ThreadGeometry& geometry, double rev_per_s, const JerkLimits& limits) noexcept;

  [[nodiscard]] ThreadSample at(double u) const noexcept;
  // Revolutions from the start angle to the end of the thread.
  [[nodiscard]] double end_revolutions() const noexcept { return u_end_; }
  [[nodiscard]] double ramp_out_start() const noexcept { return u_out_; }

 private:
  [[nodiscard]] double lead_at(double u) const noexcept {
    return geometry_.path_lead + geometry_.path_change * u;
  }
  // The synchronous part: s = offset + integral of the lead from u_in_.
  [[nodiscard]] double sync_s(double u) const noexcept;

  ThreadGeometry geometry_{};
  double n_ = 1.0;  // rev/s the ramps are laid out for
  JerkPhases ramp_in_;
  JerkPhases ramp_out_;  // as a ramp-in from rest to the end speed; run backward
  double u_in_ = 0.0;    // revolutions of the ramp-in
  double s_in_ = 0.0;    // path length of the ramp-in
  double u_out_ = 0.0;   // revolution where the ramp-out begins
  double s_out_ = 0.0;   // path length of the ramp-out
  double u_end_ = 0.0;
};

}  // namespace mcnc::motion
