#pragma once
// The spindles of a program run's channel: the speed S gave each (1-9), its turning, whether
// it is in position control (C1 mode), the reference spindle SP names and the constant surface
// speed of G96, which acts on the reference spindle only. A plain value.
#include "channel/interp/command.hpp"

#include <array>
#include <cstddef>

namespace mcnc::interp::state {

struct SpindleState {
  static constexpr std::size_t kSlots = 10;  // spindles 1-9; slot 0 unused

  std::array<double, kSlots> rpm{};
  std::array<SpindleDirection, kSlots> direction = all_stopped();
  std::array<bool, kSlots> position_control{};  // M18 (GSK M14) until M17 (M15)
  bool css = false;                             // G96 until G97
  double surface = 0.0;                         // G96 S: m/min
  double clamp_rpm = 0.0;                       // G50 S (G92 S in system B): the G96 maximum
  int reference = 1;                            // SP: the spindle G96, threading and the cycles use

  [[nodiscard]] double reference_rpm() const noexcept { return rpm[slot(reference)]; }
  [[nodiscard]] SpindleDirection reference_direction() const noexcept {
    return direction[slot(reference)];
  }
  // G96 governs `spindle`'s speed: it is the reference spindle and the mode is on.
  [[nodiscard]] bool surface_speed_on(int spindle) const noexcept {
    return css && spindle == reference;
  }

 private:
  static constexpr std::size_t slot(int spindle) noexcept {
    return static_cast<std::size_t>(spindle);
  }
  static constexpr std::array<SpindleDirection, kSlots> all_stopped() noexcept {
    std::array<SpindleDirection, kSlots> a{};
    a.fill(SpindleDirection::stop);
    return a;
  }
};

}  // namespace mcnc::interp::state
