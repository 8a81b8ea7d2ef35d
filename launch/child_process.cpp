#include "launch/child_process.hpp"

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace mcnc::launch {

ChildProcess::ChildProcess(std::string name, std::vector<std::string> argv)
    : name_(std::move(name)), argv_(std::move(argv)) {}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : name_(std::move(other.name_)),
      argv_(std::move(other.argv_)),
      pid_(other.pid_),
      exited_(other.exited_),
      status_(other.status_) {
  other.pid_ = -1;
}

ChildProcess::~ChildProcess() {
  if (!running() || poll_exited()) {
    return;
  }
  signal(SIGTERM);
  for (int i = 0; i < 100 && !poll_exited(); ++i) {
    usleep(10'000);
  }
  if (!poll_exited()) {
    signal(SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

bool ChildProcess::start(const std::vector<std::string>& env_overrides, int fifo_priority) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    bool overridden = false;
    for (const auto& o : env_overrides) {
      if (entry.compare(0, o.find('=') + 1, o, 0, o.find('=') + 1) == 0) {
        overridden = true;
      }
    }
    if (!overridden) {
      env_strings.push_back(entry);
    }
  }
  env_strings.insert(env_strings.end(), env_overrides.begin(), env_overrides.end());
  std::vector<char*> env;
  for (auto& s : env_strings) {
    env.push_back(s.data());
  }
  env.push_back(nullptr);
  std::vector<char*> args;
  for (auto& a : argv_) {
    args.push_back(a.data());
  }
  args.push_back(nullptr);
  const bool fifo = fifo_priority > 0;
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (fifo) {
    sched_param param{};
    param.sched_priority = fifo_priority;
    posix_spawnattr_setschedpolicy(&attr, SCHED_FIFO);
    posix_spawnattr_setschedparam(&attr, &param);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSCHEDULER);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // Only the standard streams: DDS implementations open their sockets without close-on-exec,
  // and a child that held the launcher's would keep its ports bound after the launcher left.
  posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);
  if (!directory_.empty()) {
    posix_spawn_file_actions_addchdir_np(&actions, directory_.c_str());
  }
  if (!output_.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  int rc = posix_spawn(&pid_, args[0], &actions, &attr, args.data(), env.data());
  posix_spawnattr_destroy(&attr);
  const bool refused = fifo && rc == EPERM;  // the priority was not permitted
  if (refused) {
    rc = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), env.data());
  }
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error("cannot start " + argv_[0] + ": " + std::strerror(rc));
  }
  return !refused;
}

bool ChildProcess::poll_exited() noexcept {
  if (pid_ <= 0 || exited_) {
    return exited_;
  }
  int status = 0;
  // A stopped child is reported once per stop, a continued one once per continue: loop until
  // nothing is left to report, the latest report counting.
  for (pid_t r = waitpid(pid_, &status, WNOHANG | WUNTRACED | WCONTINUED); r == pid_;
       r = waitpid(pid_, &status, WNOHANG | WUNTRACED | WCONTINUED)) {
    if (WIFSTOPPED(status)) {
      if (stop_signal_ == 0) {
        stopped_at_ = std::chrono::steady_clock::now();
      }
      stop_signal_ = WSTOPSIG(status);
    } else if (WIFCONTINUED(status)) {
      stop_signal_ = 0;
    } else {
      exited_ = true;
      status_ = status;
      stop_signal_ = 0;
      break;
    }
  }
  return exited_;
}

void ChildProcess::signal(int sig) noexcept {
  if (running()) {
    kill(pid_, sig);
  }
}

int ChildProcess::exit_code() const noexcept {
  if (WIFEXITED(status_)) {
    return WEXITSTATUS(status_);
  }
  if (WIFSIGNALED(status_)) {
    return -WTERMSIG(status_);
  }
  return -1;
}

std::string ChildProcess::exit_description() const {
  if (!exited_) {
    return "running";
  }
  if (WIFSIGNALED(status_)) {
    return std::string("killed by signal ") + std::to_string(WTERMSIG(status_)) + " (" +
           strsignal(WTERMSIG(status_)) + ")";
  }
  return "exited with code " + std::to_string(WEXITSTATUS(status_));
}

}  // namespace mcnc::launch
