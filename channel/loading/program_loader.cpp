#include "channel/loading/program_loader.hpp"

#include "channel/interp/program/program_format_alarms.hpp"
#include "common/process/thread_name.hpp"
#include "common/text/file_name.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <filesystem>

namespace mcnc::channel {

ProgramLoader::ProgramLoader(interp::InterpreterConfig config)
    : config_(std::move(config)), thread_([this] { run(); }) {}

ProgramLoader::~ProgramLoader() {
  stop_.store(true, std::memory_order_release);
  ring();
  thread_.join();
}

void ProgramLoader::ring() noexcept {
  bell_.fetch_add(1, std::memory_order_release);
  bell_.notify_one();
}

bool ProgramLoader::submit(bool mdi, std::string_view text) noexcept {
  if (text.empty() || text.size() > kMaxText ||
      phase_.load(std::memory_order_acquire) != Phase::idle) {
    return false;
  }
  std::copy(text.begin(), text.end(), text_.begin());
  text_[text.size()] = '\0';
  mdi_ = mdi;
  phase_.store(Phase::requested, std::memory_order_release);
  ring();
  return true;
}

std::optional<LoadedProgram> ProgramLoader::take() noexcept {
  if (phase_.load(std::memory_order_acquire) != Phase::done) {
    return std::nullopt;
  }
  std::optional<LoadedProgram> r = std::move(result_);
  result_.reset();
  phase_.store(Phase::idle, std::memory_order_release);
  return r;
}

bool ProgramLoader::busy() const noexcept {
  return phase_.load(std::memory_order_acquire) != Phase::idle;
}

void ProgramLoader::run() {
  // A check may take seconds of CPU: never at the cycle's real-time priority, which a thread
  // inherits from the process (--clock realtime).
  sched_param normal{};
  (void)pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  process::name_this_thread("program-loader");
  while (true) {
    const std::uint32_t rung = bell_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) {
      return;
    }
    if (phase_.load(std::memory_order_acquire) != Phase::requested) {
      bell_.wait(rung, std::memory_order_acquire);
      continue;
    }
    phase_.store(Phase::checking, std::memory_order_release);
    const std::string text(text_.data());
    result_ = load(mdi_, text);
    phase_.store(Phase::done, std::memory_order_release);
  }
}

LoadedProgram ProgramLoader::load(bool mdi, const std::string& text) const {
  LoadedProgram loaded;
  loaded.mdi = mdi;
  if (mdi) {
    loaded.program =
        interp::InterpreterSource::check(config_, text, std::string(interp::kMdiName), true);
    return loaded;
  }
  // The name comes from the wire: only a plain file of the program store is read.
  const auto refuse = [&](const std::string& why) {
    loaded.program.name = text;
    loaded.program.alarm =
        interp::ProgramAlarm{interp::program::alarm::kProgramNotFound, why, text, 0, 0};
    return loaded;
  };
  if (config_.program_dir.empty()) {
    return refuse("program " + text + " not selected: the machine has no program directory");
  }
  if (!text::is_plain_file_name(text)) {
    return refuse("program " + text + " not selected: a file of the program directory, by name");
  }
  const std::filesystem::path path = config_.program_dir / text;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return refuse("program " + text + " not found in the program directory");
  }
  loaded.program = interp::InterpreterSource::check_file(config_, path.string(), text);
  if (loaded.program.alarm &&
      loaded.program.alarm->number == interp::program::alarm::kFileUnreadable) {
    return refuse("program " + text + " cannot be read");
  }
  return loaded;
}

}  // namespace mcnc::channel
