// Setpoint latency, channel publish -> drive receipt of the RPDO, in the realtime clock.
// This program plays the channel and the launcher around the real drive simulator and axis nodes
// of a machine. The channel's part publishes one AxisSetpoint per cycle for the first axis of
// the first channel whose position encodes the cycle number, and listens on the CAN bus for the
// axis node's RPDOs. The latency of cycle k is (RPDO with target k received) - (setpoint k
// written). It includes the designed one-cycle delay (a setpoint stamped N is applied at N+1).
// As on a machine, the launcher's part (this process) starts the host's RouDi when none
// answers, starts the processes, the channel's part among them (--channel-part), and runs the
// run control; it stays off shared memory, since RouDi ends the processes still registered with
// it when it stops (decision 32). On a secured machine (security_dir) each part plays with its
// own identity: only the launcher's may write run control, and one process holds one identity
// on a domain.
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/frames.hpp"
#include "common/can/can_bus.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/process/shm_cleanup.hpp"
#include "common/process/startup.hpp"
#include "launch/child_process.hpp"
#include "launch/host_roudi.hpp"
#include "launch/self_path.hpp"

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace mcnc;
using namespace std::chrono_literals;

namespace {

// Cycles before the measured ones, not counted.
constexpr int kWarmupCycles = 500;

// The channel's part: on the realtime clock and shared memory, with the channel's identity.
// Announces READY once its setpoints reach every axis node and it listens on the bus; from the
// run's start, setpoint k creeps to k counts, then holds the last one, as a channel commands
// until the run stops; then prints the figures.
int play_channel(const config::MachineConfig& machine, int domain, int cycles,
                 const std::string& bus_netns) {
  clock::prepare_realtime_process();
  const config::ChannelConfig& channel = machine.channels.at(0);
  const config::AxisConfig& axis = *machine.find_axis(channel.axes.at(0));
  const config::BusConfig& bus = *machine.find_bus(axis.bus);
  process::ProcessNode node(domain, channel.name, dds::CyclicClock::realtime,
                            process::resolve_middleware(machine, channel.name),
                            dds::LocalTransport::shared_memory,
                            process::resolve_security_or_exit(machine, channel.name));
  // One setpoint writer per axis, on its topic, as the channel has.
  std::vector<std::unique_ptr<dds::Writer<AxisSetpoint>>> setpoints;
  for (const auto& name : channel.axes) {
    setpoints.push_back(std::make_unique<dds::Writer<AxisSetpoint>>(node.participant(), name));
  }
  dds::Reader<AxisFeedback> feedback(node.participant(), dds::Keys::of(channel.axes),
                                     [](const AxisFeedback&, const dds::WriterId&) {});

  // Receive RPDOs on the bus: target counts -> receive time.
  const std::int64_t cycle_ns = static_cast<std::int64_t>(machine.cycle_us) * 1000;
  const std::uint64_t total = static_cast<std::uint64_t>(cycles + kWarmupCycles);
  std::vector<std::int64_t> published(total + 10, 0);
  std::vector<std::int64_t> received(published.size(), 0);
  std::atomic<bool> stop{false};
  std::unique_ptr<can::CanBus> can;
  std::atomic<bool> listening{false};
  std::thread listener([&] {
    if (!bus_netns.empty()) {
      const int fd = ::open(bus_netns.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0 || ::setns(fd, CLONE_NEWNET) != 0) {
        std::fprintf(stderr, "cannot enter the network namespace %s\n", bus_netns.c_str());
        std::exit(1);
      }
      ::close(fd);
    }
    can = can::open_can_bus(bus.uri);
    listening = true;
    canopen::CanFrame frame;
    while (!stop) {
      if (can->receive(frame, 50ms) != can::BusResult::ok) {
        continue;
      }
      const std::int64_t now = clock::monotonic_ns();
      const auto cls = canopen::classify(frame);
      if (cls.kind == canopen::FrameKind::rpdo1 && cls.node == axis.node_id) {
        if (auto pdo = canopen::decode_rpdo_csp(frame)) {
          const std::int64_t k = pdo->target_position;  // see below
          if (k >= 0 && k < static_cast<std::int64_t>(received.size()) &&
              received[static_cast<std::size_t>(k)] == 0) {
            received[static_cast<std::size_t>(k)] = now;
          }
        }
      }
    }
  });
  const auto finish_listening = [&] {
    stop = true;
    listener.join();
  };

  const auto setpoints_matched = [&] {
    return std::all_of(setpoints.begin(), setpoints.end(),
                       [](const auto& w) { return w->matched_readers() >= 1; });
  };
  for (int i = 0; i < 3000 && !(listening && setpoints_matched()); ++i) {
    std::this_thread::sleep_for(10ms);
  }
  if (!(listening && setpoints_matched())) {
    std::fprintf(stderr, "the channel's setpoints reached no axis node\n");
    finish_listening();
    return 1;
  }
  node.announce(PHASE_READY);
  if (!node.wakeup().wait_for([&] { return node.run_control().command != RUN_NONE; }, 60s) ||
      node.run_control().command != RUN_START) {
    std::fprintf(stderr, "the run did not start\n");
    finish_listening();
    return 1;
  }
  const std::int64_t start_ns = node.run_control().start_ns;

  // Setpoint k carries position k counts, so the RPDO target identifies it: a creep of one
  // count a cycle from where the axis stands, which its following-error limit allows (a jump
  // to a far position, as this bench once sent, ends in alarm 2009 and a quick stop). After
  // the measured cycles the axis holds, commanded until the run stops (10 s at most): a
  // silence before the stop would be alarm 2001.
  const double counts = axis.counts_per_unit;
  const std::uint64_t last = total + 10'000'000 / static_cast<std::uint64_t>(machine.cycle_us);
  for (std::uint64_t cycle = 0; cycle < last; ++cycle) {
    clock::sleep_until_ns(start_ns + static_cast<std::int64_t>(cycle) * cycle_ns);
    if (cycle >= total && node.run_control().command != RUN_START) {
      break;
    }
    for (std::size_t k = 0; k < channel.axes.size(); ++k) {
      const config::AxisConfig& a = *machine.find_axis(channel.axes[k]);
      AxisSetpoint sp;
      sp.axis(static_cast<std::uint32_t>(a.id));
      sp.channel(static_cast<std::uint32_t>(channel.id));
      sp.cycle(cycle);
      sp.valid(true);
      sp.pos(a.id == axis.id ? static_cast<double>(std::min(cycle, total - 1)) / counts : 0.0);
      if (a.id == axis.id && cycle < total) {
        published[cycle] = clock::monotonic_ns();
      }
      setpoints[k]->write(sp);
    }
  }
  finish_listening();

  std::vector<double> latency_us;
  std::size_t lost = 0;
  for (std::uint64_t k = kWarmupCycles; k < total; ++k) {
    if (received[k] == 0 || published[k] == 0) {
      ++lost;
      continue;
    }
    latency_us.push_back(static_cast<double>(received[k] - published[k]) / 1000.0);
  }
  if (latency_us.empty()) {
    std::fprintf(stderr, "no RPDO matched a setpoint\n");
    return 1;
  }
  std::sort(latency_us.begin(), latency_us.end());
  auto pct = [&](double p) {
    return latency_us[std::min(
        latency_us.size() - 1,
        static_cast<std::size_t>(p * static_cast<double>(latency_us.size())))];
  };
  std::printf(
      "setpoint -> RPDO latency over %zu cycles of %d us (%zu setpoints never reached the bus):\n",
      latency_us.size(), machine.cycle_us, lost);
  std::printf("  min %.1f us  median %.1f us  p90 %.1f us  p99 %.1f us  max %.1f us\n",
              latency_us.front(), pct(0.5), pct(0.9), pct(0.99), latency_us.back());
  // Before the participant's teardown, which on a secured Cyclone DDS participant may hang.
  std::fflush(stdout);
  return 0;
}

// Waits up to `limit` for `child` to exit, then stops it: SIGTERM, and SIGKILL 2 s later.
void end_child(launch::ChildProcess& child, std::chrono::milliseconds limit) {
  const auto exits_within = [&](std::chrono::milliseconds wait) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    while (!child.poll_exited()) {
      if (std::chrono::steady_clock::now() >= deadline) {
        return false;
      }
      std::this_thread::sleep_for(10ms);
    }
    return true;
  };
  if (exits_within(limit)) {
    return;
  }
  child.signal(SIGTERM);
  if (!exits_within(2s)) {
    child.signal(SIGKILL);
    (void)exits_within(1s);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"setpoint latency: channel publish -> RPDO at the drive (realtime clock)"};
  std::string machine_path;
  int cycles = 10000;
  bool channel_part = false;
  app.add_option("machine", machine_path, "machine file")->required();
  app.add_option("--cycles", cycles, "cycles to measure");
  app.add_flag("--channel-part", channel_part,
               "be the channel's part, a process this bench starts");
  // Across hosts (bench/hosts_setpoint_latency.py): the drive simulator and axis nodes start on
  // another host, and the bus is listened to from inside that host's network namespace, so
  // that both times stay on the channel's part's clock.
  std::string nodes_prefix;
  std::string bus_netns;
  app.add_option("--nodes-prefix", nodes_prefix,
                 "a command (words separated by spaces) that the drive simulator's and the axis "
                 "nodes' command lines are run under, e.g. one that enters another host");
  app.add_option("--bus-netns", bus_netns,
                 "the network namespace (a path) whose CAN bus the RPDOs are listened for on");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = config::load_machine_file(machine_path);
  const config::ChannelConfig& channel = machine.channels.at(0);
  const config::AxisConfig& axis = *machine.find_axis(channel.axes.at(0));
  const config::BusConfig& bus = *machine.find_bus(axis.bus);
  const int domain = process::resolve_domain(machine);
  if (channel_part) {
    return play_channel(machine, domain, cycles, bus_netns);
  }
  const std::string bin = launch::executable_dir();
  // On Cyclone DDS the cyclic samples go through the host's RouDi: this one, or one started
  // (for the axis nodes and the channel's part).
  std::optional<launch::HostRoudi> roudi;
  if (launch::needs_roudi(machine, false)) {
    roudi.emplace(machine.axes.size() + 1, false);
  }

