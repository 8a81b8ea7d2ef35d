#pragma once
// The interpreter behind the channel's CommandSource. It hands the channel the commands its
// planner executes (rapid, linear and arc per minute, dwell in seconds, program end); any other
// canonical command is a program alarm naming what the channel cannot execute yet, raised
// before the program starts (feed per revolution, threads and dwells in revolutions need the
// spindle's feedback, tool and M codes the PLC node, the multi-channel words other than G04.1
// the coordination runtime). Its own first spindle's speed and direction it runs; G04.1 wait
// marks it hands to the channel.
#include "channel/interp/command_source.hpp"
#include "channel/interp/interpreter.hpp"

#include <memory>
#include <optional>
#include <string>

namespace mcnc::interp {

class InterpreterSource final : public CommandSource {
 public:
  explicit InterpreterSource(InterpreterConfig config);
  ~InterpreterSource() override;

  // Parses the whole file, then interprets it to its end from machine position 0 (a dry run of
  // at most kDryRunCommands commands, since a program may loop for ever), so that a bad block
  // is an alarm before the program starts, including commands the channel cannot execute yet.
  // Returns the first alarm, or nullopt.
  std::optional<ProgramAlarm> load(const std::string& program_text,
                                   const std::string& program_name);
  static constexpr int kDryRunCommands = 1000000;
  void rewind(const AxisVector& current) override;
  std::optional<PullResult> next() override;
  std::optional<ProgramAlarm> call(int number, const std::vector<std::pair<int, double>>& args,
                                   const AxisVector& current) override;
  [[nodiscard]] std::size_t block_count() const noexcept override { return block_count_; }
  void adopt_position(const AxisVector& at) override;

  // Whether the channel can execute `c`; when not, `why` says what is missing. A channel with a
  // spindle turns its first (M03/M04/M05 with S, G96/G97); orientation (M19) and other
  // spindles are not in this version.
  // G04.1 marks run (their participants must be channels of the machine).
  static bool for_channel(const Command& c, std::string& why, const InterpreterConfig& config);

 private:
  InterpreterConfig config_;
  std::string text_;
  std::string name_;
  std::unique_ptr<Interpreter> interpreter_;
  std::optional<ProgramAlarm> load_alarm_;  // the channel's own program, found at load()
  std::optional<ProgramAlarm> run_alarm_;   // the run under way stopped there
  bool calling_ = false;                    // the run is a program another channel called
  std::size_t block_count_ = 0;
  bool loaded_ = false;
};

}  // namespace mcnc::interp
