#include "launch/launcher.hpp"

#include "channel/control/channel_controller.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/process/command_answers.hpp"
#include "common/process/exit_deadline.hpp"
#include "common/process/process_node.hpp"
#include "common/process/shm_cleanup.hpp"
#include "common/process/startup.hpp"
#include "common/text/program_place.hpp"
#include "common/trace/trace_merge.hpp"
#include "common/trace/trace_writer.hpp"
#include "idl/dds_participant.hpp"
#include "launch/child_end.hpp"
#include "launch/child_process.hpp"
#include "launch/launch_plan.hpp"
#include "launch/machine_clock.hpp"
#include "launch/machine_security.hpp"
#include "launch/trace_shipping.hpp"

#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

namespace mcnc::launch {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

const char* to_string(::mcnc::ChannelState state) noexcept {
  // The wire's states are the channel's, in the same order.
  return channel::to_string(static_cast<channel::ChannelState>(static_cast<int>(state)));
}

namespace {

// How long a follower's trace parts may take to reach the coordinator, and the coordinator
// waits for them.
constexpr std::chrono::seconds kTraceShippingWait{20};
// After an E-stop, how long the launcher waits for the drives to come to rest, and for each axis
// node's first feedback sample (a node not heard by then is gone).
constexpr std::chrono::seconds kDrivesAtRestWait{5};
constexpr std::chrono::seconds kDriveHeardWait{2};
// A wave of a secured machine's start (launch_plan.hpp, start_waves) waits for the last one to
// be heard at most this long.
constexpr std::chrono::seconds kStartWaveWait{10};
// After an E-stop for a lost host, how long the processes on this side keep running before they
// are stopped. They learn which of their axes and partners are gone from the same DDS leases
// that told this launcher, but up to an announcement interval (1 s) later: a launcher may have
// been heard last by its announcement, a node by its last sample. Stopped sooner, a channel
// would end without the alarm that names the axis (1202) or the partner (1213, 1221) it lost.
constexpr std::chrono::seconds kLossTellHold{2};
// The most one look of the run's supervision counts towards a lockstep machine standing still.
constexpr std::chrono::milliseconds kLookLateCap{100};

struct Observed {
  std::mutex mutex;
  std::map<std::string, ProcessPhase> phases;  // under the wake-up lock, as the two below
  // Across hosts: the other hosts' launchers by their writer, and those whose writer left.
  std::map<dds::WriterId, std::string> launchers;
  std::vector<std::string> launchers_gone;
  // A follower's coordinator (the writer of "launch"), and whether its lease ran out.
  std::optional<dds::WriterId> coordinator;
  bool coordinator_gone = false;
  std::map<std::uint32_t, ::mcnc::ChannelStatus> status;
  std::map<std::uint32_t, AxisFeedback> feedback;
  std::vector<Alarm> alarms;
};

// Removes, when it goes, what a run left in /dev/shm (process::RunShmFootprint).
class LeftOverShmRemoval {
 public:
  explicit LeftOverShmRemoval(int domain) : footprint_(domain) {}
  ~LeftOverShmRemoval() { remove_left_over(); }
  void remove_left_over() noexcept {
    if (const std::size_t removed = footprint_.remove_left_over(); removed > 0) {
      spdlog::info("removed {} shared-memory files the run left in /dev/shm", removed);
    }
  }
  LeftOverShmRemoval(const LeftOverShmRemoval&) = delete;
  LeftOverShmRemoval& operator=(const LeftOverShmRemoval&) = delete;
  void note_process(pid_t pid) noexcept { footprint_.note_process(pid); }