  std::vector<std::string> prefix;
  {
    std::istringstream words(nodes_prefix);
    for (std::string w; words >> w;) {
      prefix.push_back(w);
    }
  }
  const auto under_prefix = [&](std::vector<std::string> argv) {
    argv.insert(argv.begin(), prefix.begin(), prefix.end());
    return argv;
  };
  std::vector<launch::ChildProcess> children;
  children.emplace_back(
      "sim", under_prefix({bin + "/mcnc-drivesim", "--machine", machine_path, "--bus", bus.name,
                           "--clock", "realtime", "--log-level", "warn"}));
  for (const auto& a : machine.axes) {
    children.emplace_back(
        a.name, under_prefix({bin + "/mcnc-axisnode", "--machine", machine_path, "--axis", a.name,
                              "--clock", "realtime", "--log-level", "warn"}));
  }
  std::vector<std::string> channel_argv{bin + "/mcnc_bench_setpoint_latency", machine_path,
                                        "--cycles", std::to_string(cycles), "--channel-part"};
  if (!bus_netns.empty()) {
    channel_argv.insert(channel_argv.end(), {"--bus-netns", bus_netns});
  }
  launch::ChildProcess channel_process(channel.name, channel_argv);
  const std::vector<std::string> env{"MCNC_DOMAIN=" + std::to_string(domain)};
  for (auto& c : children) {
    c.start(env);
  }
  channel_process.start(env);

