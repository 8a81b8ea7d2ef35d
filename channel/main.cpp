// mcnc-channel: one machining channel. Interpreter -> planner -> one setpoint per owned axis per
// cycle over DDS, feedback back. Wiring only: the behaviour is in ChannelController.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/loading/program_loader.hpp"
#include "channel/loading/read_ahead.hpp"
#include "channel/motion/motion_planner.hpp"
#include "channel/setup/controller_setup.hpp"
#include "channel/setup/interpreter_setup.hpp"
#include "channel/setup/motion_setup.hpp"
#include "channel/wire/axis_feedback_inputs.hpp"
#include "channel/wire/channel_outputs.hpp"
#include "channel/wire/channel_peers.hpp"
#include "channel/wire/operator_requests.hpp"
#include "channel/wire/plc_link.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/lockstep_wait_log.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace std::chrono_literals;
using namespace mcnc;

int main(int argc, char** argv) {
  CLI::App app{"mcnc channel: interpreter, planner and interpolator of one machining channel"};
  process::ShellOptions shell;
  std::string channel_name;
  std::string program_path;
  std::string trace_path;
  process::add_shell_options(app, shell);
  app.add_option("--channel", channel_name, "channel name from the machine file")->required();
  app.add_option("--program", program_path, "part program to run at cycle start")
      ->check(CLI::ExistingFile);
  app.add_option("--trace", trace_path, "write this process's trace events to FILE");
  std::string program_dir;
  app.add_option("--progdir", program_dir,
                 "where programs are found by number (overrides the machine file's program_dir)")
      ->check(CLI::ExistingDirectory);
  std::string retained_path;
  app.add_option("--retained", retained_path,
                 "keep the machine's retained macro variables #500-#999 in FILE (loaded at start; "
                 "channel 1 saves them when the run ends; overrides the machine file's)");
  bool manual_start = false;
  app.add_flag("--manual-start", manual_start,
               "load the program and wait for CYCLE START (an operator command)");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  const config::ChannelConfig* ch = machine.find_channel(channel_name);
  if (ch == nullptr) {
    std::fprintf(stderr, "error: channel %s is not in machine file %s\n", channel_name.c_str(),
                 shell.machine_path.c_str());
    return 2;
  }
  process::start_process(ch->name, shell);
  process::require_roudi_or_exit(machine, ch->name);
  std::optional<security::IdentityFiles> identity =
      process::resolve_security_or_exit(machine, ch->name);

  channel::ControllerLayout layout = channel::controller_layout_for(machine, *ch);
  channel::ChannelSetup& setup = layout.setup;
  const std::vector<const config::AxisConfig*>& axes = layout.axes;

  interp::InterpreterConfig interp_config = channel::interpreter_config_for(machine, *ch);
  // #500-#999 and #20000-#20999 are the machine's: this channel's copy, kept equal to the
  // others' by sending every write (ARCHITECTURE.md §5). The retained ones come from the
  // machine's file; channel 1 writes it back when the run ends.
  interp::macro::VariableStore shared_variables(interp_config.macro);
  channel::SharedWriteLog shared_writes;
  if (retained_path.empty()) {
    retained_path = machine.retained_file;
  }
  if (!retained_path.empty() && std::filesystem::exists(retained_path)) {
    const interp::macro::MacroAlarm a = shared_variables.load_retained_file(retained_path);
    if (a.number != 0) {
      std::fprintf(stderr, "error: %s: %s\n", retained_path.c_str(), std::string(a.text()).c_str());
      return 2;
    }
  }
  // The interpreter runs on the read-ahead's thread: its shared writes travel with its commands
  // and reach the log as the cycle takes them; the others' writes reach it at read-ahead stops.
  channel::ReadAhead read_ahead(&shared_writes, &shared_variables);
  interp_config.shared_variables = &shared_variables;
  interp_config.shared_sink = &read_ahead.interpreter_sink();
  if (!program_dir.empty()) {
    interp_config.program_dir = program_dir;
  }
  // The directory's index, kept across runs; the checks on the loader's thread keep their own.
  const auto index_of_directory = [&] {
    return interp_config.program_dir.empty()
               ? nullptr
               : std::make_shared<interp::program::ProgramStore>(interp_config.program_dir);
  };
  interp_config.program_store = index_of_directory();
  // A command's block text is kept while the controller may show it: in the read-ahead's
  // window, the planner's and the few blocks the controller holds besides.
  const motion::MotionConfig motion_config = channel::motion_config_for(machine, *ch);
  constexpr std::size_t kHeldBesides = 64;
  interp::InterpreterSource interpreter(
      interp_config, channel::ReadAhead::kWindow + motion_config.lookahead_blocks + kHeldBesides);
  std::string program_name;
  std::optional<interp::ProgramAlarm> load_alarm;
  if (!program_path.empty()) {
    program_name = program_path.substr(program_path.find_last_of('/') + 1);
    load_alarm = interpreter.load_file(program_path, program_name);
  }
  // Programs the operator selects and MDI blocks are checked off the cycle.
  interp::InterpreterConfig loader_config = interp_config;
  loader_config.program_store = index_of_directory();
  channel::ProgramLoader loader(loader_config);
  motion::MotionPlanner planner(motion_config, interp::AxisVector{});
  setup.shared_writes = &shared_writes;
  read_ahead.start(interpreter);
  // The thread stops before the interpreter it reads goes, on every way out.
  struct StopReadAhead {
    channel::ReadAhead& read_ahead;
    ~StopReadAhead() { read_ahead.stop(); }
  } stop_read_ahead{read_ahead};
  channel::ChannelController controller(setup, read_ahead, planner);

  try {
    process::ProcessNode node(process::resolve_domain(machine), ch->name,
                              process::cyclic_clock(shell),
                              process::resolve_middleware(machine, ch->name),
                              dds::LocalTransport::shared_memory, std::move(identity));
    trace::TraceWriter tracer(trace_path, ch->name);
    node.announce(PHASE_STARTING);
    node.serve_operator_commands(
        process::OperatorScope::of_channel(static_cast<std::uint32_t>(ch->id)),
        process::AdmissionLimits::for_cycle_us(static_cast<std::uint32_t>(machine.cycle_us)));

    // The lockstep gate over the feedback of the nodes the channel commands, the other
    // channels and the PLC: a node runs cycle N on the channel's setpoint N-1, so the channel
    // must not run ahead of any of them; the channels decide their wait marks from each other's
    // status and arrivals stamped N-1.
    const std::vector<const config::AxisConfig*> fed = config::fed_axes(machine, *ch);
    const std::size_t plc_input = fed.size() + machine.channels.size() - 1;
    cycle::LockstepGate gate(plc_input + (machine.plc.present ? 1 : 0));
    channel::AxisFeedbackInputs feedback(node, fed, gate, machine.deadline_cycles,
                                         static_cast<std::uint32_t>(ch->id));
    channel::ChannelPeers peers(node, machine, *ch, gate, fed.size(), read_ahead);
    std::optional<channel::PlcLink> plc;
    if (machine.plc.present) {
      plc.emplace(node, gate, plc_input, static_cast<std::uint32_t>(ch->id));
    }
    channel::ChannelOutputs outputs(node, tracer, *ch, config::channel_names(machine), axes,
                                    layout.spindles, program_name, shared_writes);
    channel::OperatorRequests operator_requests(node, tracer, *ch, loader, controller, read_ahead,
                                                outputs);

    // Discovery: the feedback writer of every node it reads and the setpoint reader of every node
    // it commands matched.
    spdlog::info("{} axes{}{}", axes.size(), program_path.empty() ? "" : ", program ",
                 program_name);
    process::CycleLoop loop(node, machine.cycle_us);
    if (!loop.start(
            [&] {
              return feedback.discovered() && outputs.setpoints_discovered() &&
                     peers.discovered() && (!plc || plc->discovered()) &&
                     outputs.event_readers() >= static_cast<int>(peers.inputs());
            },
            shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();
    read_ahead.set_lockstep(lockstep);
    // A slow lockstep wait says whose input it waits for (the gate's layout is the one above).
    const std::vector<std::string> others = config::other_channels(machine, *ch);
    loop.on_slow_wait(std::chrono::seconds(2), [&](std::uint64_t c) {
      if (const auto wait = gate.wait(c)) {
        const std::size_t i = wait->input;
        const std::string whose = i < fed.size()  ? fed[i]->name + "'s feedback"
                                  : i < plc_input ? others[i - fed.size()] + "'s status"
                                                  : std::string("the PLC's status");
        spdlog::warn("{}", process::lockstep_wait_text(c, whose, *wait));
      }
    });
    if (load_alarm) {
      controller.report_alarm(*load_alarm);
    } else if (!program_path.empty() && !manual_start) {
      controller.request_start();
    }

    std::vector<channel::AxisFeedbackView> views(fed.size());  // axes, then spindles
    bool estop_seen = false;
    // A channel runs cycle N once the feedback stamped N-1 of all its axes is in.
    for (std::uint64_t cycle = 0; loop.next(
             cycle, [&](std::uint64_t c) { return gate.may_run(c); },
             [&] { return feedback.any_lost(); });
         ++cycle) {
      if (loop.emergency_stop() && !estop_seen) {
        estop_seen = true;
        controller.emergency_stop();
      }
      operator_requests.apply(cycle);

      // An axis node leaving may be the end of the run, not a failure. In realtime, feedback
      // older than the deadline counts as the axis being gone (ARCHITECTURE.md §6).
      if (feedback.check_losses(cycle, lockstep,
                                controller.state() != channel::ChannelState::reset) &&
          node.stop_arrives_within(300ms)) {
        break;
      }
      feedback.take(cycle, lockstep, views, controller);
      operator_requests.take_loaded(cycle);

      peers.apply(cycle, lockstep, controller);
      if (plc) {
        plc->apply(cycle, lockstep, controller);
      }
      const channel::CycleOutput& out = controller.cycle(cycle, views);
      outputs.publish(cycle, controller, out, views,
                      static_cast<std::uint32_t>(read_ahead.block_count()),
                      read_ahead.has_program());
    }
    tracer.flush();
    read_ahead.stop();
    if (ch->id == 1 && !retained_path.empty()) {
      peers.apply_remaining_writes();
      const interp::macro::MacroAlarm a = shared_variables.save_retained_file(retained_path);
      if (a.number != 0) {
        spdlog::error("saving the retained variables: {}", a.text());
      }
    }
    if (shared_writes.lost() > 0) {
      spdlog::warn("{} shared variable writes not sent (write log full)", shared_writes.lost());
    }
    if (peers.dropped() > 0) {
      spdlog::warn("{} coordination events dropped (receive queue full)", peers.dropped());
    }
    if (tracer.dropped() > 0) {
      spdlog::warn("{} trace events dropped (trace writer could not keep up)", tracer.dropped());
    }
    node.announce_stopped();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
