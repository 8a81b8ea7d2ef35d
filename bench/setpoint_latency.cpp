// Setpoint latency, channel publish -> drive receipt of the RPDO, in the realtime clock.
// This program plays the channel: it starts the real drive simulator and axis nodes of a
// machine, publishes one AxisSetpoint per cycle for the first axis of the first channel whose
// position encodes the cycle number, and listens on the CAN bus for the axis node's RPDOs. The
// latency of cycle k is (RPDO with target k received) - (setpoint k written). It includes the
// designed one-cycle delay (a setpoint stamped N is applied at N+1).
// The launcher's part, the run control, is a second process of this program (--run-control):
// on a secured machine (security_dir) each plays with its own identity, since only the
// launcher's may write run control and one process holds one identity on a domain.
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

// The launcher's part: RUN_START now for `start_ns`, RUN_STOP at `stop_ns` (CLOCK_MONOTONIC,
// one clock on one host). Run control is reliable and transient-local: an axis node that
// authenticates late still gets the start.
int send_run_control(const config::MachineConfig& machine, int domain, std::int64_t start_ns,
                     std::int64_t stop_ns) {
  process::ProcessNode node(
      domain, "launch", dds::CyclicClock::realtime, process::resolve_middleware(machine, "launch"),
      dds::LocalTransport::network, process::resolve_security_or_exit(machine, "launch"));
  dds::Writer<RunControl> control(node.participant());
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
  std::this_thread::sleep_for(500ms);  // delivered before the participant goes
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"setpoint latency: channel publish -> RPDO at the drive (realtime clock)"};
  std::string machine_path;
  int cycles = 10000;
  std::vector<std::int64_t> run_control;
  app.add_option("machine", machine_path, "machine file")->required();
  app.add_option("--cycles", cycles, "cycles to measure");
  app.add_option("--run-control", run_control,
                 "START_NS STOP_NS: be the launcher's part, the second process of this bench")
      ->expected(2);
  // Across hosts (bench/hosts_setpoint_latency.py): the drive simulator and axis nodes start on
  // another host, and the bus is listened to from inside that host's network namespace, so
  // that both times stay on this process's clock.
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
  if (run_control.size() == 2) {
    return send_run_control(machine, domain, run_control[0], run_control[1]);
  }
  const std::string bin = launch::executable_dir();
  // On Cyclone DDS the cyclic samples go through the host's RouDi: this one, or one started.
  std::optional<launch::HostRoudi> roudi;
  if (launch::needs_roudi(machine, false)) {
    roudi.emplace(machine.axes.size() + 2, false);
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
  const std::vector<std::string> env{"MCNC_DOMAIN=" + std::to_string(domain)};
  for (auto& c : children) {
    c.start(env);
  }

  clock::prepare_realtime_process();
  process::ProcessNode node(domain, channel.name, dds::CyclicClock::realtime,
                            process::resolve_middleware(machine, channel.name),
                            dds::LocalTransport::shared_memory,
                            process::resolve_security_or_exit(machine, channel.name));
  std::mutex mutex;
  std::map<std::string, ProcessPhase> phases;
  dds::Reader<ProcessState> states(node.participant(),
                                   [&](const ProcessState& s, const dds::WriterId&) {
                                     std::lock_guard<std::mutex> lock(mutex);
                                     phases[s.name()] = s.phase();
                                   });
  // One setpoint writer per axis, in its partition, as the channel has.
  std::vector<std::unique_ptr<dds::Writer<AxisSetpoint>>> setpoints;
  for (const auto& name : channel.axes) {
    setpoints.push_back(std::make_unique<dds::Writer<AxisSetpoint>>(node.participant(), name));
  }
  dds::Reader<AxisFeedback> feedback(node.participant(), dds::Keys::of(channel.axes),
                                     [](const AxisFeedback&, const dds::WriterId&) {});

  // Receive RPDOs on the bus: target counts -> receive time.
  const std::int64_t cycle_ns = static_cast<std::int64_t>(machine.cycle_us) * 1000;
  const int warmup = 500;
  std::vector<std::int64_t> published(static_cast<std::size_t>(cycles + warmup + 10), 0);
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

  while (!listening) {
    std::this_thread::sleep_for(1ms);
  }
  const auto ready = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& a : machine.axes) {
      if (phases[a.name] != PHASE_READY) {
        return false;
      }
    }
    return true;
  };
  for (int i = 0; i < 3000 && !ready(); ++i) {
    std::this_thread::sleep_for(10ms);
  }
  if (!ready()) {
    std::fprintf(stderr, "axis nodes did not come up\n");
    return 1;
  }
  // Time for the launcher's part to start and (secured) authenticate with the axis nodes.
  const std::int64_t start_ns = clock::monotonic_ns() + 2'000'000'000;
  const std::uint64_t total_cycles = static_cast<std::uint64_t>(cycles + warmup);
  const std::int64_t stop_ns =
      start_ns + static_cast<std::int64_t>(total_cycles) * cycle_ns + 100'000'000;
  children.emplace_back(
      "launch",
      std::vector<std::string>{bin + "/mcnc_bench_setpoint_latency", machine_path, "--run-control",
                               std::to_string(start_ns), std::to_string(stop_ns)});
  children.back().start(env);

  // Setpoint k carries position k counts, so the RPDO target identifies it: a creep of one
  // count a cycle from where the axis stands, which its following-error limit allows (a jump
  // to a far position, as this bench once sent, ends in alarm 2009 and a quick stop).
  const double counts = axis.counts_per_unit;
  const std::uint64_t total = total_cycles;
  for (std::uint64_t cycle = 0; cycle < total; ++cycle) {
    clock::sleep_until_ns(start_ns + static_cast<std::int64_t>(cycle) * cycle_ns);
    for (std::size_t k = 0; k < channel.axes.size(); ++k) {
      const config::AxisConfig& a = *machine.find_axis(channel.axes[k]);
      AxisSetpoint sp;
      sp.axis(static_cast<std::uint32_t>(a.id));
      sp.channel(static_cast<std::uint32_t>(channel.id));
      sp.cycle(cycle);
      sp.valid(true);
      sp.pos(a.id == axis.id ? static_cast<double>(cycle) / counts : 0.0);
      if (a.id == axis.id) {
        published[cycle] = clock::monotonic_ns();
      }
      setpoints[k]->write(sp);
    }
  }
  clock::sleep_until_ns(stop_ns);  // the launcher's part stops the run
  stop = true;
  listener.join();
  for (auto& c : children) {
    for (int i = 0; i < 300 && !c.poll_exited(); ++i) {
      if (i == 100) {
        c.signal(SIGTERM);
      }
      std::this_thread::sleep_for(10ms);
    }
  }
  process::remove_stale_dds_shm_files();

  std::vector<double> latency_us;
  std::size_t lost = 0;
  for (std::uint64_t k = warmup; k < total; ++k) {
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
  return 0;
}
