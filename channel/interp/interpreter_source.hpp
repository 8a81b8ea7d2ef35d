#pragma once
// The interpreter behind the channel's CommandSource: the channel's own program, a program
// another channel calls in it (G144) and the operator's MDI blocks, each checked before it
// runs. The check is a dry run of the whole program, so that a bad block, or a command this
// channel cannot execute (for_channel: a G04.1 or G144 naming a channel the machine lacks, a
// G51.4 of an axis that may not follow, a spindle function the channel has no spindle for), is
// an alarm before anything moves (docs/alarms.md).
#include "channel/interp/command_source.hpp"
#include "channel/interp/interpreter.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mcnc::interp {

class InterpreterSource final : public CommandSource {
 public:
  // `texts_kept`: how many commands pulled later a command's block_text is still valid (each
  // is copied here: the interpreter keeps a program's lines only for a window of it).
  explicit InterpreterSource(InterpreterConfig config, std::size_t texts_kept = kTextsKept);
  static constexpr std::size_t kTextsKept = 1024;
  ~InterpreterSource() override;

  // Parses the whole text, then interprets it to its end from machine position 0 (a dry run of
  // at most kDryRunCommands commands, since a program may loop for ever), so that a bad block
  // is an alarm before the program starts, including commands the channel cannot execute yet.
  // `mdi`: blocks the operator typed, which their text's end ends (file name kMdiName).
  // Touches no source: it may run on another thread than the channel's cycle, and take long.
  static CheckedProgram check(const InterpreterConfig& config, std::string text, std::string name,
                              bool mdi);
  // The same for the program file at `path`, read line by line (named `name` in alarms): the
  // check and each run read it again, and never hold it whole.
  static CheckedProgram check_file(const InterpreterConfig& config, std::string path,
                                   std::string name);
  static constexpr int kDryRunCommands = 1000000;
  // check(), then adopt(). Returns the program's first alarm, or nullopt.
  std::optional<ProgramAlarm> load(const std::string& program_text,
                                   const std::string& program_name);
  // check_file(), then adopt().
  std::optional<ProgramAlarm> load_file(const std::string& path, const std::string& program_name);
  // block_count() is the adopted program's from then on.
  void adopt(CheckedProgram program) noexcept override;
  void prepare_mdi(CheckedProgram blocks) noexcept override;
  [[nodiscard]] bool has_program() const noexcept override { return loaded_ && !load_alarm_; }
  void rewind(const AxisVector& current) override;
  std::optional<PullResult> next() override;
  std::optional<ProgramAlarm> call(int number, std::span<const std::pair<int, double>> args,
                                   const AxisVector& current) override;
  std::optional<ProgramAlarm> start_mdi(const AxisVector& current) override;
  // The blocks of the run under way (the channel's program, a called program, MDI blocks).
  [[nodiscard]] std::size_t block_count() const noexcept override { return run_blocks_; }
  void adopt_position(const AxisVector& at) override;
  void skip_result(bool skipped, const AxisVector& skip_at, const AxisVector& stop_at) override;
  void multi_skip_result(std::span<const double> latched, const AxisVector& stop_at) override;
  void overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                       const AxisVector& stop_at) override;
  void load_timer_result(std::uint32_t axes) override;

  // Whether the channel can execute `c`; when not, `why` says what is missing. A channel with a
  // spindle turns its first (M03/M04/M05 with S, G96/G97); orientation (M19) and other
  // spindles are not in this version.
  // G04.1 marks run (their participants must be channels of the machine).
  static bool for_channel(const Command& c, std::string& why, const InterpreterConfig& config);

 private:
  // A fresh interpreter at `current` for a run.
  void start_interpreter(const AxisVector& current);
  // The dry run of check() over a started probe.
  static void dry_run(const InterpreterConfig& config, Interpreter& probe, CheckedProgram& checked);
  static InterpreterConfig dry_config(const InterpreterConfig& config);
  // `c`'s block_text, as a copy that outlives the interpreter's window.
  void keep_text(Command& c);

  InterpreterConfig config_;
  std::string text_;
  std::string path_;
  std::string name_;
  std::unique_ptr<Interpreter> interpreter_;
  std::optional<ProgramAlarm> load_alarm_;  // the channel's own program, found at load()
  std::optional<ProgramAlarm> run_alarm_;   // the run under way stopped there
  bool calling_ = false;  // the run is not the channel's program: a called one, or MDI blocks
  std::size_t block_count_ = 0;  // of the channel's program
  std::size_t run_blocks_ = 0;   // of the run under way
  bool loaded_ = false;
  std::string mdi_text_;  // prepared by prepare_mdi()
  std::size_t mdi_blocks_ = 0;
  std::vector<std::string> texts_;  // a ring: the block texts of the last commands pulled
  std::size_t next_text_ = 0;
};

}  // namespace mcnc::interp
