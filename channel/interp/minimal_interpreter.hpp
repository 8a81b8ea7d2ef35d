#pragma once
// The walking-skeleton interpreter: G00, G01, G04 (P ms integer / X,U seconds), F (units/min),
// X/Z absolute, U/W incremental (X/U in diameter on diameter axes), N, comments, %, O, M30/M02.
// The whole program is checked when loaded, so a bad block is an alarm before anything moves.
#include "channel/interp/axis_address.hpp"
#include "channel/interp/command_source.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::interp {

struct LexedLine;  // channel/interp/block_lexer.hpp

class MinimalInterpreter final : public CommandSource {
 public:
  explicit MinimalInterpreter(std::vector<AxisAddress> axes);
  // Parses and checks the whole text. Returns the first alarm, or nullopt when it is good.
  std::optional<ProgramAlarm> load(const std::string& program_text,
                                   const std::string& program_name);
  void rewind(const AxisVector& current) override;
  std::optional<PullResult> next() override;
  [[nodiscard]] std::size_t block_count() const noexcept override;

 private:
  // One axis as a block programs it, resolved to physical units at load time.
  enum class AxisMode { unchanged, absolute, incremental };
  struct AxisWord {
    AxisMode mode = AxisMode::unchanged;
    double value = 0.0;  // physical: radius for diameter axes
  };
  // A command with its modal state resolved; only the target depends on the start position.
  struct Step {
    CanonicalCommand command;
    std::array<AxisWord, kMaxChannelAxes> axes{};
  };
  struct Modal;

  std::optional<ProgramAlarm> parse_block(const LexedLine& lexed, int line, Modal& modal,
                                          bool& ended);

  std::vector<AxisAddress> axes_;
  std::vector<Step> steps_;
  std::size_t block_count_ = 0;
  std::size_t cursor_ = 0;
  AxisVector position_{};
  std::optional<ProgramAlarm> load_alarm_;
  std::string program_name_;
};

}  // namespace mcnc::interp
