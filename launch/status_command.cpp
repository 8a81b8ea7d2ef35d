#include "launch/status_command.hpp"

#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "idl/dds_participant.hpp"
#include "tools/status/status_lines.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

namespace mcnc::launch {
namespace {

status::ChannelView view_of(const ::mcnc::ChannelStatus& s) {
  status::ChannelView v;
  v.state = static_cast<channel::ChannelState>(static_cast<int>(s.state()));
  v.block = s.block();
  v.block_total = s.block_total();
  v.line = s.line();
  v.alarms = s.alarms();
  v.program_end = s.program_end();
  v.sync_p = s.sync_p();
  v.sync_waiting_for = s.sync_waiting_for();
  v.call_caller = s.call_caller();
  return v;
}

status::AxisView view_of(const AxisFeedback& f) {
  status::AxisView v;
  v.cmd = f.cmd();
  v.act = f.act();
  v.vel = f.vel();
  v.following_error = f.following_error();
  v.enabled = f.enabled();
  v.alarm = f.alarm();
  v.owner = f.owner();
  v.released_by = f.released_by();
  v.coupled_to = f.coupled_to();
  v.coupling_locked = f.coupling_locked();
  v.mode_display = f.mode_display();
  return v;
}

}  // namespace

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
  dds::Participant participant(process::resolve_domain(machine), "status");
  std::mutex mutex;
  status::StatusSnapshot snapshot;
  dds::Reader<::mcnc::ChannelStatus> channels(
      participant, [&](const ::mcnc::ChannelStatus& s, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex);
        snapshot.channels[s.channel()] = view_of(s);
      });
  dds::Reader<AxisFeedback> axes(participant, [&](const AxisFeedback& f, const dds::WriterId&) {
    std::lock_guard<std::mutex> lock(mutex);
    snapshot.axes[f.axis()] = view_of(f);
  });
  const auto copy = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return snapshot;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(args.wait_ms);
  while (!status::missing(machine, copy()).empty() && std::chrono::steady_clock::now() < deadline &&
         process::g_stop_signal == 0) {
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
