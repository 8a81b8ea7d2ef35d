#pragma once
// The pull-based source of canonical commands the channel reads from.
#include "channel/interp/command.hpp"

#include <optional>
#include <variant>

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
};

}  // namespace mcnc::interp
