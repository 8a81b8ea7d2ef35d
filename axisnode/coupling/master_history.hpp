#pragma once
// G51.4: the commanded positions of the axes a slave may follow, by cycle, as their feedback
// brings them. In lockstep a master can run ahead of its slave (it waits for nobody's slave),
// so each keeps a long history; a cycle that history no longer holds is reported as lost rather
// than waited for. Allocates at construction only; the rest is noexcept.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace mcnc::coupling {

class MasterHistory {
 public:
  // `masters`: the axis ids that may lead; `depth`: cycles kept per master.
  MasterHistory(std::span<const std::uint32_t> masters, std::size_t depth);

  [[nodiscard]] bool may_lead(std::uint32_t axis) const noexcept { return index(axis) >= 0; }
  // The master's commanded position stamped `cycle` (ignored for an axis that may not lead).
  void put(std::uint32_t axis, std::uint64_t cycle, double cmd) noexcept;
  // The master's node is gone: nothing of it is waited for any more.
  void gone(std::uint32_t axis) noexcept;

  enum class Lookup : std::uint8_t { found, not_yet, unavailable };
  struct Sample {
    Lookup lookup = Lookup::not_yet;
    double cmd = 0.0;
  };
  // The position stamped `cycle`: found; not_yet (it may still come); unavailable (the node is
  // gone, the history has moved past it, or the axis may not lead).
  [[nodiscard]] Sample at(std::uint32_t axis, std::uint64_t cycle) const noexcept;
  // The newest position received (realtime: the node takes the latest there is).
  [[nodiscard]] std::optional<double> latest(std::uint32_t axis) const noexcept;

 private:
  [[nodiscard]] int index(std::uint32_t axis) const noexcept;
  struct Master {
    std::uint32_t axis = 0;
    std::vector<std::uint64_t> cycles;  // ring: cycle + 1 stored (0: empty)
    std::vector<double> cmd;
    bool gone = false;
    bool any = false;
    std::uint64_t newest = 0;
  };
  std::vector<Master> masters_;
  std::size_t depth_;
};

}  // namespace mcnc::coupling
