#include "axisnode/coupling/catch_up.hpp"

#include <algorithm>

namespace mcnc::coupling {

double catch_up_acceleration(double phase_error, double speed_error, double cycle_s,
                             double max_acceleration) noexcept {
  const double omega = std::min(20.0, 0.25 / cycle_s);  // rad/s
  return std::clamp(omega * omega * phase_error + 2.0 * omega * speed_error, -max_acceleration,
                    max_acceleration);
}

}  // namespace mcnc::coupling
