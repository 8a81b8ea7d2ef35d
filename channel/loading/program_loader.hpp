#pragma once
// The channel's program checks off the cycle: a program the operator selects, or MDI blocks,
// checked on a thread of its own, since a dry run (InterpreterSource::check) may take seconds
// where a cycle has milliseconds. The cycle hands a request over and later takes the result;
// neither blocks, allocates or takes a lock (the hand-over is one atomic phase, the thread's
// wake-up a futex). One request at a time.
#include "channel/interp/interpreter_source.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

namespace mcnc::channel {

// A checked request: a program file of the program store (read again as it runs), or MDI
// blocks. A file that cannot be read is an alarm of its own.
struct LoadedProgram {
  bool mdi = false;
  interp::CheckedProgram program;
};

class ProgramLoader {
 public:
  static constexpr std::size_t kMaxText = 128;  // a file name or MDI blocks, as the wire holds

  // `config`: the channel's interpreter configuration; a selected file is read from its
  // program_dir.
  explicit ProgramLoader(interp::InterpreterConfig config);
  ~ProgramLoader();
  ProgramLoader(const ProgramLoader&) = delete;
  ProgramLoader& operator=(const ProgramLoader&) = delete;

  // Hands over a program file name (`mdi` false) or MDI blocks. False when the text is empty or
  // longer than kMaxText, or when a request is still checked or its result not taken.
  bool submit(bool mdi, std::string_view text) noexcept;
  // The result of the request, once checked.
  std::optional<LoadedProgram> take() noexcept;
  // A request is checked, or its result waits to be taken.
  [[nodiscard]] bool busy() const noexcept;

 private:
  void run();
  LoadedProgram load(bool mdi, const std::string& text) const;

  // Who holds the request: the cycle (idle: no request; done: its result waits to be taken)
  // or the thread (requested, checking). text_, mdi_ and result_ belong to whoever holds it.
  enum class Phase : std::uint8_t { idle, requested, checking, done };
  void ring() noexcept;

  const interp::InterpreterConfig config_;
  std::atomic<Phase> phase_{Phase::idle};
  std::atomic<std::uint32_t> bell_{0};  // rung on a request and on stop
  std::atomic<bool> stop_{false};
  bool mdi_ = false;
  std::array<char, kMaxText + 1> text_{};
  std::optional<LoadedProgram> result_;
  std::thread thread_;  // last: starts once the rest is built
};

}  // namespace mcnc::channel
