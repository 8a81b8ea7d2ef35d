#pragma once
// The blocks handed to the planner, in program order, until their end event: a ring of fixed
// capacity (the planner's window and a little more). It says which event of the oldest block is
// due: a block starts when the planner is in it (or past it), ends when the path passed its end
// (a stop there: and every axis in position, which the caller checks); a block that does not
// move (a spindle command, a move to where the axes are) passes at once. Allocates only when
// built.
#include "channel/interp/command.hpp"
#include "channel/motion/motion_planner.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::channel {

struct QueuedBlock {
  std::uint64_t n = 0;
  int line = 0;
  interp::AxisVector to{};
  bool exact_stop = false;
  bool still = false;                 // a move to where the axes already are
  const std::string* file = nullptr;  // owned by the interpreter
  std::string_view text;              // the line, as the interpreter holds it
  interp::ModalState modal;
  // Bit i: the block moves channel axis i; a G160 that sets a torque limit (not P-1), or a
  // G31 P98/P99 (its load ratios).
  std::uint32_t moves = 0;
  bool sets_torque_limit = false;
  bool feed = false;  // a G01 (G10 L14 P1 watches its load)
};

class BlockQueue {
 public:
  explicit BlockQueue(std::size_t capacity) : blocks_(capacity > 0 ? capacity : 1) {}

  [[nodiscard]] bool full() const noexcept { return count_ == blocks_.size(); }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }
  void clear() noexcept {
    head_ = 0;
    count_ = 0;
    started_ = false;
  }
  // Command `c`, which the planner accepted, starting where the axes are at `start`.
  void push(const interp::Command& c, const interp::AxisVector& start) noexcept;
  // The newest block ends at `at` instead (a skipped move ends where it stopped).
  void end_newest_at(const interp::AxisVector& at) noexcept;
  // The line of the first queued block that moves axis `axis` away from `from` (0: none).
  [[nodiscard]] int first_moving(std::size_t axis, double from) const noexcept;

  enum class Due : std::uint8_t {
    none,
    start,              // front() starts
    end,                // front() ends
    end_if_in_position  // front() ends once every axis stands in position at its end
  };
  // The oldest block's next event, given the planner's output this cycle.
  [[nodiscard]] Due due(const motion::MotionOutput& m, bool planner_idle) const noexcept;
  [[nodiscard]] const QueuedBlock& front() const noexcept { return blocks_[head_]; }
  void started() noexcept { started_ = true; }
  void ended() noexcept;

 private:
  std::vector<QueuedBlock> blocks_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  bool started_ = false;  // the oldest block had its start event
};

}  // namespace mcnc::channel