 private:
  process::RunShmFootprint footprint_;
};

bool drive_at_rest(const AxisFeedback& fb) {
  return std::fabs(fb.vel()) < 1e-9 && !fb.enabled();
}

}  // namespace

Launcher::Launcher(config::MachineConfig machine, LaunchOptions options)
    : machine_(std::move(machine)), options_(std::move(options)) {}

LaunchResult Launcher::run(
    const std::function<void(const std::vector<ChannelProgress>&)>& on_progress,
    const std::function<void(const LaunchResult&)>& on_result) {
  LaunchResult result;
  const int domain = process::resolve_domain(machine_);
  // What /dev/shm held before the run: what the run's processes leave there is removed when
  // run() returns, after this launcher's own participant is gone too (Fast DDS leaves its port
  // files even after a clean exit), and nothing of another machine's run on this host.
  LeftOverShmRemoval shm_footprint(domain);
  // On a machine of several hosts, a launcher other than the first host's follows the run.
  const bool follower = is_follower(machine_, options_.host);
  // Children end with the launcher, even when it is killed (see process::die_with_parent()).
  std::vector<std::string> env{"MCNC_DOMAIN=" + std::to_string(domain), "MCNC_DIE_WITH_PARENT=1",
                               "MCNC_LAUNCHER_PID=" + std::to_string(::getpid())};
  if (!options_.host.empty()) {
    env.push_back("MCNC_HOST=" + options_.host);  // its processes keep machine time
  }

  // Trace parts: one per process, merged at the end.
  std::string parts_dir;
  std::vector<std::string> part_paths;
  if (!options_.trace_path.empty()) {
    parts_dir = options_.trace_path + ".parts";
    if (options_.host.empty()) {
      fs::remove_all(parts_dir);  // across hosts the others may be writing theirs already
    }
    fs::create_directories(parts_dir);
  }
  auto part_for = [&](const std::string& name) {
    if (parts_dir.empty()) {
      return std::string();
    }
    part_paths.push_back(trace_part(parts_dir, name));
    return part_paths.back();
  };

  // An onlooker of the cyclic topics: off shared memory, so a RouDi it started and stops
  // after the machine never counts it among the processes to end (HostRoudi).
  const std::string self = launcher_identity(machine_, options_.host);
  process::ProcessNode node(
      domain, self, dds::CyclicClock::realtime, process::resolve_middleware(machine_, "launch"),
      dds::LocalTransport::network,
      process::resolve_security_or_exit(machine_, self, {!options_.host.empty(), false}));
  trace::TraceWriter tracer(follower ? std::string() : part_for("launch"), "launch");
  Observed seen;
  process::Wakeup& wake = node.wakeup();
  dds::Reader<ProcessState> state_reader(
      node.participant(),
      [&](const ProcessState& s, const dds::WriterId& writer) {
        wake.update([&] {
          seen.phases[s.name()] = s.phase();
          if (s.name().rfind("launch-", 0) == 0) {
            seen.launchers[writer] = s.name();
          } else if (s.name() == "launch") {
            seen.coordinator = writer;
          }
        });
      },
      [&](const dds::WriterId& writer, bool matched) {
        if (!matched) {
          wake.update([&] {
            if (const auto it = seen.launchers.find(writer); it != seen.launchers.end()) {
              seen.launchers_gone.push_back(it->second);
            }
            seen.coordinator_gone = seen.coordinator_gone || seen.coordinator == writer;
          });
        }
      });
  // The processes a launcher answers for: a follower its own host's, the coordinator (or the
  // launcher of a machine on one host) every one.
  const auto answers_for = [&](const std::string& process) {
    const config::HostConfig* host = machine_.host_of(process);
    return !follower || (host != nullptr && host->name == options_.host);
  };
  // The run's progress, end and alarms need only each channel's latest sample (a channel's
  // status carries its run's start and end cycles), so the reader is an observer: no writer
  // waits for the launcher or repeats samples for it. Still, each is a sample a cycle, over the
  // network across hosts, so a follower reads only its own host's channels.
  std::vector<std::string> status_keys;
  for (const auto& ch : machine_.channels) {
    if (answers_for(ch.name)) {
      status_keys.push_back(ch.name);
    }
  }
  dds::Reader<::mcnc::ChannelStatus> status_reader(
      node.participant(), dds::Keys::of(status_keys),
      [&](const ::mcnc::ChannelStatus& s, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(seen.mutex);
        auto& slot = seen.status[s.channel()];
        if (s.cycle() >= slot.cycle()) {
          slot = s;
        }
      },
      {}, dds::ReaderRole::observer);
  dds::Reader<Alarm> alarm_reader(node.participant(), [&](const Alarm& a, const dds::WriterId&) {
    std::lock_guard<std::mutex> lock(seen.mutex);
    seen.alarms.push_back(a);
  });
  // The machine clock across hosts: the coordinator's CLOCK_MONOTONIC, which every other host
  // estimates its offset against; the run starts once every host has announced its offset.
  std::optional<MachineClockReference> clock_reference;
  std::optional<HostClockEstimator> clock_estimator;
  std::optional<HostClocks> host_clocks;
  if (!options_.host.empty()) {
    if (follower) {
      clock_estimator.emplace(node.participant(), options_.host);
    } else {
      host_clocks.emplace(node.participant());
      clock_reference.emplace(node.participant(), options_.host);
    }
  }
  std::optional<TracePartReceiver> trace_receiver;
  if (!follower && !options_.host.empty() && !parts_dir.empty()) {
    trace_receiver.emplace(node.participant(), parts_dir);
  }
  dds::Writer<RunControl> control_writer(node.participant());
  dds::Writer<OperatorCommand> operator_writer(node.participant());
  // The scripted operator's commands go out before the run starts, and the run starts once every
  // process they concern has taken them: one refused, or not answered within
  // kScriptAnswerLimit, fails the run before anything moves (docs/operations.md "Operator
  // commands").
  process::CommandAnswers script_answers(node.participant(), machine_);
  auto send_script = [&](std::uint64_t run_generation) -> std::string {
    std::vector<std::pair<std::uint64_t, std::string>> sent;  // seq, ACTION[:CHANNEL]@CYCLE
    std::uint64_t seq = 0;
    for (const auto& c : options_.operator_script) {
      OperatorCommand cmd;
      cmd.seq(++seq);
      cmd.generation(run_generation);
      cmd.cycle(c.cycle);
      cmd.channel(c.channel);
      cmd.action(c.action);
      cmd.value(c.value);
      cmd.origin("launch");
      cmd.sender(script_answers.sender());
      script_answers.expect(cmd.seq(), cmd.channel(), static_cast<int>(cmd.action()));
      std::string label =
          process::to_string(static_cast<process::OperatorActionKind>(static_cast<int>(c.action)));
      if (const config::ChannelConfig* channel = machine_.channel_by_id(c.channel)) {
        label += ":" + channel->name;
      }
      sent.emplace_back(cmd.seq(), label + "@" + std::to_string(c.cycle));
      operator_writer.write(cmd);
    }
    const auto deadline = std::chrono::steady_clock::now() + kScriptAnswerLimit;
    for (const auto& [command_seq, label] : sent) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      const process::CommandAnswers::Standing answer =
          script_answers.wait(command_seq, std::max(left, std::chrono::milliseconds(0)));
      if (answer.outcome == process::AnswerTally::Outcome::refused) {
        return "operator command " + label + " " + answer.why;
      }
      if (answer.outcome == process::AnswerTally::Outcome::pending) {
        return "operator command " + label + ": " + answer.why + " within " +
               std::to_string(kScriptAnswerLimit.count()) + " s";
      }
    }
    return {};
  };
  std::uint64_t script_end = 0;    // the last scripted command's cycle
  std::uint64_t alarms_after = 0;  // alarms from this cycle on stop the run
  for (const auto& c : options_.operator_script) {
    script_end = std::max(script_end, c.cycle);
    if (c.action == OP_RESET) {
      alarms_after = std::max(alarms_after, c.cycle);
    }
  }
  std::uint64_t generation = 0;
  // The generation the next RunControl this launcher sends carries: past every one heard.
  auto next_generation = [&] { return std::max(generation, node.run_control().generation) + 1; };
  // A follower whose coordinator is gone E-stops and stops its own host's processes.
  bool host_alone = false;
  // The run's start, set before RUN_START is sent: every RunControl carries it, an E-stop or a
  // stop too. A realtime process takes its cycles' origin from every RunControl
  // (cycle_loop.hpp), and with 0 its cycle numbers jumped to the host's uptime in cycles while
  // its drive stopped.
  std::int64_t run_start_ns = 0;
  auto send_control = [&](RunCommand command, const std::string& reason) {
    if (follower && !host_alone) {
      return;  // the coordinator runs the machine
    }
    RunControl rc;
    generation = next_generation();
    rc.generation(generation);
    rc.command(command);
    rc.clock(options_.clock);
    // This launcher keeps no host clock offset: the start it read is machine time, as it was
    // sent, and stays the start of the run it ends.
    rc.start_ns(follower ? node.run_control().start_ns : run_start_ns);
    rc.pace(options_.pace);
    rc.reason(reason);
    control_writer.write(rc);
  };

