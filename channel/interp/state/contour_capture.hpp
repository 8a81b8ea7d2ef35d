#pragma once
// The P..Q contour of G70-G73 as a program run reads it: whether its blocks are running (and
// how), what its first motion block gave, and the program line of each captured element so an
// alarm of the cycle can name the contour block it comes from. A plain value.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mcnc::interp::state {

enum class ContourMode : std::uint8_t {
  none,
  finish,   // G70: the blocks run as written, F S T effective
  capture,  // G71-G73: the blocks are read for their geometry; F S T M are ignored
};

struct ContourCapture {
  ContourMode mode = ContourMode::none;
  std::vector<int> lines;  // the program line of each captured contour element
  int first = 0;           // the last captured contour's line range (for the resume point)
  int last = 0;
  int motions = 0;                   // motion blocks of the contour so far
  std::array<bool, 2> first_axes{};  // plane axes the first one gives

  // The contour's blocks are running (G70, or being captured by G71-G73).
  [[nodiscard]] bool active() const noexcept { return mode != ContourMode::none; }
  [[nodiscard]] bool capturing() const noexcept { return mode == ContourMode::capture; }

  // The contour's blocks start running in `m`: no motion block seen yet.
  void begin(ContourMode m) noexcept {
    mode = m;
    motions = 0;
    first_axes = {false, false};
  }
  // A motion block of the contour with axis words; the first one's plane axes are kept.
  void note_motion(bool first_axis_given, bool second_axis_given) noexcept {
    if (motions++ == 0) {
      first_axes = {first_axis_given, second_axis_given};
    }
  }
  // Type II of G71/G72: the contour's first block gives both plane axes (gsk A.6.30).
  [[nodiscard]] bool type2() const noexcept { return first_axes[0] && first_axes[1]; }

  // The program line of captured element `source` (a path error's source), if there is one.
  [[nodiscard]] std::optional<int> line_of(int source) const noexcept {
    if (source < 0 || static_cast<std::size_t>(source) >= lines.size()) {
      return std::nullopt;
    }
    return lines[static_cast<std::size_t>(source)];
  }
};

}  // namespace mcnc::interp::state
