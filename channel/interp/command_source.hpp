#pragma once
// The pull-based source of canonical commands the channel reads from.
#include "channel/interp/command.hpp"

#include <optional>
#include <utility>
#include <variant>
#include <vector>

namespace mcnc::interp {

// next(): a command, or an alarm (the program stops there), or nullopt when nothing is left.
using PullResult = std::variant<Command, ProgramAlarm>;

class CommandSource {
 public:
  virtual ~CommandSource() = default;
  // Position the source at the program start. `current` is the channel's physical position
  // (channel axis order); incremental words and unprogrammed axes start from it.
  virtual void rewind(const AxisVector& current) = 0;
  virtual std::optional<PullResult> next() = 0;
  [[nodiscard]] virtual std::size_t block_count() const noexcept = 0;
  // The channel's axes stand at `at` now: an exchanged axis (G141, G142) came with its machine
  // position. Called at a command that stops read-ahead, so nothing after it was evaluated.
  // A source that does not track positions ignores it.
  virtual void adopt_position(const AxisVector& at) { (void)at; }
  // Positions the source at the start of program O<number> called by another channel (G144)
  // with locals #1-#26 from `args`; an alarm when it cannot (not found, no program store).
  // Outside the cycle's allocation rule: a call loads a program. The next rewind() goes back to
  // the channel's own program.
  virtual std::optional<ProgramAlarm> call(int number,
                                           const std::vector<std::pair<int, double>>& args,
                                           const AxisVector& current) {
    (void)number;
    (void)args;
    (void)current;
    return ProgramAlarm{1100, "this channel cannot run programs called by another channel", "", 0,
                        0};
  }
  // Positions the source at the start of the MDI blocks the operator typed (prepared before),
  // at `current`; an alarm when there are none. Outside the cycle's allocation rule, as call().
  // The next rewind() goes back to the channel's own program.
  virtual std::optional<ProgramAlarm> start_mdi(const AxisVector& current) {
    (void)current;
    return ProgramAlarm{1100, "this channel cannot run MDI blocks", "", 0, 0};
  }
};

}  // namespace mcnc::interp
