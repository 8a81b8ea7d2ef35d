#pragma once
// The walking-skeleton interpreter: G00, G01, G04 (P ms integer / X,U seconds), F (units/min),
// X/Z absolute, U/W incremental (X/U in diameter on diameter axes), N, comments, %, O, M30/M02.
// The whole program is checked when loaded, so a bad block is an alarm before anything moves.
#include "channel/interp/command_source.hpp"

#include <string>
#include <vector>

namespace mcnc::interp {

// One axis of the channel as the program addresses it.
struct AxisAddress {
  char absolute = 'X';     // X, Z, Y, C ...
  char incremental = 'U';  // U, W, V, H ...
  bool diameter = false;
};

class MinimalInterpreter final : public CommandSource {
public:
  explicit MinimalInterpreter(std::vector<AxisAddress> axes);
  // Parses and checks the whole text. Returns the first alarm, or nullopt when it is good.
  std::optional<ProgramAlarm> load(const std::string& program_text, const std::string& program_name);
  void rewind(const AxisVector& current) override;
  std::optional<PullResult> next() override;
  [[nodiscard]] std::size_t block_count() const noexcept override;
  // ...
};

} // namespace mcnc::interp
