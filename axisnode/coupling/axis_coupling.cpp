#include "axisnode/coupling/axis_coupling.hpp"

namespace mcnc::coupling {

void AxisCoupling::couple(std::uint32_t master) noexcept {
  master_ = master;
  based_ = false;
}

AxisTarget AxisCoupling::step(double master_now, double slave_cmd) noexcept {
  if (!based_) {
    based_ = true;
    base_master_ = master_now;
    base_slave_ = slave_cmd;
    last_master_ = master_now;
  }
  const double increment = master_now - last_master_;
  last_master_ = master_now;
  return AxisTarget{base_slave_ + (master_now - base_master_), increment / cycle_s_};
}

}  // namespace mcnc::coupling
