#pragma once
// The coordinate systems of a program run, per channel axis and physical: the work offsets (EXT
// and G54-G59, G54.1 P1-P99, which G10 L2/L20 and #5201.. change), the G52 local system of each
// work system, the G50 (system B: G92) shift, and the work system selected. How they add up to
// the offset between the machine and the program, and how G50 and G52 set them from a
// position, is decided here. A plain value.
#include "channel/interp/axis_vector.hpp"
#include "channel/interp/interp_config.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace mcnc::interp::state {

class CoordinateSystems {
 public:
  using AxisValues = std::array<double, kMaxChannelAxes>;

  CoordinateSystems() : CoordinateSystems(std::vector<AxisValues>{}) {}
  // `work_offsets`: [0] EXT, [1..] the systems as configured; the rest are zero.
  explicit CoordinateSystems(const std::vector<AxisValues>& work_offsets)
      : work_(work_offsets), local_(work_offsets.size()) {
    work_.resize(kSystems);
    local_.resize(kSystems);
  }

  // 1-6 = G54-G59, 7.. = G54.1 P1..
  [[nodiscard]] int selected() const noexcept { return selected_; }
  void select(int system) noexcept { selected_ = system; }

  // The work offset data of `system` (0: EXT) on channel axis `axis`.
  [[nodiscard]] double& offset(int system, int axis) noexcept {
    return work_[at(system)][at(axis)];
  }
  [[nodiscard]] double offset(int system, int axis) const noexcept {
    return work_[at(system)][at(axis)];
  }

  // What lies between the machine and the program on `axis`: EXT + work + G50 shift + G52.
  [[nodiscard]] double sum(int axis) const noexcept {
    const auto i = at(axis);
    const auto ws = at(selected_);
    return work_[0][i] + work_[ws][i] + shift_[i] + local_[ws][i];
  }

  // G50 X: the position `machine` (before the tool offset) reads `value`; G52 of the axis ends
  // in every system.
  void set_position(int axis, double machine, double value) noexcept {
    const auto i = at(axis);
    const auto ws = at(selected_);
    clear_local(i);
    shift_[i] = machine - work_[0][i] - work_[ws][i] - value;
  }
  // G50 U: the position reads `amount` more.
  void shift_by(int axis, double amount) noexcept { shift_[at(axis)] -= amount; }
  // G52: the local system's origin of the selected work system at `value` ...
  void set_local(int axis, double value) noexcept { local_[at(selected_)][at(axis)] = value; }
  // ... or, with U/W, at `value` from `machine` (its tool offset `tool`) in the work system.
  void set_local_from(int axis, double machine, double tool, double value) noexcept {
    const auto i = at(axis);
    const auto ws = at(selected_);
    local_[ws][i] = machine - work_[0][i] - work_[ws][i] - shift_[i] - tool + value;
  }
  // Homing and G50.3 (G92.1): the G50 shift and the G52 local systems of the axis end.
  void clear_shift_and_local(int axis) noexcept {
    const auto i = at(axis);
    shift_[i] = 0.0;
    clear_local(i);
  }

 private:
  static constexpr std::size_t kSystems = kWorkSystems + 1;  // [0] EXT
  static constexpr std::size_t at(int n) noexcept { return static_cast<std::size_t>(n); }
  void clear_local(std::size_t i) noexcept {
    for (AxisValues& l : local_) {
      l[i] = 0.0;
    }
  }

  std::vector<AxisValues> work_;   // [0] EXT, [1..] systems
  std::vector<AxisValues> local_;  // G52 per work system
  AxisValues shift_{};             // G50 shift
  int selected_ = 1;
};

}  // namespace mcnc::interp::state
