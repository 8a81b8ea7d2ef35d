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
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

bool ProgramLoader::submit(bool mdi, std::string_view text) noexcept {
  if (text.empty() || text.size() > kMaxText) {
    return false;
  }
  {
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || requested_ || checking_ || result_) {
      return false;
    }
    std::copy(text.begin(), text.end(), text_.begin());
    text_[text.size()] = '\0';
    mdi_ = mdi;
    requested_ = true;
  }
  wake_.notify_one();
  return true;
}

std::optional<LoadedProgram> ProgramLoader::take() noexcept {
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !result_) {
    return std::nullopt;
  }
  std::optional<LoadedProgram> r = std::move(result_);
  result_.reset();
  return r;
}

bool ProgramLoader::busy() const noexcept {
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  return !lock.owns_lock() || requested_ || checking_ || result_.has_value();
}

void ProgramLoader::run() {
  // A check may take seconds of CPU: never at the cycle's real-time priority, which a thread
  // inherits from the process (--clock realtime).
  sched_param normal{};
  (void)pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  process::name_this_thread("program-loader");
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || requested_; });
    if (stop_) {
      return;
    }
    requested_ = false;
    checking_ = true;
    const bool mdi = mdi_;
    const std::string text(text_.data());
    lock.unlock();
    LoadedProgram loaded = load(mdi, text);
    lock.lock();
    result_ = std::move(loaded);
    checking_ = false;
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
