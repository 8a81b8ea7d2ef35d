#include "common/process/process_node.hpp"

#include "common/config/machine_config.hpp"
#include "common/process/startup.hpp"

#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

namespace mcnc::process {

int resolve_domain(const config::MachineConfig& machine) {
  const char* env = std::getenv("MCNC_DOMAIN");
  if (env == nullptr || *env == '\0') {
    return machine.domain;
  }
  char* end = nullptr;
  const long value = std::strtol(env, &end, 10);
  if (*end != '\0' || value < 0 || value > 232) {
    throw std::runtime_error(std::string("MCNC_DOMAIN must be a DDS domain id 0..232, not '") +
                             env + "'");
  }
  return static_cast<int>(value);
}

ProcessNode::ProcessNode(int domain, std::string name)
    : name_(std::move(name)),
      participant_(domain, name_),
      state_writer_(participant_),
      alarm_writer_(participant_),
      run_control_reader_(participant_, [this](const RunControl& rc, const dds::WriterId&) {
        wakeup_.update([&] {
          rc_command_.store(rc.command());
          rc_clock_.store(rc.clock());
          rc_start_ns_.store(rc.start_ns());
          rc_pace_.store(rc.pace());
          rc_generation_.store(rc.generation());
        });
      }) {}

void ProcessNode::announce(ProcessPhase phase, std::uint64_t cycle, const std::string& detail) {
  ProcessState state;
  state.name(name_);
  state.pid(static_cast<int32_t>(getpid()));
  state.phase(phase);
  state.cycle(cycle);
  state.detail(detail);
  state_writer_.write(state);
}

RunControlView ProcessNode::run_control() const noexcept {
  RunControlView view;
  view.generation = rc_generation_.load();
  view.command = static_cast<RunCommand>(rc_command_.load());
  view.clock = static_cast<ClockKind>(rc_clock_.load());
  view.start_ns = rc_start_ns_.load();
  view.pace = rc_pace_.load();
  return view;
}

bool ProcessNode::stop_arrives_within(std::chrono::milliseconds grace) {
  return wakeup_.wait_for(
      [this] {
        return static_cast<RunCommand>(rc_command_.load()) == RUN_STOP || g_stop_signal != 0;
      },
      grace);
}

void ProcessNode::raise_alarm(std::uint32_t number, const std::string& text, std::uint64_t cycle,
                              int channel, int axis, int line) {
  Alarm alarm;
  alarm.src(name_);
  alarm.number(number);
  alarm.text(text);
  alarm.channel(channel);
  alarm.axis(axis);
  alarm.line(line);
  alarm.cycle(cycle);
  alarm.seq(++alarm_seq_);
  alarm_writer_.write(alarm);
}

}  // namespace mcnc::process
