#pragma once
// The tools of a program run: the tool and offset numbers T, H and D selected, and the offset
// table (geometry and wear, which G10 and #2001.. change as the program runs). What an offset
// amounts to on an axis is decided here, for the lathe's T offsets and the mill's G43/G44
// length. A plain value.
#include "channel/interp/interp_config.hpp"

#include <array>
#include <cstddef>

namespace mcnc::interp::state {

struct ToolTable {
  using Offsets = std::array<ToolOffsetValues, kMaxToolOffsets + 1>;  // [0] unused

  int tool = 0;    // the T's tool number
  int offset = 0;  // the lathe's T offset number (0: none)
  // The mill: G43 (+1) / G44 (-1) / G49 (0) with the length of offset H on Z, and the radius
  // of offset D for G41/G42.
  int length_sign = 0;
  int length_offset = 0;
  int radius_offset = 0;
  double t_value = 0.0;  // the last T word as written (#4120)
  Offsets geometry{};
  Offsets wear{};

  ToolTable() = default;
  ToolTable(const Offsets& geometry_values, const Offsets& wear_values)
      : geometry(geometry_values), wear(wear_values) {}

  // The geometry or the wear values of offset `n` (1-kMaxToolOffsets).
  [[nodiscard]] ToolOffsetValues& values(bool of_geometry, int n) noexcept {
    return of_geometry ? geometry[slot(n)] : wear[slot(n)];
  }
  [[nodiscard]] const ToolOffsetValues& values(bool of_geometry, int n) const noexcept {
    return of_geometry ? geometry[slot(n)] : wear[slot(n)];
  }
  // The nose (or cutter) radius of offset `n`: geometry plus wear; its tip is the geometry's.
  [[nodiscard]] double radius(int n) const noexcept {
    return geometry[slot(n)].radius + wear[slot(n)].radius;
  }
  [[nodiscard]] int tip(int n) const noexcept { return geometry[slot(n)].tip; }

  // The lathe: the T offset on the axis named `axis` (X, Z or Y), geometry plus wear, X halved
  // when it is programmed as a diameter; 0 without an offset.
  [[nodiscard]] double lathe_offset(char axis, bool diameter) const noexcept {
    if (offset <= 0) {
      return 0.0;
    }
    const ToolOffsetValues& g = geometry[slot(offset)];
    const ToolOffsetValues& w = wear[slot(offset)];
    switch (axis) {
      case 'X':
        return (g.x + w.x) / (diameter ? 2.0 : 1.0);
      case 'Z':
        return g.z + w.z;
      case 'Y':
        return g.y + w.y;
      default:
        return 0.0;
    }
  }
  // The mill: G43/G44 H's length on the axis named `axis`, which is Z whatever the plane
  // (FANUC's tool length compensation A); 0 under G49 or without H.
  [[nodiscard]] double mill_length(char axis) const noexcept {
    if (length_sign == 0 || length_offset <= 0 || axis != 'Z') {
      return 0.0;
    }
    const auto h = slot(length_offset);
    return length_sign * (geometry[h].z + wear[h].z);
  }

 private:
  static constexpr std::size_t slot(int n) noexcept { return static_cast<std::size_t>(n); }
};

}  // namespace mcnc::interp::state
