#include "axisnode/coupling/axis_coupling.hpp"

namespace mcnc::coupling {

void AxisCoupling::couple(std::uint32_t master) noexcept {
  master_ = master;
  based_ = false;
}

AxisTarget AxisCoupling::step(double master_cmd, double slave_cmd) noexcept {
  if (!based_) {
    based_ = true;
    base_master_ = master_cmd;
    base_slave_ = slave_cmd;
    last_master_ = master_cmd;
  }
  const double increment = master_cmd - last_master_;
  last_master_ = master_cmd;
  // The master's position now: where it was, plus what it moved in the last cycle.
  const double master_now = master_cmd + increment;
  return AxisTarget{base_slave_ + (master_now - base_master_), increment / cycle_s_};
}

}  // namespace mcnc::coupling
