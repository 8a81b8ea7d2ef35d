#pragma once
// G51.4: the commanded positions of the axes a slave may follow, by cycle, as their feedback
// brings them, and where a master stands at a cycle. The node learns a master's position one
// cycle late (or, in realtime, whenever its feedback arrives), so the position at this cycle is
// extrapolated from its newest sample at the speed between that sample and the one before: the
// slave moves with its master, not behind it, and once the master stands the two agree exactly.
// A master can run ahead of its slave, so each keeps a long history; a cycle that history no
// longer holds is reported unavailable rather than waited for. Allocates at construction only.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mcnc::coupling {

class MasterHistory {
 public:
  // `masters`: the axis ids that may lead; `depth`: cycles kept per master.
  MasterHistory(std::span<const std::uint32_t> masters, std::size_t depth);

  [[nodiscard]] bool may_lead(std::uint32_t axis) const noexcept { return index(axis) >= 0; }
  // The master's commanded position stamped `cycle`, and whether its drive was in operation
  // (ignored for an axis that may not lead).
  void put(std::uint32_t axis, std::uint64_t cycle, double cmd, bool operating) noexcept;
  // The master's node is gone: nothing of it is waited for any more.
  void gone(std::uint32_t axis) noexcept;

  enum class Lookup : std::uint8_t { found, not_yet, unavailable };
  struct Sample {
    Lookup lookup = Lookup::not_yet;
    double cmd = 0.0;
    bool operating = false;
  };
  // The sample stamped `cycle`: found; not_yet (it may still come); unavailable (the node is
  // gone, the history has moved past it, or the axis may not lead).
  [[nodiscard]] Sample at(std::uint32_t axis, std::uint64_t cycle) const noexcept;

  // Where the master stands at `cycle`. Lockstep (`exact`): from its sample of cycle - 1, which
  // must be there (else its lookup), and the one of cycle - 2. Realtime: from its newest sample
  // and the one before it, up to 8 cycles apart (late samples, skipped cycles). Without such an
  // earlier sample in operation the master counts as standing. `operating`: the newest
  // sample's (a master out of operation is not followed: its position may jump, e.g. homing).
  [[nodiscard]] Sample estimate(std::uint32_t axis, std::uint64_t cycle, bool exact) const noexcept;

 private:
  [[nodiscard]] int index(std::uint32_t axis) const noexcept;
  struct Master {
    std::uint32_t axis = 0;
    std::vector<std::uint64_t> cycles;  // ring: cycle + 1 stored (0: empty)
    std::vector<double> cmd;
    std::vector<bool> operating;
    bool gone = false;
    bool any = false;
    std::uint64_t newest = 0;
  };
  [[nodiscard]] Sample sample(const Master& m, std::uint64_t cycle) const noexcept;
  std::vector<Master> masters_;
  std::size_t depth_;
};

}  // namespace mcnc::coupling