  // Children: drive simulators first (they answer the nodes' NMT), then axis nodes, channels.
  const LaunchPlan plan = launch_plan(machine_, options_, parts_dir, options_.host);
  std::vector<ChildProcess> children;
  children.reserve(plan.children.size());
  for (const ChildSpec& spec : plan.children) {
    children.emplace_back(spec.name, spec.argv);
  }
  const std::vector<std::string>& dds_processes = plan.dds_processes;
  // Merge order inside a cycle: channels, axes, the PLC, launch.
  std::vector<std::string> merge_order = launch_plan(machine_, options_, parts_dir).trace_parts;
  merge_order.insert(merge_order.end(), part_paths.begin(), part_paths.end());

  // The files in /dev/shm that the run's processes (this one among them) use.
  const auto note_run_shm = [&] {
    shm_footprint.note_process(::getpid());
    for (auto& child : children) {
      if (child.running()) {
        shm_footprint.note_process(child.pid());
      }
    }
  };
  // A large secured machine starts in waves (decision 112): the next once this launcher has
  // heard every DDS process of the last (its participant made, its handshake with this one
  // done), or after kStartWaveWait. Any other machine starts every child at once, as before.
  const std::vector<std::vector<std::size_t>> waves =
      start_waves(plan, !machine_.security_dir.empty());
  std::size_t next_wave = 0;
  auto wave_started = std::chrono::steady_clock::now();
  const auto start_wave = [&] {
    for (const std::size_t i : waves[next_wave]) {
      children[i].start(env);
      spdlog::debug("started {} (pid {})", children[i].name(), children[i].pid());
    }
    ++next_wave;
    wave_started = std::chrono::steady_clock::now();
  };
  start_wave();
  if (waves.size() > 1) {
    spdlog::info("secured machine of {} DDS processes: starting them in {} waves",
                 dds_processes.size(), waves.size());
  }
  // Starts the next wave when the last one has been heard: true once every wave has started.
  const auto start_next_wave = [&] {
    if (next_wave == waves.size()) {
      return true;
    }
    bool heard = true;
    wake.update([&] {
      for (const std::size_t i : waves[next_wave - 1]) {
        const std::string& name = children[i].name();
        const bool dds =
            std::find(dds_processes.begin(), dds_processes.end(), name) != dds_processes.end();
        heard = heard && (!dds || seen.phases.count(name) != 0);
      }
    });
    if (heard || std::chrono::steady_clock::now() >= wave_started + kStartWaveWait) {
      start_wave();
      note_run_shm();
    }
    return next_wave == waves.size();
  };
  if (!options_.host.empty()) {
    // The coordinator watches the other hosts by it, and they watch the coordinator.
    node.announce(PHASE_RUNNING);
  }

