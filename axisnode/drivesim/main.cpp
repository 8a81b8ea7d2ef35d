// mcnc-drivesim: the simulated CiA 402 drives of one CAN bus of a machine. Process shell only:
// parse the command line, load the machine file, open the bus, pump frames through the
// DriveBusSimulator until SIGTERM/SIGINT.
#include "axisnode/drivesim/drive_bus_simulator.hpp"
#include "axisnode/drivesim/launcher_loss.hpp"
#include "canopen/bus_filters.hpp"
#include "canopen/sdo_abort.hpp"
#include "common/can/can_bus.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/machine_config.hpp"
#include "common/log/logging.hpp"
#include "common/process/startup.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace {

const char* result_name(mcnc::can::BusResult result) {
  switch (result) {
    case mcnc::can::BusResult::ok:
      return "ok";
    case mcnc::can::BusResult::timeout:
      return "timeout";
    case mcnc::can::BusResult::malformed:
      return "malformed";
    case mcnc::can::BusResult::error:
      return "error";
    case mcnc::can::BusResult::bus_off:
      return "bus off";
  }
  return "?";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mcnc;

  CLI::App app{"mcnc-drivesim: simulated CiA 402 drives of one CAN bus"};
  process::ShellOptions shell;
  std::string bus_name;
  // --clock lockstep also holds each SYNC until the RPDOs of its cycle are in (UDP does not
  // order senders the way a bus does).
  process::add_shell_options(app, shell);
  app.add_option("--bus", bus_name, "name of the bus to simulate (buses[].name)")->required();
  std::vector<std::string> refusals;
  std::vector<std::string> faults;
  app.add_option("--fault", faults,
                 "fault injection: NODE:KIND@SYNC, KIND overcurrent (EMCY 0x2310), "
                 "following_error (EMCY 0x8611) or heartbeat_stop, at the drive's SYNC number");
  app.add_option("--refuse-sdo", refusals,
                 "fault injection: NODE:INDEX, the drive refuses every SDO access to that object "
                 "(abort 0x08000022), e.g. 1:0x6060");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  const config::BusConfig* bus_config = machine.find_bus(bus_name);
  if (bus_config == nullptr) {
    std::fprintf(stderr, "mcnc-drivesim: %s: no bus named \"%s\"\n", shell.machine_path.c_str(),
                 bus_name.c_str());
    return 2;
  }

  std::vector<drivesim::DriveParams> drives;
  for (const config::AxisConfig& axis : machine.axes) {
    if (axis.bus != bus_name) {
      continue;
    }
    if (axis.node_id < 1 || axis.node_id > 127) {
      std::fprintf(stderr, "mcnc-drivesim: axis %s: node_id %d outside 1..127\n", axis.name.c_str(),
                   axis.node_id);
      return 2;
    }
    drivesim::DriveParams params;
    params.node_id = static_cast<std::uint8_t>(axis.node_id);
    params.counts_per_unit = axis.counts_per_unit;
    params.time_constant_s = axis.drive.time_constant_s;
    params.max_velocity = axis.drive.max_velocity;
    params.quick_stop_decel = axis.drive.quick_stop_decel;
    params.units_per_rev = axis.drive.units_per_rev;
    params.inertia = axis.drive.inertia;
    params.friction = axis.drive.friction;
    params.torque_limit = axis.drive.torque_limit;
    params.rated_torque = axis.drive.rated_torque;
    params.velocity_bandwidth_hz = axis.drive.velocity_bandwidth_hz;
    params.probe_side = axis.drive.probe_side;
    params.probe_at = axis.drive.probe_at;
    params.probe_pitch = axis.drive.probe_pitch;
    params.probe_width = axis.drive.probe_width;
    params.probe_count = axis.drive.probe_count;
    params.contact_side = axis.drive.contact_side;
    params.contact_at = axis.drive.contact_at;
    for (const config::DriveObjectDefault& o : axis.drive.objects) {
      params.objects[params.object_count++] = drivesim::ObjectDefault{
          static_cast<std::uint16_t>(o.index), static_cast<std::uint8_t>(o.sub), o.value};
    }
    // The defaults must fit the drive's dictionary: a wrong one is a machine-file error.
    drivesim::SimulatedDrive probe(params, machine.cycle_s());
    drivesim::ObjectDefault failed;
    if (const std::uint32_t code = probe.apply_defaults(&failed)) {
      std::fprintf(stderr,
                   "mcnc-drivesim: axis %s: drive.objects 0x%04X:%02X = %lld was refused: %s\n",
                   axis.name.c_str(), failed.index, failed.sub,
                   static_cast<long long>(failed.value), canopen::sdo_abort_text(code));
      return 2;
    }
    drives.push_back(params);
  }

  process::start_process("drivesim-" + bus_name, shell, process::WhenLauncherDies::outlive);
  const bool lockstep = shell.clock == "lockstep";
  if (!lockstep) {
    // The simulator stands for the drives' own hardware, which no host's load delays: its frame
    // loop runs with the axis nodes' cycles, above the machine's other threads (decision 55).
    (void)clock::raise_realtime_thread(clock::kAxisCyclePriority);
  }

  try {
    drivesim::DriveBusSimulator simulator(drives, machine.cycle_s());
    for (const std::string& refusal : refusals) {
      const auto colon = refusal.find(':');
      unsigned long node = 0;
      unsigned long index = 0;
      try {
        node = std::stoul(refusal.substr(0, colon));
        index = std::stoul(refusal.substr(colon + 1), nullptr, 0);
      } catch (const std::exception&) {
        node = 0;
      }
      if (colon == std::string::npos || node > 127 || index > 0xFFFF ||
          !simulator.refuse_sdo(static_cast<std::uint8_t>(node),
                                static_cast<std::uint16_t>(index))) {
        std::fprintf(stderr, "mcnc-drivesim: --refuse-sdo %s: want NODE:INDEX of a drive on %s\n",
                     refusal.c_str(), bus_name.c_str());
        return 2;
      }
      spdlog::info("fault injection: node {} refuses SDO access to 0x{:04X}", node, index);
    }
    for (const std::string& spec : faults) {
      const auto colon = spec.find(':');
      const auto at = spec.find('@');
      unsigned long node = 0;
      unsigned long long sync = 0;
      drivesim::DriveFault fault = drivesim::DriveFault::none;
      if (colon != std::string::npos && at != std::string::npos && at > colon) {
        const std::string kind = spec.substr(colon + 1, at - colon - 1);
        fault = kind == "overcurrent"       ? drivesim::DriveFault::overcurrent
                : kind == "following_error" ? drivesim::DriveFault::following_error
                : kind == "heartbeat_stop"  ? drivesim::DriveFault::heartbeat_stop
                                            : drivesim::DriveFault::none;
        try {
          node = std::stoul(spec.substr(0, colon));
          sync = std::stoull(spec.substr(at + 1));
        } catch (const std::exception&) {
          fault = drivesim::DriveFault::none;
        }
      }
      if (fault == drivesim::DriveFault::none || node > 127 || sync == 0 ||
          !simulator.schedule_fault(static_cast<std::uint8_t>(node), fault, sync)) {
        std::fprintf(stderr,
                     "mcnc-drivesim: --fault %s: want NODE:KIND@SYNC, KIND overcurrent, "
                     "following_error or heartbeat_stop, for a drive on %s\n",
                     spec.c_str(), bus_name.c_str());
        return 2;
      }
      spdlog::info("fault injection: node {} has {} at SYNC {}", node, spec.substr(colon + 1),
                   sync);
    }
    std::unique_ptr<can::CanBus> bus = can::open_can_bus(bus_config->uri);
    {
      // Only what the drives need reaches the simulator (in the kernel on SocketCAN).
      std::vector<std::uint8_t> nodes;
      for (const drivesim::DriveParams& d : drives) {
        nodes.push_back(d.node_id);
      }
      std::array<can::CanFilter, can::kMaxFilters> filters{};
      const std::size_t n = canopen::device_filters(nodes, filters);
      if (!bus->set_filters(std::span(filters.data(), n))) {
        spdlog::warn("the bus refused the receive filter; receiving every frame");
      }
    }
    spdlog::info("{} drive(s) on {} ({}), cycle {} us", drives.size(), bus_name, bus_config->uri,
                 machine.cycle_us);

    // One TPDO per drive per SYNC at most; sized once so the loop does not allocate.
    std::vector<canopen::CanFrame> out(
        drives.size() * drivesim::DriveBusSimulator::kFramesPerDrive + 1);
    unsigned long send_failures = 0;
    const auto send_all = [&](std::size_t count) {
      for (std::size_t i = 0; i < count; ++i) {
        if (bus->send(out[i]) != can::BusResult::ok && send_failures++ == 0) {
          spdlog::warn("sending a frame failed (further failures counted, not logged)");
        }
      }
    };
    send_all(simulator.power_on(out));

    unsigned long bus_malformed_logged = 0;
    unsigned long sim_malformed_logged = 0;
    // Lockstep: a SYNC waits here until the RPDOs of its cycle are in (see rpdos_complete()).
    std::optional<canopen::CanFrame> held_sync;
    auto held_since = std::chrono::steady_clock::now();
    const auto release_held_sync = [&] {
      send_all(simulator.handle(*held_sync, out));
      held_sync.reset();
    };
    drivesim::LauncherLoss launcher_loss(std::chrono::seconds(1), std::chrono::seconds(20));
    while (process::g_stop_signal == 0) {
      canopen::CanFrame frame;
      const can::BusResult result =
          bus->receive(frame, std::chrono::milliseconds(held_sync ? 10 : 100));
      if (launcher_loss.leave(std::chrono::steady_clock::now(), process::launcher_gone(),
                              result == can::BusResult::ok)) {
        spdlog::warn("the launcher is gone and the bus's masters are quiet: leaving");
        break;
      }
      send_all(simulator.heartbeats_out_of_operation(
          static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                         std::chrono::steady_clock::now().time_since_epoch())
                                         .count()),
          out));
      if (held_sync &&
          std::chrono::steady_clock::now() - held_since > std::chrono::milliseconds(500)) {
        simulator.stop_awaiting_silent_drives();
        spdlog::warn("lockstep: a node stopped sending RPDOs; no longer waiting for it");
        release_held_sync();
      }
      if (result == can::BusResult::ok) {
        const bool is_sync = canopen::classify(frame).kind == canopen::FrameKind::sync;
        if (held_sync && is_sync) {
          release_held_sync();  // a second SYNC: the held one's cycle is over
        }
        if (lockstep && is_sync && !simulator.rpdos_complete()) {
          held_sync = frame;
          held_since = std::chrono::steady_clock::now();
          continue;
        }
        send_all(simulator.handle(frame, out));
        if (held_sync && simulator.rpdos_complete()) {
          release_held_sync();
        }
        if (simulator.malformed_count() != sim_malformed_logged) {
          sim_malformed_logged = simulator.malformed_count();
          spdlog::debug("dropped malformed CANopen frame id 0x{:03X} dlc {} ({} so far)", frame.id,
                        frame.dlc, sim_malformed_logged);
        }
      } else if (result == can::BusResult::malformed) {
        if (bus_malformed_logged++ == 0) {
          spdlog::warn("dropped a malformed datagram (further ones counted)");
        }
      } else if (result == can::BusResult::error) {
        spdlog::warn("bus receive: {} (frame id 0x{:08X})", result_name(result), frame.id);
      }
    }
    spdlog::info("stopping: {} malformed datagram(s), {} malformed frame(s), {} send failure(s)",
                 bus->malformed_count(), simulator.malformed_count(), send_failures);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
