// mcnc-axisnode: one axis or spindle. DDS on one side (setpoints from the channels that may
// own it, their events, operator commands, feedback out), CAN on the other (a CiA 402 drive in
// cyclic synchronous position, velocity for a spindle, homing at start-up). Wiring only: the
// behaviour is in AxisNode (axisnode/node/), the DDS adapters in axisnode/wire/ and the drive's
// link in DriveLink.
#include "axisnode/link/core_exchange.hpp"
#include "axisnode/link/drive_link.hpp"
#include "axisnode/node/axis_node.hpp"
#include "axisnode/node/drive_stop.hpp"
#include "axisnode/setup/axis_node_setup.hpp"
#include "axisnode/wire/axis_inputs.hpp"
#include "axisnode/wire/axis_outputs.hpp"
#include "axisnode/wire/input_wait_log.hpp"
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>

using namespace std::chrono_literals;
using namespace mcnc;

int main(int argc, char** argv) {
  CLI::App app{"mcnc axis node: one axis, CiA 402 drive over CAN, setpoints over DDS"};
  process::ShellOptions shell;
  std::string axis_name;
  std::string trace_path;
  int trace_pos_every = 10;
  int stall_ms = 2000;
  process::add_shell_options(app, shell);
  app.add_option("--axis", axis_name, "axis name from the machine file")->required();
  app.add_option("--trace", trace_path, "write this process's trace events to FILE");
  app.add_option("--trace-pos-every", trace_pos_every, "pos event every K cycles")
      ->check(CLI::PositiveNumber);
  app.add_option("--lockstep-stall-ms", stall_ms,
                 "lockstep: warn when the bus or the inputs keep a cycle waiting this long");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  const config::AxisConfig* axis = machine.find_axis(axis_name);
  if (axis == nullptr) {
    std::fprintf(stderr, "error: axis %s is not in machine file %s\n", axis_name.c_str(),
                 shell.machine_path.c_str());
    return 2;
  }
  if (!axis->spindle.empty()) {
    std::fprintf(stderr, "error: %s is spindle %s's C axis: the spindle's node drives it\n",
                 axis_name.c_str(), axis->spindle.c_str());
    return 2;
  }
  const config::BusConfig* bus = machine.find_bus(axis->bus);
  process::start_process(axis->name, shell);
  process::require_roudi_or_exit(machine, axis->name);
  std::optional<security::IdentityFiles> identity =
      process::resolve_security_or_exit(machine, axis->name);

  const bool sync_producer = bus->sync_producer == axis->name;
  const auto node_id = static_cast<std::uint8_t>(axis->node_id);

  try {
    process::ProcessNode node(process::resolve_domain(machine), axis->name,
                              process::cyclic_clock(shell),
                              process::resolve_middleware(machine, axis->name),
                              dds::LocalTransport::shared_memory, std::move(identity));
    trace::TraceWriter tracer(trace_path, axis->name);
    node.announce(PHASE_STARTING);
    node.serve_operator_commands(
        process::OperatorScope::of_axis_node(),
        process::AdmissionLimits::for_cycle_us(static_cast<std::uint32_t>(machine.cycle_us)));

    const canopen::NodeStartupConfig startup = axisnode::drive_startup_of(*axis);
    axisnode::AxisNode core(axisnode::roles_of(machine, *axis, startup));
    axisnode::AxisInputs inputs(node, machine, *axis, core);
    axisnode::AxisOutputs outputs(node, machine, *axis, tracer, trace_pos_every);
    process::Wakeup& wake = node.wakeup();

    axisnode::DriveLink link(can::open_can_bus(bus->uri), node_id, sync_producer,
                             axisnode::other_nodes_on_bus(machine, *axis), wake);
    if (const auto error = link.configure(startup, 10s)) {
      spdlog::error("drive on {}: {}", bus->uri, *error);
      node.raise_alarm(axisnode::kAlarmBase + static_cast<int>(axisnode::AxisAlarm::drive_startup),
                       error->c_str(), 0, 0, axis->id);
      node.announce(PHASE_FAILED, 0, *error);
      return 1;
    }

    // Discovery: the writers of every channel that may command the node, and the feedback
    // reader of every channel that reads it.
    process::CycleLoop loop(node, machine.cycle_us, clock::kAxisCyclePriority);
    spdlog::info("node {} on {}{}", node_id, bus->uri, sync_producer ? " (SYNC producer)" : "");
    if (!loop.start([&] { return inputs.discovered() && outputs.discovered(); }, shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();
    loop.on_slow_wait(std::chrono::milliseconds(stall_ms), [&](std::uint64_t c) {
      if (const auto wait = core.input_wait(c)) {
        spdlog::warn("{}", axisnode::input_wait_text(*wait, c, machine));
      }
    });
    axisnode::DriveActivation activation;
    activation.lockstep = lockstep;
    if (sync_producer && !lockstep) {
      // Realtime: SYNC at a fixed offset inside every cycle, from a timer of its own.
      constexpr std::int64_t kNsPerUs = 1000;
      activation.sync_timer = canopen::SyncSchedule(
          node.run_control().start_ns, machine.cycle_us * kNsPerUs, bus->sync_offset_us * kNsPerUs);
    }
    // A lockstep bus wait ends with the run, an E-stop or the owner gone.
    activation.abandon = [&] {
      const RunCommand cmd = node.run_control().command;
      bool lost = false;
      wake.with_lock([&] { lost = core.owner_lost(); });
      return cmd == RUN_STOP || cmd == RUN_ESTOP || lost || process::g_stop_signal != 0;
    };
    activation.slow = std::chrono::milliseconds(stall_ms);
    link.activate(activation);
    outputs.trace_start(core);
    const std::int64_t period_ns = static_cast<std::int64_t>(machine.cycle_us) * 1000;

    // The drive's side of a cycle: its answer, the core's step, the feedback stamped N, then
    // the bus (RPDO and SYNC, and in lockstep the drive's answer to this SYNC).
    const auto drive_cycle = [&](std::uint64_t cycle, bool emergency_stop, bool step_lockstep,
                                 bool in_run) {
      const auto time_ns = static_cast<std::int64_t>(cycle) * period_ns;
      link.read(time_ns, period_ns);  // a bus off is in the state, for the core to alarm
      const axisnode::DriveSample& state = link.state();
      const axisnode::AxisNodeOutput& out = core.step(cycle, axisnode::readings_of(state),
                                                      emergency_stop, lockstep && loop.degraded());
      outputs.publish(cycle, core, state, in_run);
      link.command() = axisnode::command_of(out);
      link.set_lockstep(step_lockstep);
      link.write(time_ns, period_ns);
    };

    bool owner_loss_checked = false;
    std::uint64_t cycle = 0;
    for (; loop.next(
             cycle, [&](std::uint64_t c) { return core.ready(c); },
             [&] { return core.owner_lost(); });
         ++cycle) {
      // 1. Inputs stamped N-1: who owns the axis (the requests sent before this cycle) and
      //    which setpoint wins.
      bool lost_now = false;
      wake.update([&] {
        core.take_inputs(cycle, lockstep);
        lost_now = core.owner_lost();
      });
      outputs.trace_decisions(cycle, core);
      if (!lockstep && !loop.degraded()) {
        link.follow_machine_start(loop.origin_ns());  // the SYNCs too (decision 128)
        axisnode::SentSync sync;
        outputs.trace_tick(cycle, loop.due_ns(), loop.woke_ns(),
                           sync_producer && link.latest_sync(sync) ? &sync : nullptr);
      }
      if (lost_now && !owner_loss_checked) {
        owner_loss_checked = true;
        if (node.stop_arrives_within(300ms)) {  // the owner left because the run ends
          break;
        }
      }
      while (const auto request = node.take_operator_request(cycle)) {
        if (request->action == process::OperatorActionKind::reset &&
            request->concerns(core.commanding_channel())) {
          core.reset();
          outputs.trace_reset(cycle);
        }
      }
      // 2. The drive's cycle, and the feedback stamped N.
      drive_cycle(cycle, loop.emergency_stop(), lockstep && !loop.degraded(), true);
    }

    // Stopping is safe (axisnode/node/drive_stop.hpp): the drive quick-stops in cycles paced to
    // real time, nothing the machine says is obeyed any more, and it is disabled only at rest
    // (the SYNC producer once the bus's other nodes are quiet too). The feedback goes on, so
    // that a machine still running steps on and sees the axis stop.
    axisnode::DriveStopLimits stop_limits;
    stop_limits.limit_cycles = static_cast<int>(machine.cycles_of(5000));
    stop_limits.quiet_cycles =
        std::max(stop_limits.quiet_cycles, static_cast<int>(machine.cycles_of(50)));
    // The same half second as the paced cycles' watch: a lockstep machine may step slower than
    // real time for a while.
    stop_limits.silent_drive_cycles = core.roles().controller.best_effort_watch_cycles;
    axisnode::DriveStop drive_stop(sync_producer, stop_limits);
    // At a run's end the drives stand where the programs ended, and an E-stop has already
    // stopped them in the loop: they are disabled at once, as before, and the bus and the trace
    // end as they did. A signal, or a drive still moving, takes the stop.
    const bool must_stop = process::g_stop_signal != 0 || core.output().vel != 0.0;
    axisnode::DriveStop::Verdict verdict =
        must_stop ? axisnode::DriveStop::Verdict::go_on : axisnode::DriveStop::Verdict::disable;
    axisnode::AxisAlarm alarm_while_stopping = axisnode::AxisAlarm::none;
    while (verdict == axisnode::DriveStop::Verdict::go_on) {
      loop.next_stopping(cycle);
      drive_cycle(cycle, true, false, false);
      if (alarm_while_stopping == axisnode::AxisAlarm::none) {
        alarm_while_stopping = core.output().new_alarm;
      }
      verdict =
          drive_stop.cycle(link.state().fresh, core.ready_to_disable(), link.other_nodes_rpdos());
      ++cycle;
    }
    if (must_stop) {
      spdlog::info("drive stopped in {} cycles: {}", drive_stop.cycles(),
                   axisnode::to_text(verdict));
    }
    if (verdict != axisnode::DriveStop::Verdict::disable) {
      spdlog::warn("the drive is disabled without standing still: {}", axisnode::to_text(verdict));
    }
    if (alarm_while_stopping != axisnode::AxisAlarm::none) {
      spdlog::warn("while stopping: alarm {} {}",
                   axisnode::kAlarmBase + static_cast<int>(alarm_while_stopping),
                   axisnode::to_text(alarm_while_stopping));
    }
    link.deactivate(
        canopen::DriveCommand{cia402::encode_controlword(cia402::Command::disable_voltage),
                              core.output().target_counts, 0, core.output().mode});
    tracer.flush();
    spdlog::info("stopped: {} EMCY, {} malformed frames, {} trace events dropped",
                 link.emcy_count(), link.malformed_count(), tracer.dropped());
    if (core.requests_dropped() > 0) {
      spdlog::warn("{} axis requests dropped (more waiting than the node keeps)",
                   core.requests_dropped());
    }
    node.announce_stopped();
    // The drives leave last: a channel still waiting for this cycle's feedback when the run
    // stops would otherwise see its axis go before it has seen the stop, and raise alarm 1202
    // for what is only the end of the run. Its feedback writer stays until the channels have
    // gone (2 s at most; the launcher waits 3 s for every DDS process).
    const auto linger_end = std::chrono::steady_clock::now() + 2s;
    while (process::g_stop_signal == 0 && inputs.setpoint_writers() > 0 &&
           std::chrono::steady_clock::now() < linger_end) {
      std::this_thread::sleep_for(10ms);
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