  std::uint64_t last_cycle = 0;
  auto progress = [&] {
    std::vector<ChannelProgress> list;
    std::lock_guard<std::mutex> lock(seen.mutex);
    for (const auto& ch : machine_.channels) {
      if (!answers_for(ch.name)) {
        continue;  // a follower's result is its host's part of the run
      }
      ChannelProgress p;
      p.name = ch.name;
      p.has_program = options_.programs.count(ch.name) != 0;
      auto it = seen.status.find(static_cast<std::uint32_t>(ch.id));
      if (it != seen.status.end()) {
        const auto& s = it->second;
        p.state = s.state();
        p.block = s.block();
        p.block_total = s.block_total();
        p.line = s.line();
        p.alarms = s.alarms();
        p.ended = s.program_end();
        p.end_code = s.end_code();
        p.cycle = s.cycle();
        // The channel reports its own start and end cycles: exact from any one sample.
        p.seen_running = s.state() == CH_RUNNING || s.program_end() || s.run_start_cycle() > 0;
        p.run_start_cycle = s.run_start_cycle();
        p.end_cycle = s.end_cycle();
        last_cycle = std::max(last_cycle, s.cycle());
      }
      list.push_back(p);
    }
    return list;
  };
  auto find_exited = [&]() -> ChildProcess* {
    for (auto& child : children) {
      if (child.running() && child.poll_exited()) {
        if (child.name() == kHmiName) {
          // The operator station is not the machine: without it, the machine goes on.
          spdlog::warn("{} {}; the machine goes on without it", child.name(),
                       child.exit_description());
          continue;
        }
        return &child;
      }
    }
    return nullptr;
  };
  // A child stopped by a signal (SIGSTOP, a debugger, SIGTSTP) takes no step: in lockstep the
  // whole machine stands with it. Its name and the signal, or "" when none is stopped. A stop
  // of less than a second is not yet a fault: a process held for a moment and resumed (a
  // debugger's attach, a machine paused as a whole and resumed child by child) goes on.
  constexpr auto kStoppedGrace = std::chrono::seconds(1);
  const auto stopped_child = [&]() -> std::string {
    for (auto& child : children) {
      if (child.running() && child.stop_signal() != 0 && child.name() != kHmiName &&
          child.stopped_for() >= kStoppedGrace) {
        return child.name() + " stopped by signal " + std::to_string(child.stop_signal()) + " (" +
               strsignal(child.stop_signal()) + "): the machine cannot step";
      }
    }
    return {};
  };
  // After the E-stop went out: a stopped child is resumed, so that it quick-stops its drive and
  // leaves with the others (stopped, it would neither, and a drive it commands would keep its
  // last setpoint). One that still does not leave is killed as any other.
  const auto resume_stopped_children = [&] {
    for (auto& child : children) {
      if (child.running() && child.stop_signal() != 0) {
        spdlog::warn("{} was stopped by signal {}: resumed for the E-stop", child.name(),
                     child.stop_signal());
        child.signal(SIGCONT);
      }
    }
  };

  const auto roudi_lost = [&] { return options_.watch_roudi && !dds::roudi_answers(); };
  const char* const kRoudiLost = "the host's iceoryx RouDi stopped answering";

