#pragma once
// G51.4 axis synchronisation as the slave axis's node runs it (spec dafeng §3.2): from the
// cycle it is coupled, the slave copies its master's increments; absolute positions are not
// aligned. The coupling is the slave node's state: a reset does not end it, only G50.4 does.
// Pure: one step per cycle, no allocation, no exceptions.
#include <cstdint>

namespace mcnc::coupling {

struct AxisTarget {
  double pos = 0.0;
  double vel = 0.0;
};

class AxisCoupling {
 public:
  explicit AxisCoupling(double cycle_s) noexcept : cycle_s_(cycle_s) {}

  // Follows `master` (an axis id) from the next step on, from where both stand then.
  void couple(std::uint32_t master) noexcept;
  void decouple() noexcept { master_ = 0; }
  // The slave did not follow this cycle (its drive or its master out of operation: an alarm,
  // an E-stop, a reset, a homing): the coupling resumes from where both stand when it follows
  // again, with no catch-up.
  void rebase() noexcept { based_ = false; }
  [[nodiscard]] bool active() const noexcept { return master_ != 0; }
  [[nodiscard]] std::uint32_t master() const noexcept { return master_; }

  // One cycle: the master's position at this cycle (MasterHistory::estimate) and the slave's
  // own commanded position now in; the slave's position and velocity for this cycle out.
  AxisTarget step(double master_now, double slave_cmd) noexcept;

 private:
  double cycle_s_;
  std::uint32_t master_ = 0;
  bool based_ = false;
  double base_master_ = 0.0;
  double base_slave_ = 0.0;
  double last_master_ = 0.0;
};

}  // namespace mcnc::coupling
