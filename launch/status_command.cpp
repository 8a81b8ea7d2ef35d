#include "launch/status_command.hpp"

#include "common/config/cyclic_routes.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "idl/dds_participant.hpp"
#include "tools/status/status_lines.hpp"
#include "tools/status/wire/status_wire.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

namespace mcnc::launch {

void add_status_options(CLI::App& app, StatusArguments& args) {
  app.add_option("machine", args.machine_path, "machine file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--wait-ms", args.wait_ms,
                 "wait this long for every channel and axis to be heard (default 3000)")
      ->check(CLI::Range(1, 600000));
  app.add_flag("--watch", args.watch, "print again every --every-ms until interrupted");
  app.add_option("--every-ms", args.every_ms, "with --watch: how often (default 500)")
      ->check(CLI::Range(50, 60000));
}

int execute_status(const StatusArguments& args) {
  const config::MachineConfig machine = process::load_machine_or_exit(args.machine_path);
  process::install_stop_signals();
  // It only looks on: on a secured machine, as the viewer, which may write nothing.
  dds::Participant participant(
      process::resolve_domain(machine), "status", dds::CyclicClock::realtime,
      process::resolve_middleware(machine, "status"), dds::LocalTransport::network,
      process::resolve_security_or_exit(machine, security::kViewerIdentity));
  std::mutex mutex;
  status::StatusSnapshot snapshot;
  dds::Reader<::mcnc::ChannelStatus> channels(
      participant, dds::Keys::of(config::channel_names(machine)),
      [&](const ::mcnc::ChannelStatus& s, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex);
        snapshot.channels[s.channel()] = status::view_of(s);
      });
  dds::Reader<AxisFeedback> axes(participant, dds::Keys::of(config::node_keys(machine)),
                                 [&](const AxisFeedback& f, const dds::WriterId&) {
                                   std::lock_guard<std::mutex> lock(mutex);
                                   snapshot.axes[f.axis()] = status::view_of(f);
                                 });
  dds::Reader<HostClock> host_clocks(participant, [&](const HostClock& hc, const dds::WriterId&) {
    std::lock_guard<std::mutex> lock(mutex);
    snapshot.host_clocks[hc.host()] =
        status::HostClockView{hc.offset_ns(), hc.error_ns(), hc.samples()};
  });
  const auto copy = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return snapshot;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(args.wait_ms);
  // Each host's clock too, when the machine has hosts: the launchers are discovered apart
  // from the channels and axes, and one may be heard later.
  const auto clocks_missing = [&] {
    const status::StatusSnapshot now = copy();
    return std::any_of(machine.hosts.begin(), machine.hosts.end(),
                       [&](const auto& h) { return now.host_clocks.count(h.name) == 0; });
  };
  while ((!status::missing(machine, copy()).empty() || clocks_missing()) &&
         std::chrono::steady_clock::now() < deadline && process::g_stop_signal == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (;;) {
    const status::StatusSnapshot now = copy();
    for (const std::string& line : status::status_lines(machine, now)) {
      std::printf("%s\n", line.c_str());
    }
    const std::vector<std::string> absent = status::missing(machine, now);
    if (!args.watch || process::g_stop_signal != 0) {
      if (!absent.empty()) {
        std::fprintf(stderr,
                     "no status from %zu of %zu channels and axes (domain %d): is %s running?\n",
                     absent.size(), machine.channels.size() + machine.axes.size(),
                     process::resolve_domain(machine), machine.name.c_str());
        return 1;
      }
      return 0;
    }
    std::printf("\n");
    std::fflush(stdout);
    const auto next = std::chrono::steady_clock::now() + std::chrono::milliseconds(args.every_ms);
    while (std::chrono::steady_clock::now() < next && process::g_stop_signal == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
}

}  // namespace mcnc::launch
