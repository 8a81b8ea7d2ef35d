#pragma once
// The ISO lathe interpreter of one channel (spec dafeng, gsk; decisions in docs/dialect.md): a
// pull-based generator of canonical commands. next() runs the program just far enough to yield
// one command, so macro statements are evaluated only as far as commands have been pulled and a
// read-ahead barrier (Command::barrier) is never looked past: a channel that holds its pulls at
// a G04.1 has not evaluated the IF[#500...] after it.
//
// Pure: no I/O except reading programs (their files, the program directory) and the
// retained-variable file; no DDS, no threads, no clock (timers come through
// InterpreterEnvironment).
#include "channel/interp/command.hpp"
#include "channel/interp/interp_config.hpp"
#include "channel/interp/macro/variable_store.hpp"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace mcnc::interp {

// What the interpreter asks of the world: a clock for #3001/#3002, the date for #3011/#3012.
class InterpreterEnvironment {
 public:
  virtual ~InterpreterEnvironment() = default;
  virtual double milliseconds() const { return 0.0; }  // monotonic
  virtual double date() const { return 0.0; }          // yyyymmdd
  virtual double time_of_day() const { return 0.0; }   // hhmmss
};

using InterpResult = std::variant<Command, ProgramAlarm>;

class ProgramRun;  // the run state and its execution (program_run.hpp)

class Interpreter {
 public:
  explicit Interpreter(const InterpreterConfig& config,
                       const InterpreterEnvironment* environment = nullptr);
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  // Loads a program file's text: its first program is the main program; the others are found
  // by number (M98, G65, ...) before the program directory is searched. Every line of a program
  // is parsed when the program is loaded, so a syntax error is an alarm before anything moves.
  std::optional<ProgramAlarm> start(std::string text, const std::string& file_name);
  // The same from the file at `path`, read as the program runs, never whole: memory does not
  // grow with the program (`file_name`: the file's name in alarms and commands).
  std::optional<ProgramAlarm> start_file(const std::string& path, const std::string& file_name);
  // Starts program O<number> of the program directory.
  std::optional<ProgramAlarm> start_number(int number);
  // Starts O<number> of the program directory for a G144 call of another channel: locals
  // #1-#26 from `args` (#number, value), and M99 in it ends the program (M99 code 99).
  std::optional<ProgramAlarm> start_called(int number,
                                           std::span<const std::pair<int, double>> args);
  // Starts blocks the operator typed (MDI, file name kMdiName): the end of the text ends them
  // with end code 0, as do M30, M02 and an M99 at their top level.
  std::optional<ProgramAlarm> start_mdi(std::string text);

  // The next command; or an alarm (the program stops there, later pulls return nullopt); or
  // nullopt once the program has ended.
  std::optional<InterpResult> next();
  // What the program asked for that the control ignores, with where (number 0), since the last
  // call: a word the spec's decision list says to ignore with a warning (Dafeng G92 P). At
  // most the first 100 of a run are kept.
  std::vector<ProgramAlarm> take_warnings();

  macro::VariableStore& variables();
  // Physical machine position of each channel axis after the last pulled command.
  AxisVector machine_position() const;
  // The axes stand at `at` now (an exchanged axis came with its machine position): the next
  // command starts from there. Only between commands that stop read-ahead.
  void set_machine_position(const AxisVector& at);
  // The G31 just pulled ended: skipped at `skip_at` (machine position when the signal came),
  // or not (it ran to its end); the axes stand at `stop_at`. Without this call a G31 counts as
  // skipped at its end point (a dry run, `mcnc interp`). Only while the G31 is the last
  // command pulled.
  void skip_result(bool skipped, const AxisVector& skip_at, const AxisVector& stop_at);
  // The G31.8 just pulled ended: its axis's probe latched at `latched` (machine positions, in
  // order), which go to #P.. and their count to #R; the axes stand at `stop_at`. Without this
  // call the signals count as coming evenly along the move (decision 93).
  void multi_skip_result(std::span<const double> latched, const AxisVector& stop_at);
  // The G10 L14 P20-P51 just pulled was decided by the channel's load timer: `axes` (bit i:
  // channel axis i) met its condition and go to its R variable. Without this call #R is not
  // written (a dry run).
  void load_timer_result(std::uint32_t axes);
  // The G10 L14 P7/P8-watched in-feed just pulled ended: `overloads` overloads happened (added
  // to its R variable); `dropped_block` (0: none) is its Command::overload_block when the block
  // ends there (the overload's "go on"): its commands not pulled yet are dropped and the axes
  // stand at `stop_at`. Without this call no overload happens (a dry run).
  void overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                       const AxisVector& stop_at);
  // The workpiece position as #5001.. reads it (X as a diameter on a diameter axis).
  double program_position(int axis) const;
  // The number of non-empty lines of the main program (0 before start).
  std::size_t main_block_count() const;
  // Saves #500-#999 to the configured retained file (also done when the program ends).
  std::optional<ProgramAlarm> save_retained();

 private:
  std::unique_ptr<ProgramRun> run_;
};

}  // namespace mcnc::interp