  // The launcher's part: an onlooker off shared memory, with the launcher's identity.
  process::ProcessNode node(
      domain, "launch", dds::CyclicClock::realtime, process::resolve_middleware(machine, "launch"),
      dds::LocalTransport::network, process::resolve_security_or_exit(machine, "launch"));
  std::mutex mutex;
  std::map<std::string, ProcessPhase> phases;
  dds::Reader<ProcessState> states(node.participant(),
                                   [&](const ProcessState& s, const dds::WriterId&) {
                                     std::lock_guard<std::mutex> lock(mutex);
                                     phases[s.name()] = s.phase();
                                   });
  dds::Writer<RunControl> control(node.participant());
  const auto ready = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& a : machine.axes) {
      if (phases[a.name] != PHASE_READY) {
        return false;
      }
    }
    return phases[channel.name] == PHASE_READY;
  };
  for (int i = 0; i < 3000 && !ready() && !channel_process.poll_exited(); ++i) {
    std::this_thread::sleep_for(10ms);
  }
  if (!ready()) {
    std::fprintf(stderr, "the axis nodes and the channel's part did not come up\n");
    return 1;
  }
  // Time for the run control to reach every part (secured: their handshakes with the
  // launcher's part may still go on).
  const std::int64_t start_ns = clock::monotonic_ns() + 2'000'000'000;
  const std::int64_t cycle_ns = static_cast<std::int64_t>(machine.cycle_us) * 1000;
  const std::int64_t stop_ns =
      start_ns + static_cast<std::int64_t>(cycles + kWarmupCycles) * cycle_ns + 100'000'000;
  RunControl rc;
  rc.generation(1);
  rc.command(RUN_START);
  rc.clock(REALTIME_CLOCK);
  rc.start_ns(start_ns);
  control.write(rc);
  clock::sleep_until_ns(stop_ns);
  rc.generation(2);
  rc.command(RUN_STOP);
  control.write(rc);

  // The channel's part prints the figures once the stop reached it; then the processes go,
  // and RouDi after them.
  end_child(channel_process, 15s);
  for (auto& c : children) {
    end_child(c, 1s);
  }
  process::remove_stale_dds_shm_files();
  return channel_process.exit_code() == 0 ? 0 : 1;
}
