#pragma once
// Param 5522 (spec dafeng L4827, L5172; decision 164): the program's torque percentages (G10
// L14, G160, G31 P98/P99, % of the motor's rated torque) and the drive's torque objects
// (0x6071 target, 0x6072 max, 0x6077 actual: per mille of what the drive counts as 1000).
// `scale` is that 1000 per mille in % of the rated torque: 100 for a CiA 402 drive, whose
// objects count of the rated torque (0x6076). The one place the axis node converts them.

namespace mcnc::axisnode {

[[nodiscard]] constexpr double drive_permille(double percent, double scale) noexcept {
  return percent * 1000.0 / scale;
}

[[nodiscard]] constexpr double rated_percent(double permille, double scale) noexcept {
  return permille * scale / 1000.0;
}

}  // namespace mcnc::axisnode
