#pragma once
// What the drive simulator's tests share: a drive powered, started and enabled at 0 in CSP, and
// for the torque tests one with a contact that holds the load at -12.5 from above (a tailstock's
// centre): peak torque 10 N m, rated 3 N m, 10 units per motor revolution, 10000 counts per unit.
#include "axisnode/drivesim/simulated_drive.hpp"

#include <cstdint>

namespace mcnc::drivesim::test {

inline constexpr double kPressCycle = 0.001;
inline constexpr double kPressCounts = 10000.0;

inline SimulatedDrive enabled_drive(const DriveParams& p, double cycle_s) {
  SimulatedDrive d(p, cycle_s);
  d.power_on();
  d.on_nmt(canopen::NmtCommand::start);
  for (const std::uint16_t cw : {0x06, 0x07, 0x0F, 0x0F}) {
    d.on_rpdo(canopen::RxPdoCsp{cw, 0});
    d.on_sync();
  }
  return d;
}

inline SimulatedDrive pressing_drive() {
  DriveParams p{1, kPressCounts, 0.004, 500.0, 5000.0, 0.0};
  p.contact_side = -1;
  p.contact_at = -12.5;
  return enabled_drive(p, kPressCycle);
}

}  // namespace mcnc::drivesim::test
