#pragma once
// The last few samples of one cyclic input, found by their cycle stamp. Fixed size, no
// allocation: a lockstep consumer looks up exactly the sample stamped N-1 even when the
// producer has already sent N and N+1.
#include <array>
#include <cstddef>
#include <cstdint>

namespace mcnc::cycle {

template <class T, std::size_t Depth = 8>
class CycleBuffer {
 public:
  void put(std::uint64_t cycle, const T& value) noexcept {
    Slot& slot = slots_[cycle % Depth];
    slot.cycle = cycle;
    slot.value = value;
    slot.used = true;
    if (!has_latest_ || cycle >= latest_cycle_) {
      latest_cycle_ = cycle;
      has_latest_ = true;
    }
  }
  // The sample stamped `cycle`, or nullptr when it has not arrived or was overwritten.
  [[nodiscard]] const T* at(std::uint64_t cycle) const noexcept {
    const Slot& slot = slots_[cycle % Depth];
    return slot.used && slot.cycle == cycle ? &slot.value : nullptr;
  }
  [[nodiscard]] const T* latest() const noexcept {
    return has_latest_ ? at(latest_cycle_) : nullptr;
  }
  [[nodiscard]] bool empty() const noexcept { return !has_latest_; }
  [[nodiscard]] std::uint64_t latest_cycle() const noexcept { return latest_cycle_; }
  void clear() noexcept { *this = CycleBuffer{}; }

 private:
  struct Slot {
    std::uint64_t cycle = 0;
    T value{};
    bool used = false;
  };
  std::array<Slot, Depth> slots_{};
  std::uint64_t latest_cycle_ = 0;
  bool has_latest_ = false;
};

}  // namespace mcnc::cycle
