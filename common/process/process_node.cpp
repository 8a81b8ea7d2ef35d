#include "common/process/process_node.hpp"

#include "common/config/machine_config.hpp"
#include "common/process/exit_deadline.hpp"
#include "common/process/startup.hpp"
#include "common/process/thread_name.hpp"
#include "common/text/program_place.hpp"

#include <unistd.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
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

dds::Middleware resolve_middleware(const config::MachineConfig& machine,
                                   const std::string& process) {
  const std::string named = machine.middleware_of(process);
  if (named.empty()) {
    return dds::middleware_from_env();
  }
  return dds::parse_middleware(named).value_or(dds::kDefaultMiddleware);
}

std::string resolve_host() {
  const char* env = std::getenv("MCNC_HOST");
  return env == nullptr ? std::string() : std::string(env);
}

ProcessNode::ProcessNode(int domain, std::string name, dds::CyclicClock clock,
                         std::optional<dds::Middleware> middleware, dds::LocalTransport local,
                         std::optional<security::IdentityFiles> security)
    : name_(std::move(name)),
      participant_(domain, name_, clock, middleware, local, std::move(security)),
      state_writer_(participant_),
      alarm_writer_(participant_),
      run_control_reader_(participant_,
                          [this](const RunControl& rc, const dds::WriterId&) {
                            wakeup_.update([&] {
                              rc_command_.store(rc.command());
                              rc_clock_.store(rc.clock());
                              rc_start_ns_.store(rc.start_ns());
                              rc_pace_.store(rc.pace());
                              rc_generation_.store(rc.generation());
                            });
                          }),
      operator_reader_(participant_, [this](const OperatorCommand& c,
                                            const dds::WriterId&) { on_operator_command(c); }),
      host_(resolve_host()) {
  if (host_.empty()) {
    clock_known_.store(true);
  } else {
    host_clock_reader_.emplace(participant_, [this](const HostClock& hc, const dds::WriterId&) {
      if (hc.host() != host_) {
        return;
      }
      clock_offset_ns_.store(hc.offset_ns());
      if (!clock_known_.load()) {
        wakeup_.update([&] { clock_known_.store(true); });
      }
    });
  }
  alarm_thread_ = std::thread([this] {
    name_this_thread("alarms");
    publish_alarms();
  });
}

void ProcessNode::announce(ProcessPhase phase, std::uint64_t cycle, const std::string& detail) {
  ProcessState state;
  state.name(name_);
  state.pid(static_cast<int32_t>(getpid()));
  state.phase(phase);
  state.cycle(cycle);
  state.detail(detail);
  state_writer_.write(state);
}

void ProcessNode::announce_stopped() {
  announce(PHASE_STOPPED);
  // Alarms are sent by the alarm thread and the last ones only in the destructor: a process
  // that raised any may leave by its deadline before they reached the launcher.
  const bool raised = alarm_head_.load() > 0 || alarms_lost_.load() > 0;
  arm_exit_deadline(name_.c_str(), kStopToExitLimit,
                    raised ? kExitTeardownHungAfterAlarms : kExitTeardownHung);
}

RunControlView ProcessNode::run_control() const noexcept {
  RunControlView view;
  view.generation = rc_generation_.load();
  view.command = static_cast<RunCommand>(rc_command_.load());
  view.clock = static_cast<ClockKind>(rc_clock_.load());
  view.start_ns = rc_start_ns_.load() + clock_offset_ns_.load();
  view.pace = rc_pace_.load();
  return view;
}

void ProcessNode::serve_operator_commands(OperatorScope scope, AdmissionLimits limits) {
  operator_scope_ = scope;
  admission_limits_ = limits;
  answer_writer_.emplace(participant_);
  serving_.store(true, std::memory_order_release);
}

