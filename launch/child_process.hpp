#pragma once
// A child process started by mcnc-launch: spawn, poll for exit, signal.
#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace mcnc::launch {

class ChildProcess {
 public:
  ChildProcess(std::string name, std::vector<std::string> argv);
  // A child still running when its handle goes (an exception, an early return) is terminated:
  // SIGTERM, then SIGKILL after a second.
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  // Starts it with `env_overrides` ("KEY=VALUE") added to this process's environment, and with
  // `fifo_priority` > 0 at SCHED_FIFO of that priority from its first instruction, so every
  // thread it makes inherits it. Returns false when that priority was not permitted: it then
  // runs as an ordinary process. It inherits the standard streams and no other descriptor.
  // Throws std::runtime_error when the executable cannot be started.
  bool start(const std::vector<std::string>& env_overrides, int fifo_priority = 0);
  // Before start(): the child's working directory, and a file its standard output and error go
  // to (created or truncated). Unset, it shares this process's.
  void set_directory(std::string directory) { directory_ = std::move(directory); }
  void set_output(std::string path) { output_ = std::move(path); }
  // True once it has exited (reaps it); exit_status() then says how. Also notes whether it is
  // stopped by a signal (SIGSTOP, SIGTSTP, ...) or has been continued since.
  bool poll_exited() noexcept;
  // The signal that stopped it, 0 while it runs (as of the last poll_exited()).
  [[nodiscard]] int stop_signal() const noexcept { return stop_signal_; }
  // How long it has been stopped (poll_exited() notices stops); zero when it runs.
  [[nodiscard]] std::chrono::steady_clock::duration stopped_for() const noexcept {
    return stop_signal_ == 0 ? std::chrono::steady_clock::duration::zero()
                             : std::chrono::steady_clock::now() - stopped_at_;
  }
  void signal(int sig) noexcept;
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  [[nodiscard]] bool running() const noexcept { return pid_ > 0 && !exited_; }
  [[nodiscard]] std::string exit_description() const;
  [[nodiscard]] int exit_code() const noexcept;  // -signal when killed by a signal

 private:
  std::string name_;
  std::vector<std::string> argv_;
  std::string directory_;
  std::string output_;
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = 0;
  int stop_signal_ = 0;
  std::chrono::steady_clock::time_point stopped_at_{};
};

}  // namespace mcnc::launch
