#include "launch/launch_plan.hpp"

#include <algorithm>

namespace mcnc::launch {

std::string trace_part(const std::string& parts_dir, const std::string& name) {
  return parts_dir + "/" + name + ".jsonl";
}

LaunchPlan launch_plan(const config::MachineConfig& machine, const LaunchOptions& options,
                       const std::string& parts_dir, const std::string& host) {
  LaunchPlan plan;
  const std::string bin = options.bin_dir.empty() ? std::string(".") : options.bin_dir;
  // On a machine of several hosts, what this host runs; else everything.
  auto here = [&](const std::string& process) {
    if (host.empty()) {
      return true;
    }
    const config::HostConfig* h = machine.host_of(process);
    return h != nullptr && h->name == host;
  };
  auto with_common = [&](std::vector<std::string> args) {
    args.emplace_back("--clock");
    args.emplace_back(options.clock == LOCKSTEP_CLOCK ? "lockstep" : "realtime");
    if (!options.log_level.empty()) {
      args.emplace_back("--log-level");
      args.push_back(options.log_level);
    }
    return args;
  };
  auto part = [&](const std::string& name) { return trace_part(parts_dir, name); };
  std::vector<std::string> channel_parts;
  std::vector<std::string> other_parts;

  for (const auto& bus : machine.buses) {
    if (!here(bus.name)) {
      continue;
    }
    std::vector<std::string> args{bin + "/mcnc-drivesim", "--machine", options.machine_path,
                                  "--bus", bus.name};
    if (const auto extra = options.drivesim_args.find(bus.name);
        extra != options.drivesim_args.end()) {
      args.insert(args.end(), extra->second.begin(), extra->second.end());
    }
    plan.children.push_back(ChildSpec{"drivesim-" + bus.name, with_common(args)});
  }
  for (const auto& axis : machine.axes) {
    plan.dds_processes.push_back(axis.name);
    if (!here(axis.name)) {
      continue;
    }
    std::vector<std::string> args{bin + "/mcnc-axisnode", "--machine", options.machine_path,
                                  "--axis", axis.name};
    if (!parts_dir.empty()) {
      args.insert(args.end(), {"--trace", part(axis.name), "--trace-pos-every",
                               std::to_string(options.trace_pos_every)});
      other_parts.push_back(part(axis.name));
    }
    plan.children.push_back(ChildSpec{axis.name, with_common(args)});
  }
  for (const auto& ch : machine.channels) {
    plan.dds_processes.push_back(ch.name);
    if (!here(ch.name)) {
      continue;
    }
    std::vector<std::string> args{bin + "/mcnc-channel", "--machine", options.machine_path,
                                  "--channel", ch.name};
    if (auto it = options.programs.find(ch.name); it != options.programs.end()) {
      args.insert(args.end(), {"--program", it->second});
    }
    if (!options.retained_file.empty()) {
      args.insert(args.end(), {"--retained", options.retained_file});
    }
    if (!options.program_dir.empty()) {
      args.insert(args.end(), {"--progdir", options.program_dir});
    }
    if (options.manual_start) {
      args.emplace_back("--manual-start");
    }
    if (!parts_dir.empty()) {
      args.insert(args.end(), {"--trace", part(ch.name)});
      channel_parts.push_back(part(ch.name));
    }
    plan.children.push_back(ChildSpec{ch.name, with_common(args)});
  }
  if (machine.plc.present) {
    plan.dds_processes.emplace_back("PLC");
    if (here("plc")) {
      std::vector<std::string> args{bin + "/mcnc-plcnode", "--machine", options.machine_path};
      if (!parts_dir.empty()) {
        args.insert(args.end(), {"--trace", part("PLC")});
        other_parts.push_back(part("PLC"));
      }
      plan.children.push_back(ChildSpec{"PLC", with_common(args)});
    }
  }
  if (!options.hmi_listen.empty() && here(kHmiName)) {
    std::vector<std::string> args{bin + "/mcnc-hmi", "--machine", options.machine_path, "--listen",
                                  options.hmi_listen};
    for (const auto& [channel, file] : options.programs) {
      args.insert(args.end(), {"--program", channel + "=" + file});
    }
    if (!options.program_dir.empty()) {
      args.insert(args.end(), {"--progdir", options.program_dir});
    }
    if (!options.log_level.empty()) {
      args.insert(args.end(), {"--log-level", options.log_level});
    }
    plan.children.push_back(ChildSpec{kHmiName, args});
  }
  plan.trace_parts = channel_parts;
  plan.trace_parts.insert(plan.trace_parts.end(), other_parts.begin(), other_parts.end());
  return plan;
}

std::vector<std::vector<std::size_t>> start_waves(const LaunchPlan& plan, bool secured) {
  std::vector<std::vector<std::size_t>> waves(1);
  const bool staggered = secured && plan.dds_processes.size() > kUnstaggeredDdsProcesses;
  std::size_t in_wave = 0;  // DDS processes in the last wave
  for (std::size_t i = 0; i < plan.children.size(); ++i) {
    const bool dds = std::find(plan.dds_processes.begin(), plan.dds_processes.end(),
                               plan.children[i].name) != plan.dds_processes.end();
    if (staggered && dds && in_wave == kStartWave) {
      waves.emplace_back();
      in_wave = 0;
    }
    // A child without DDS joins the first wave: it waits for no handshake.
    (dds ? waves.back() : waves.front()).push_back(i);
    in_wave += dds ? 1 : 0;
  }
  return waves;
}

}  // namespace mcnc::launch