void ProcessNode::on_operator_command(const OperatorCommand& c) {
  // The wire's actions and refusals are in the same order as the inbox's and the rule's.
  static_assert(static_cast<int>(OperatorActionKind::alarm_ack) == OP_ALARM_ACK);
  static_assert(static_cast<int>(OperatorRefusal::text_too_long) == OPR_TEXT_TOO_LONG);
  if (!serving_.load(std::memory_order_acquire) ||
      !operator_scope_.covers(c.channel(), static_cast<int>(c.action()))) {
    return;  // not this process's to take, nor to answer
  }
  ArrivingCommand arriving;
  arriving.generation = c.generation();
  arriving.cycle = c.cycle();
  arriving.action = static_cast<int>(c.action());
  arriving.origin = c.origin();
  arriving.text_size = c.text().size();
  const std::uint64_t now = operator_cycle_.load();
  OperatorRefusal refusal = OperatorRefusal::none;
  wakeup_.update([&] {
    AdmissionState state;
    state.cycle = now;
    state.generation = rc_generation_.load();
    state.queued = operator_inbox_.size();
    state.queued_later = operator_inbox_.count_due_after_next(now);
    refusal = admit(arriving, state, admission_limits_);
    if (refusal != OperatorRefusal::none) {
      return;
    }
    OperatorRequest r;
    r.seq = c.seq();
    r.generation = c.generation();
    r.cycle = c.cycle();
    r.channel = c.channel();
    r.value = c.value();
    r.action = static_cast<OperatorActionKind>(c.action());
    std::copy(c.text().begin(), c.text().end(), r.text.begin());
    operator_inbox_.put(r);  // admit() saw the room
  });
  if (refusal != OperatorRefusal::none) {
    // A flood is logged by its first refusals and then every thousandth.
    const std::uint64_t refused = operator_refused_.fetch_add(1) + 1;
    if (refused <= 10 || refused % 1000 == 0) {
      spdlog::warn(
          "operator command (action {}) from {} (seq {}, cycle {}) refused at cycle {}: {} ({} "
          "refused so far)",
          static_cast<int>(c.action()), c.origin(), c.seq(), c.cycle(), now, reason_of(refusal),
          refused);
    }
  }
  OperatorAnswer answer;
  answer.process(name_);
  answer.sender(c.sender());
  answer.seq(c.seq());
  answer.refusal(static_cast<::mcnc::OperatorRefusal>(refusal));
  answer.reason(refusal == OperatorRefusal::none ? "" : reason_of(refusal));
  answer_writer_->write(answer);
}

std::optional<OperatorRequest> ProcessNode::take_operator_request(std::uint64_t cycle) noexcept {
  operator_cycle_.store(cycle);
  std::optional<OperatorRequest> due;
  const std::uint64_t generation = rc_generation_.load();
  wakeup_.with_lock([&] { due = operator_inbox_.take_due(cycle, generation); });
  return due;
}

bool ProcessNode::stop_arrives_within(std::chrono::milliseconds grace) {
  return wakeup_.wait_for(
      [this] {
        return static_cast<RunCommand>(rc_command_.load()) == RUN_STOP || g_stop_signal != 0;
      },
      grace);
}

bool ProcessNode::raise_alarm(std::uint32_t number, const char* text, std::uint64_t cycle,
                              int channel, int axis, int line, int column,
                              const char* file) noexcept {
  const std::uint64_t head = alarm_head_.load(std::memory_order_relaxed);
  if (head - alarm_tail_.load(std::memory_order_acquire) >= kAlarmSlots) {
    alarms_lost_.fetch_add(1);
    return false;
  }
  AlarmRecord& record = alarm_slots_[head % kAlarmSlots];
  record.number = number;
  std::snprintf(record.text.data(), record.text.size(), "%s", text);
  record.cycle = cycle;
  record.channel = channel;
  record.axis = axis;
  record.line = line;
  record.column = column;
  std::snprintf(record.file.data(), record.file.size(), "%s", file == nullptr ? "" : file);
  alarm_head_.store(head + 1, std::memory_order_release);
  alarm_signal_.fetch_add(1, std::memory_order_release);
  alarm_signal_.notify_one();
  return true;
}

void ProcessNode::publish_alarms() {
  std::uint64_t seq = 0;
  for (;;) {
    const std::uint64_t signal = alarm_signal_.load(std::memory_order_acquire);
    std::uint64_t tail = alarm_tail_.load(std::memory_order_relaxed);
    const std::uint64_t head = alarm_head_.load(std::memory_order_acquire);
    if (tail == head) {
      if (alarm_stop_.load()) {
        return;  // drained
      }
      alarm_signal_.wait(signal);  // returns at once if a raise came after the load above
      continue;
    }
    for (; tail != head; ++tail) {
      const AlarmRecord& record = alarm_slots_[tail % kAlarmSlots];
      Alarm alarm;
      alarm.src(name_);
      alarm.number(record.number);
      alarm.text(record.text.data());
      alarm.channel(record.channel);
      alarm.axis(record.axis);
      alarm.line(record.line);
      alarm.column(record.column);
      alarm.program(record.file.data());
      alarm.cycle(record.cycle);
      alarm.seq(++seq);
      alarm_writer_.write(alarm);
      const std::string place = text::program_place(record.file.data(), record.line, record.column);
      spdlog::error("alarm {}: {}{}", record.number, record.text.data(),
                    place.empty() ? place : " (" + place + ")");
      alarm_tail_.store(tail + 1, std::memory_order_release);
    }
  }
}

ProcessNode::~ProcessNode() {
  // Publish what is queued, then stop, while the writers still exist.
  alarm_stop_.store(true);
  alarm_signal_.fetch_add(1);
  alarm_signal_.notify_all();
  alarm_thread_.join();
  if (alarms_lost_.load() > 0) {
    spdlog::error("{} alarms were lost: the alarm queue was full", alarms_lost_.load());
  }
}

}  // namespace mcnc::process
