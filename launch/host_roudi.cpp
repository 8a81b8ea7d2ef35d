#include "launch/host_roudi.hpp"

#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "idl/dds_participant.hpp"
#include "launch/self_path.hpp"

#include <sched.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace mcnc::launch {

namespace {

constexpr auto kAnswerTimeout = std::chrono::seconds(10);
constexpr auto kStopTimeout = std::chrono::seconds(5);
// A RouDi that serves registers a process in milliseconds; mcnc-roudi-check runs above the
// host's load, as RouDi does.
constexpr auto kRegisterTimeout = std::chrono::seconds(5);

// iox-roudi on PATH (posix_spawn takes a path).
std::string find_roudi() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(dir) / "iox-roudi";
    if (!dir.empty() && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
  }
  return {};
}

// The pid of a running iox-roudi, from /proc; -1 when none runs.
pid_t running_roudi_pid() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    std::string comm;
    std::getline(std::ifstream(entry.path() / "comm"), comm);
    if (comm == "iox-roudi") {
      return static_cast<pid_t>(std::stol(name));
    }
  }
  return -1;
}

// Empty when the RouDi that answers registers a process (mcnc-roudi-check) within
// kRegisterTimeout; else what it did instead.
std::string registration_failure() {
  ChildProcess check("roudi-check", {executable_dir() + "/mcnc-roudi-check"});
  check.start({}, kRoudiPriority);
  const auto deadline = std::chrono::steady_clock::now() + kRegisterTimeout;
  while (!check.poll_exited()) {
    if (std::chrono::steady_clock::now() > deadline) {
      return "did not register a process within " + std::to_string(kRegisterTimeout.count()) +
             " s";  // the check is ended with its handle
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return check.exit_code() == 0
             ? std::string()
             : "refused a process's registration (" + check.exit_description() + ")";
}

}  // namespace

std::vector<std::string> dds_process_names(const config::MachineConfig& machine, bool with_hmi) {
  std::vector<std::string> names{"launch"};
  for (const auto& axis : machine.axes) {
    names.push_back(axis.name);
  }
  for (const auto& channel : machine.channels) {
    names.push_back(channel.name);
  }
  if (machine.plc.present) {
    names.emplace_back("PLC");
  }
  if (with_hmi) {
    names.emplace_back("HMI");
  }
  return names;
}

bool needs_roudi(const config::MachineConfig& machine, bool with_hmi) {
  for (const std::string& name : dds_process_names(machine, with_hmi)) {
    // The launcher itself is on the network (launcher.cpp).
    if (name != "launch" &&
        process::resolve_middleware(machine, name) == dds::Middleware::cyclonedds) {
      return true;
    }
  }
  return false;
}

std::string roudi_config(std::size_t processes) {
  // A cyclic sample is under 200 bytes; with iceoryx's and Cyclone DDS's headers it fits a
  // 512-byte chunk. Each process writes and reads a few cyclic topics; each writer keeps 8
  // samples of history and each reader queues 8 and holds 8 per key in its cache: 256 chunks a
  // process is four times what a channel of four axes can hold at once.
  const std::size_t chunks = std::max<std::size_t>(2048, 256 * (processes + 1));
  std::ostringstream out;
  out << "[general]\nversion = 1\n\n[[segment]]\n\n"
      << "[[segment.mempool]]\nsize = 512\ncount = " << chunks << "\n\n"
      << "[[segment.mempool]]\nsize = 4096\ncount = 256\n";
  return out.str();
}

HostRoudi::HostRoudi(std::size_t processes, bool must_be_running) {
  if (dds::roudi_answers()) {
    const pid_t pid = running_roudi_pid();
    if (const std::string why = registration_failure(); !why.empty()) {
      throw std::runtime_error(
          "the host's iceoryx RouDi (pid " + std::to_string(pid) + ") answers at " +
          dds::kRoudiSocket + " but " + why +
          ": it is stuck (iceoryx 2.0 can hang for good cleaning up after a process killed "
          "with SIGKILL); restart it");
    }
    spdlog::info("using the iceoryx RouDi that runs on this host");
    sched_param param{};
    if (pid > 0 && (::sched_getscheduler(pid) != SCHED_FIFO || ::sched_getparam(pid, &param) != 0 ||
                    param.sched_priority < kRoudiPriority)) {
      spdlog::warn(
          "the host's iceoryx RouDi (pid {}) runs below SCHED_FIFO {}: under load it may fall "
          "behind and remove processes that still run (start it with chrt -f {})",
          pid, kRoudiPriority, kRoudiPriority);
    }
    return;
  }
  if (must_be_running) {
    throw std::runtime_error(std::string("no iceoryx RouDi answers at ") + dds::kRoudiSocket +
                             ", and the machine file says one runs (roudi: running)");
  }
  const std::string binary = find_roudi();
  if (binary.empty()) {
    throw std::runtime_error(
        "no iceoryx RouDi answers and iox-roudi is not on PATH (package "
        "iceoryx)");
  }
  config_path_ = (std::filesystem::temp_directory_path() /
                  ("mcnc-roudi-" + std::to_string(::getpid()) + ".toml"))
                     .string();
  std::ofstream(config_path_) << roudi_config(processes);
  child_.emplace("roudi",
                 std::vector<std::string>{binary, "-c", config_path_, "-l", "warning", "-k", "1"});
  if (!child_->start({}, kRoudiPriority)) {
    spdlog::warn(
        "the iceoryx RouDi could not have SCHED_FIFO {}: under load it may fall behind and "
        "remove processes that still run",
        kRoudiPriority);
  }
  const auto deadline = std::chrono::steady_clock::now() + kAnswerTimeout;
  while (!dds::roudi_answers()) {
    if (child_->poll_exited() || std::chrono::steady_clock::now() > deadline) {
      const std::string why =
          child_->running() ? "did not answer within 10 s" : child_->exit_description();
      child_.reset();  // terminates it if it still runs
      std::filesystem::remove(config_path_);
      throw std::runtime_error("the iceoryx RouDi that mcnc-launch started " + why);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  spdlog::info("started the iceoryx RouDi (pid {}) for {} processes", child_->pid(), processes);
}

HostRoudi::~HostRoudi() {
  stop();
}

void HostRoudi::stop() noexcept {
  if (!child_) {
    return;
  }
  child_->signal(SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + kStopTimeout;
  while (!child_->poll_exited() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!child_->poll_exited()) {
    spdlog::warn("the iceoryx RouDi did not stop within 5 s; killing it");
    child_->signal(SIGKILL);
  }
  child_.reset();
  std::error_code ec;
  std::filesystem::remove(config_path_, ec);
}

}  // namespace mcnc::launch
