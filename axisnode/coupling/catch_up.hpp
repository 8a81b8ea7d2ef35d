#pragma once
// How a coupled axis catches up with a target that moves on at a speed of its own (G114.1 and
// G51.2 in SpindleCoupling, G81.4 in GearBoxCoupling): one rule for all of them. Pure.

namespace mcnc::coupling {

// The acceleration (units/s^2) of a critically damped pull on `phase_error` (the target minus
// where the axis would be next cycle at its present speed) and `speed_error` (the target's speed
// minus the axis's), within +-max_acceleration. The speed term leads while the speeds differ, so
// the axis reaches the target's speed first and then closes the phase, settling in a few tenths
// of a second.
double catch_up_acceleration(double phase_error, double speed_error, double cycle_s,
                             double max_acceleration) noexcept;

}  // namespace mcnc::coupling