  // A follower's report of a process it lost (alarm 3001 from "launch-<host>"), for the
  // coordinator: empty when there is none.
  const auto host_failure = [&]() -> std::string {
    if (follower || options_.host.empty()) {
      return {};
    }
    // A host whose launcher left (its DDS lease ran out: the host is down or cut off).
    std::string gone;
    wake.update([&] {
      if (!seen.launchers_gone.empty()) {
        gone = seen.launchers_gone.front().substr(std::string("launch-").size()) +
               ": its launcher is gone (the host is down or cut off)";
      }
    });
    if (!gone.empty()) {
      return gone;
    }
    std::lock_guard<std::mutex> lock(seen.mutex);
    for (const auto& a : seen.alarms) {
      if (a.number() == 3001 && a.src() != "launch") {
        return a.src().substr(std::string("launch-").size()) + ": " + a.text();
      }
    }
    return {};
  };
  const auto a_launcher_gone = [&] {
    bool gone = false;
    wake.update([&] { gone = !seen.launchers_gone.empty(); });
    return gone;
  };
  const auto coordinator_ended = [&] {
    const RunCommand cmd = node.run_control().command;
    return follower && (cmd == RUN_STOP || cmd == RUN_ESTOP);
  };
  // A follower's coordinator whose DDS lease ran out: its host is down or cut off from this one.
  const auto coordinator_lost = [&]() -> std::string {
    bool gone = false;
    wake.update([&] { gone = follower && seen.coordinator_gone; });
    return gone ? "the coordinator on host " + machine_.hosts.front().name +
                      " is gone (its launcher's lease ran out: the host is down or cut off)"
                : std::string();
  };
  // After an E-stop: until every drive this launcher answers for is at rest, at most 5 s. Their
  // feedback is read only now: all through the run it would cost a sample a cycle from every
  // axis node, over the network across hosts (decision 54). A node not heard within
  // kDriveHeardWait (its process or host is gone) does not hold the stop up.
  const auto wait_drives_at_rest = [&] {
    std::vector<std::string> keys;
    std::vector<std::uint32_t> ids;
    for (const auto& axis : machine_.axes) {
      if (answers_for(config::node_key(axis))) {
        keys.push_back(config::node_key(axis));
        ids.push_back(static_cast<std::uint32_t>(axis.id));
      }
    }
    dds::Reader<AxisFeedback> feedback_reader(
        node.participant(), dds::Keys::of(keys),
        [&](const AxisFeedback& f, const dds::WriterId&) {
          std::lock_guard<std::mutex> lock(seen.mutex);
          seen.feedback[f.axis()] = f;
        },
        {}, dds::ReaderRole::observer);
    const auto begin = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() < begin + kDrivesAtRestWait) {
      std::this_thread::sleep_for(20ms);
      find_exited();
      bool rest = true;
      bool heard = true;
      std::lock_guard<std::mutex> lock(seen.mutex);
      for (const std::uint32_t id : ids) {
        auto it = seen.feedback.find(id);
        heard = heard && it != seen.feedback.end();
        rest = rest && (it == seen.feedback.end() || drive_at_rest(it->second));
      }
      if (rest && (heard || std::chrono::steady_clock::now() >= begin + kDriveHeardWait)) {
        break;
      }
    }
  };

  std::string failure;
  bool killed_child = false;
  bool sent_kill = false;  // children that had not left after the run were killed

  // 1. Wait until every DDS process is ready (discovery done, drive answered).
  // A follower waits 30 s longer than its coordinator: the coordinator, which may have been
  // started later, is the one to give up and say which host does not answer.
  const auto start_deadline =
      std::chrono::steady_clock::now() +
      std::chrono::milliseconds(static_cast<long>(options_.start_timeout_s * 1000)) +
      (follower ? 30s : 0s);
  for (;;) {
    if (ChildProcess* dead = find_exited()) {
      failure = dead->name() + " " + dead->exit_description() + " during start-up";
      break;
    }
    if (roudi_lost()) {
      failure = std::string(kRoudiLost) + " during start-up";
      break;
    }
    if (const std::string lost = host_failure(); !lost.empty()) {
      failure = "host " + lost + " during start-up";
      break;
    }
    if (coordinator_ended()) {
      break;  // the coordinator gave up the start: this host stops too
    }
    if (const std::string lost = coordinator_lost(); !lost.empty()) {
      failure = lost + " during start-up";
      break;
    }
    const bool all_started = start_next_wave();
    std::string not_ready;  // the processes still starting, for the operator
    wake.update([&] {
      for (const auto& name : dds_processes) {
        // Running counts too: a follower may hear a process's READY only together with the
        // RUNNING that replaced it (a lost sample is repaired with the next), once the
        // coordinator has started the run.
        auto it = seen.phases.find(name);
        if (it == seen.phases.end() || (it->second != PHASE_READY && it->second != PHASE_RUNNING)) {
          not_ready += (not_ready.empty() ? "" : ", ") + name;
        }
      }
    });
    for (std::size_t h = 0; host_clocks && h < machine_.hosts.size(); ++h) {
      if (!host_clocks->of(machine_.hosts[h].name)) {
        not_ready += (not_ready.empty() ? "" : ", ") + machine_.hosts[h].name + "'s clock";
      }
    }
    if (not_ready.empty() && all_started) {
      break;
    }
    if (std::chrono::steady_clock::now() > start_deadline || process::g_stop_signal != 0) {
      failure = process::g_stop_signal != 0 ? "interrupted during start-up"
                                            : "start-up timed out (not ready: " + not_ready + ")";
      // Across hosts, the hosts whose launcher never announced itself come first.
      std::string silent;
      for (std::size_t h = 1; !follower && !options_.host.empty() && h < machine_.hosts.size();
           ++h) {
        const std::string name = "launch-" + machine_.hosts[h].name;
        wake.update([&] {
          if (seen.phases.find(name) == seen.phases.end()) {
            silent += (silent.empty() ? "" : ", ") + machine_.hosts[h].name;
          }
        });
      }
      if (!silent.empty()) {
        failure = "start-up timed out: no launcher answers on host " + silent +
                  " (not ready: " + not_ready + ")";
      }
      break;
    }
    std::this_thread::sleep_for(5ms);
  }

  // 2. Run.
  bool estopped = false;
  bool host_lost = false;  // the coordinator's E-stop is for a host gone or cut off
  if (follower) {
    // Until the coordinator stops the run: this host's processes, a lost one reported once.
    bool reported = false;
    std::optional<std::chrono::steady_clock::time_point> failed_at;
    for (;;) {
      if (!failure.empty() && !reported) {
        reported = true;
        failed_at = std::chrono::steady_clock::now();
        spdlog::error("host {}: {}", options_.host, failure);
        node.raise_alarm(3001, ("emergency stop: " + failure).c_str(), last_cycle);
      }
      if (node.run_control().command == RUN_STOP || process::g_stop_signal != 0 ||
          (failed_at && std::chrono::steady_clock::now() - *failed_at > 30s)) {
        break;
      }
      if (const std::string lost = coordinator_lost(); !lost.empty()) {
        // Nobody else will stop this host's processes: E-stop them here (drives quick stop,
        // channels reset), and stop them once the drives are at rest.
        if (failure.empty()) {
          failure = lost;
        } else {
          spdlog::error("host {}: {}", options_.host, lost);
        }
        spdlog::error("host {}: E-stop: {}", options_.host, failure);
        node.raise_alarm(3001, ("emergency stop: " + failure).c_str(), last_cycle);
        host_alone = true;
        estopped = true;
        send_control(RUN_ESTOP, failure);
        wait_drives_at_rest();
        std::this_thread::sleep_for(kLossTellHold);
        break;
      }
      std::this_thread::sleep_for(20ms);
      (void)progress();
      if (ChildProcess* dead = find_exited(); dead != nullptr && failure.empty()) {
        failure = dead->name() + " " + dead->exit_description();
        killed_child = dead->exit_code() < 0;
      }
      if (const std::string stopped = stopped_child(); !stopped.empty() && failure.empty()) {
        failure = stopped;  // reported to the coordinator, which E-stops the machine
        resume_stopped_children();
      }
    }
  } else if (failure.empty()) {
    spdlog::info("all {} processes ready; starting the run ({} clock)", dds_processes.size(),
                 options_.clock == LOCKSTEP_CLOCK ? "lockstep" : "realtime");
    // Each host's clock as the run starts with it (docs/trace.md `clock`).
    for (std::size_t h = 0; host_clocks && h < machine_.hosts.size(); ++h) {
      const HostClock hc = *host_clocks->of(machine_.hosts[h].name);
      spdlog::info("host {}: clock offset {} us (+-{} us, {} exchanges)", hc.host(),
                   hc.offset_ns() / 1000, hc.error_ns() / 1000, hc.samples());
      tracer.emit(0, "clock", "\"host\":\"%s\",\"offset_ns\":%lld,\"error_ns\":%lld,\"samples\":%u",
                  hc.host().c_str(), static_cast<long long>(hc.offset_ns()),
                  static_cast<long long>(hc.error_ns()), hc.samples());
    }
    // The script belongs to the run that starts next (send_control numbers it so).
    failure = send_script(next_generation());
    const bool started = failure.empty();
    if (started) {
      // Realtime: cycle 0 a little in the future so every process starts on the same tick.
      run_start_ns = clock::monotonic_ns() + 100'000'000;
      send_control(RUN_START, "");
    } else {
      spdlog::error("not started: {}", failure);  // nothing moved: no E-stop
    }
    note_run_shm();  // every endpoint is made by now: ready means discovered
    const bool any_program = !options_.programs.empty();
    const bool realtime = options_.clock == REALTIME_CLOCK;
    if (realtime) {
      // Every child is started: none inherits this priority.
      sched_param param{};
      param.sched_priority = kSupervisorPriority;
      if (::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &param) != 0) {
        spdlog::warn(
            "the launcher could not run at SCHED_FIFO {}: a machine that overloads the host "
            "would also keep it from stopping the machine",
            kSupervisorPriority);
      }
    }
    const auto run_start = std::chrono::steady_clock::now();
    std::uint64_t heard_cycle = 0;  // the newest cycle any channel reported
    auto heard_at = run_start;
    // Lockstep: how long no channel has stepped, as far as the launcher looked on time.
    auto looked_at = run_start;
    std::chrono::steady_clock::duration standing{};
    auto last_progress = std::chrono::steady_clock::now() - 1s;
    std::optional<std::chrono::steady_clock::time_point> alarm_since;
    std::uint64_t alarm_cycle = 0;
    while (failure.empty()) {
      // Ends, alarms and exits are noticed within this period. Each look costs system calls,
      // which are dear in an emulated machine (about 40 us each under the user-mode Linux the
      // socketcan tests once ran in): polling every 2 ms made their machine a fifth slower
      // there (docs/decisions.md 27).
      std::this_thread::sleep_for(20ms);
      const auto list = progress();
      if (std::chrono::steady_clock::now() - last_progress > 100ms) {
        last_progress = std::chrono::steady_clock::now();
        if (on_progress) {
          on_progress(list);
        }
      }
      if (ChildProcess* dead = find_exited()) {
        failure = dead->name() + " " + dead->exit_description();
        killed_child = dead->exit_code() < 0;
        break;
      }
      if (const std::string stopped = stopped_child(); !stopped.empty()) {
        failure = stopped;
        break;
      }
      if (roudi_lost()) {
        failure = kRoudiLost;
        break;
      }
      if (const std::string lost = host_failure(); !lost.empty()) {
        failure = "host " + lost;
        host_lost = a_launcher_gone();
        break;
      }
      if (process::g_stop_signal != 0) {
        failure = "interrupted";
        break;
      }
      const auto looked_now = std::chrono::steady_clock::now();
      if (last_cycle > heard_cycle) {
        heard_cycle = last_cycle;
        heard_at = looked_now;
        standing = std::chrono::steady_clock::duration::zero();
      } else {
        // A look that came late (the launcher itself starved by a loaded host) counts for no
        // more than kLookLateCap: the machine may have stepped in that time unheard.
        standing +=
            std::min<std::chrono::steady_clock::duration>(looked_now - looked_at, kLookLateCap);
      }
      looked_at = looked_now;
      if (realtime && std::chrono::steady_clock::now() - heard_at > kMachineSilentLimit) {
        failure = "no channel heard for " + std::to_string(kMachineSilentLimit.count()) +
                  " s: this host does not keep up with the machine in realtime";
        break;
      }
      if (!realtime && standing > kMachineSilentLimit) {
        failure = "the machine stands still at cycle " + std::to_string(heard_cycle) +
                  ": no channel stepped for " + std::to_string(kMachineSilentLimit.count()) +
                  " s (a process or a drive no longer answers)";
        break;
      }
      if (options_.run_timeout_s > 0 && std::chrono::steady_clock::now() - run_start >
                                            std::chrono::duration<double>(options_.run_timeout_s)) {
        failure = "run timed out";
        break;
      }
      // An alarm anywhere stops the run: wait until the channels have reacted (alarm, end or
      // reset), at most a second of machine time, then stop cleanly. The alarm makes the result
      // a failure. A scripted operator still to act keeps the run going. In lockstep the second
      // is counted in cycles, so that a loaded host does not cut short what the others do in
      // it; 30 s of wall time end a machine that no longer steps.
      const bool script_pending = last_cycle <= script_end;
      std::size_t alarm_count = 0;
      {
        std::lock_guard<std::mutex> lock(seen.mutex);
        for (const auto& a : seen.alarms) {
          alarm_count += a.cycle() >= alarms_after ? 1 : 0;
        }
      }
      if (alarm_count > 0 && !script_pending) {
        if (!alarm_since) {
          alarm_since = std::chrono::steady_clock::now();
          alarm_cycle = last_cycle;
        }
        bool settled = true;
        for (const auto& p : list) {
          settled =
              settled && (!p.has_program || p.ended || p.state == CH_ALARM || p.state == CH_RESET);
        }
        const auto waited = std::chrono::steady_clock::now() - *alarm_since;
        const bool second_passed =
            options_.clock == LOCKSTEP_CLOCK
                ? last_cycle > alarm_cycle + machine_.cycles_of(1000) || waited > 30s
                : waited > 1s;
        if (settled || second_passed) {
          break;
        }
      }
      if (any_program && !script_pending) {
        bool all_done = true;
        std::uint64_t last_program_end = 0;
        for (const auto& p : list) {
          if (p.has_program) {
            // After a scripted operator, a channel left idle (reset and not started again) has
            // nothing more to do either.
            all_done = all_done && (p.ended || p.state == CH_ALARM ||
                                    (!options_.operator_script.empty() && p.state == CH_IDLE));
          }
          if (p.ended) {
            last_program_end = std::max(last_program_end, p.end_cycle);
          }
        }
        // A channel running a program another channel called (G144) holds the run too; a call
        // sent just before a program's end (also a called program's) starts in the next cycle,
        // so every channel must report a cycle past the last end first.
        for (const auto& p : list) {
          all_done = all_done && p.cycle >= last_program_end + 2 && p.state != CH_RUNNING &&
                     p.state != CH_WAITING && p.state != CH_HOLD;
        }
        if (all_done) {
          break;
        }
      }
    }
    if (failure.empty() && alarm_since && !options_.host.empty()) {
      // Across hosts, a host that went down is often heard first through its peers' alarms
      // (an owner or partner lost); its launcher's lease runs out within 3 s. Wait that long
      // for it, so that a lost host ends the run in an E-stop, not a stop.
      const auto lease_end = std::chrono::steady_clock::now() + 4s;
      while (failure.empty() && std::chrono::steady_clock::now() < lease_end) {
        if (const std::string lost = host_failure(); !lost.empty()) {
          failure = "host " + lost;
          host_lost = a_launcher_gone();
        }
        std::this_thread::sleep_for(20ms);
      }
    }
    if (!failure.empty() && started) {
      // E-stop: channels reset, drives quick stop; wait until the drives are at rest.
      estopped = true;
      spdlog::error("E-stop: {}", failure);
      tracer.emit(last_cycle, "alarm", "\"number\":3001,\"text\":\"emergency stop: %s\"",
                  failure.c_str());
      node.raise_alarm(3001, ("emergency stop: " + failure).c_str(), last_cycle);
      send_control(RUN_ESTOP, failure);
      resume_stopped_children();
      wait_drives_at_rest();
      if (host_lost) {
        std::this_thread::sleep_for(kLossTellHold);
      }
    }
  }

  // 3. Stop: ask politely (DDS processes by run control, drive simulators by SIGTERM once
  // their nodes are gone), then insist.
  note_run_shm();
  send_control(RUN_STOP, failure);
  auto wait_all = [&](std::chrono::milliseconds timeout, bool dds_only = false) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      bool any = false;
      for (auto& child : children) {
        // Drive simulators and the HMI take no run control: they are signalled after the rest.
        const bool signalled = child.name().rfind("drivesim-", 0) == 0 || child.name() == kHmiName;
        if (dds_only && signalled) {
          continue;
        }
        any = any || (child.running() && !child.poll_exited());
      }
      if (!any || std::chrono::steady_clock::now() > deadline) {
        return !any;
      }
      std::this_thread::sleep_for(10ms);
    }
  };
  wait_all(3s, true);
  for (auto& child : children) {
    if (child.name().rfind("drivesim-", 0) == 0 || child.name() == kHmiName) {
      child.signal(SIGTERM);
    }
  }
  if (!wait_all(3s)) {
    for (auto& child : children) {
      child.signal(SIGTERM);
    }
    // Longer than a process's exit deadline after its stop (kStopToExitLimit), so that one
    // stopped by this SIGTERM whose DDS teardown then hangs leaves by itself, saying so.
    if (!wait_all(process::kStopToExitLimit + 2s)) {
      for (auto& child : children) {
        child.signal(SIGKILL);
      }
      killed_child = true;
      sent_kill = true;
      wait_all(3s);
    }
  }
  const bool run_failed = !failure.empty();
  for (auto& child : children) {
    if (child.pid() <= 0) {
      continue;  // a wave the start never reached
    }
    ChildExit exit_facts;
    exit_facts.exit_code = child.exit_code();
    exit_facts.killed_by_launcher = sent_kill;
    exit_facts.run_failed = run_failed;
    wake.update([&] {
      const auto it = seen.phases.find(child.name());
      exit_facts.announced_stop = it != seen.phases.end() && it->second == PHASE_STOPPED;
    });
    const ChildEnd end = classify_child_end(exit_facts);
    if (end == ChildEnd::teardown || end == ChildEnd::teardown_early) {
      spdlog::warn(
          "{} {} after the run ended (DDS teardown){}", child.name(), child.exit_description(),
          end == ChildEnd::teardown ? ""
                                    : ", before it had stopped: what it does at its end (a channel "
                                      "saving the retained variables) may not be done");
      killed_child = true;  // its shared-memory files stay behind, as after a kill
      continue;
    }
    if (end == ChildEnd::failed && failure.empty() && child.name() != kHmiName) {
      failure = child.name() + " " + child.exit_description();
    }
  }
  if (killed_child) {
    process::remove_stale_dds_shm_files();
  }

  // Across hosts, a follower sends its host's trace parts to the coordinator (unless it lost
  // it): the hosts need not share the trace's directory.
  if (follower && !options_.trace_path.empty() && !host_alone) {
    TracePartSender sender(node.participant(), options_.host);
    if (!sender.send(plan.trace_parts, kTraceShippingWait)) {
      spdlog::warn("host {}: the coordinator did not confirm this host's trace parts",
                   options_.host);
    }
  }

  // 4. Result and trace.
  const auto final_list = progress();
  {
    std::lock_guard<std::mutex> lock(seen.mutex);
    for (const auto& a : seen.alarms) {
      // Where in a program, as the check before the run says it: the main program by the path
      // it was given, a called program by the path the channel read.
      std::string file = a.program();
      const config::ChannelConfig* ch =
          machine_.channel_by_id(static_cast<std::uint64_t>(std::max(a.channel(), 0)));
      const auto given = ch == nullptr ? options_.programs.end() : options_.programs.find(ch->name);
      if (given != options_.programs.end() && !file.empty() &&
          fs::path(given->second).filename() == file) {
        file = given->second;
      }
      const std::string place = text::program_place(file, a.line(), a.column());
      result.alarms.push_back(a.src() + " " + std::to_string(a.number()) + " " + a.text() +
                              (place.empty() ? "" : " (" + place + ")"));
    }
  }
  bool ok = failure.empty() && !estopped;
  for (const ChannelProgress& p : final_list) {
    if (p.has_program && (!p.ended || p.alarms > 0)) {
      ok = false;
    }
    result.channels.push_back(p);
  }
  if (!result.alarms.empty()) {
    ok = false;
  }
  // The run lasted until the last program end (the stop that follows takes a few more cycles).
  std::uint64_t last_end = 0;
  bool all_ended = !options_.programs.empty();
  for (const auto& p : result.channels) {
    if (p.has_program) {
      all_ended = all_ended && p.ended;
    }
    if (p.has_program || p.ended) {  // a called program's end counts too
      last_end = std::max(last_end, p.end_cycle);
    }
  }
  result.cycles = all_ended ? last_end : last_cycle;
  result.failure = failure;
  result.exit_code = ok ? 0 : 1;

  tracer.flush();
  if (!options_.host.empty() && !follower && !options_.trace_path.empty()) {
    // The other hosts' processes write their parts until they stop: wait for each to say so
    // (or to be gone) before the merge, at most 10 s.
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    for (bool all = false; !all && std::chrono::steady_clock::now() < deadline;) {
      all = true;
      wake.update([&] {
        for (const auto& name : dds_processes) {
          const auto it = seen.phases.find(name);
          all = all && it != seen.phases.end() &&
                (it->second == PHASE_STOPPED || it->second == PHASE_FAILED);
        }
      });
      std::this_thread::sleep_for(20ms);
    }
  }
  if (trace_receiver) {
    // The other hosts' parts, from every host whose launcher came and is still there.
    std::vector<std::string> senders;
    wake.update([&] {
      for (std::size_t h = 1; h < machine_.hosts.size(); ++h) {
        const std::string name = "launch-" + machine_.hosts[h].name;
        const bool came = std::any_of(seen.launchers.begin(), seen.launchers.end(),
                                      [&](const auto& l) { return l.second == name; });
        const bool gone = std::find(seen.launchers_gone.begin(), seen.launchers_gone.end(), name) !=
                          seen.launchers_gone.end();
        if (came && !gone) {
          senders.push_back(machine_.hosts[h].name);
        }
      }
    });
    for (const std::string& host : trace_receiver->wait_for(senders, kTraceShippingWait)) {
      spdlog::warn(
          "host {}: its trace parts did not all come; the trace has what its "
          "processes wrote here",
          host);
    }
  }
  if (!options_.trace_path.empty() && !follower) {
    const std::uint64_t merged_last = trace::merge_parts(merge_order, options_.trace_path);
    if (!all_ended) {
      result.cycles = std::max(result.cycles, merged_last);  // the run's last cycle
    }
    std::ofstream out(options_.trace_path, std::ios::app);
    std::ostringstream summary;
    summary << "{\"cycle\":" << std::max(merged_last, result.cycles)
            << ",\"src\":\"launch\",\"ev\":\"summary\",\"ok\":" << (ok ? "true" : "false")
            << ",\"cycles\":" << result.cycles << ",\"channels\":{";
    bool first = true;
    for (const auto& p : result.channels) {
      summary << (first ? "" : ",") << "\"" << p.name << "\":{\"end\":";
      first = false;
      if (p.ended) {
        summary << p.end_code;
      } else {
        summary << "null";
      }
      const double cycle_time =
          p.ended && p.seen_running
              ? static_cast<double>(p.end_cycle - p.run_start_cycle) * machine_.cycle_s()
              : 0.0;
      summary << ",\"alarms\":" << p.alarms << ",\"cycle_time_s\":" << cycle_time << "}";
    }
    summary << "}}";
    out << summary.str() << '\n';
    fs::remove_all(parts_dir);
  }
  if (on_result) {
    // What the run's processes left goes now: the teardown that follows may be cut short
    // (process::TeardownBound).
    shm_footprint.remove_left_over();
    on_result(result);
  }
  return result;  // the participant and its readers are deleted now
}

}  // namespace mcnc::launch
