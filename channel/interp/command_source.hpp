#pragma once
// The pull-based source of canonical commands the channel reads from.
#include "channel/interp/command.hpp"

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>

namespace mcnc::interp {

// next(): a command, or an alarm (the program stops there), or nullopt when nothing is left.
using PullResult = std::variant<Command, ProgramAlarm>;

// A program checked before it runs (InterpreterSource::check): where its blocks are, its
// block count and the first alarm of its dry run.
struct CheckedProgram {
  std::string name;
  std::string text;  // the blocks, when they came as a text (MDI blocks, a test's program)
  std::string path;  // else the file they are read from as they run
  std::size_t block_count = 0;
  std::optional<ProgramAlarm> alarm;
};

class CommandSource {
 public:
  virtual ~CommandSource() = default;
  // Position the source at the program start. `current` is the channel's physical position
  // (channel axis order); incremental words and unprogrammed axes start from it.
  virtual void rewind(const AxisVector& current) = 0;
  virtual std::optional<PullResult> next() = 0;
  // What next() answers, in place: valid until the next call of this source's functions;
  // nullptr when nothing is left. A source that holds its answers in a buffer (the read-ahead's
  // ring) hands them over without a copy: the cycle reads a command where it lies.
  virtual const PullResult* take() {
    taken_ = next();
    return taken_ ? &*taken_ : nullptr;
  }
  // Whether next() has its answer now. A source that computes it when asked always has; one
  // that reads ahead on another thread (channel/loading) may not have it yet: then the
  // cycle pulls again in a later cycle.
  virtual bool ready() noexcept { return true; }
  [[nodiscard]] virtual std::size_t block_count() const noexcept = 0;
  // The channel's axes stand at `at` now: an exchanged axis (G141, G142) came with its machine
  // position. Called at a command that stops read-ahead, so nothing after it was evaluated.
  // A source that does not track positions ignores it.
  virtual void adopt_position(const AxisVector& at) { (void)at; }
  // The G31 (Command::skip) just pulled ended: skipped at `skip_at` (the axes' position when
  // the input switched), or not; the axes stand at `stop_at`. Called before the next pull.
  virtual void skip_result(bool skipped, const AxisVector& skip_at, const AxisVector& stop_at) {
    (void)skipped;
    (void)skip_at;
    (void)stop_at;
  }
  // The G31.8 (Command::multi_skip) just pulled ended: its axis's probe latched at `latched`
  // (machine positions, in order); the axes stand at `stop_at`. Called before the next pull.
  virtual void multi_skip_result(std::span<const double> latched, const AxisVector& stop_at) {
    (void)latched;
    (void)stop_at;
  }
  // The G10 L14 P20-P51 (Op::load_timer_check) just pulled: `axes` (bit i: channel axis i) met
  // its condition. Called before the next pull.
  virtual void load_timer_result(std::uint32_t axes) { (void)axes; }
  // The G10 L14 P7/P8-watched in-feed (Command::overload_axes) just pulled ended after
  // `overloads` overloads; `dropped_block` (0: none) ends its block there, the axes standing at
  // `stop_at` (Interpreter::overload_result). Called before the next pull.
  virtual void overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                               const AxisVector& stop_at) {
    (void)overloads;
    (void)dropped_block;
    (void)stop_at;
  }
  // Positions the source at the start of program O<number> called by another channel (G144)
  // with locals #1-#26 from `args`; an alarm when it cannot (not found, no program store).
  // Outside the cycle's allocation rule: a call loads a program. The next rewind() goes back to
  // the channel's own program.
  virtual std::optional<ProgramAlarm> call(int number, std::span<const std::pair<int, double>> args,
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
  // Makes `program` the channel's own: the next rewind() starts it; an alarm in it is the
  // answer of every pull until another program is adopted. Called while no run is under way.
  // A source without programs of its own ignores it.
  virtual void adopt(CheckedProgram program) noexcept { (void)program; }
  // The checked MDI blocks that the next start_mdi() starts.
  virtual void prepare_mdi(CheckedProgram blocks) noexcept { (void)blocks; }
  // The run under way ended without its end (a reset): nothing more of it is pulled. A source
  // that reads ahead stops reading it.
  virtual void abandon() noexcept {}
  // Whether the channel has its own program, free of alarms.
  [[nodiscard]] virtual bool has_program() const noexcept { return false; }

 private:
  std::optional<PullResult> taken_;  // take()'s answer, for a source without a buffer
};

}  // namespace mcnc::interp
