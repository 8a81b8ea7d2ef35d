// mcnc-channel: one machining channel. Interpreter -> planner -> one setpoint per owned axis per
// cycle over DDS, feedback back. Wiring only: the behaviour is in ChannelController.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/loading/program_loader.hpp"
#include "channel/motion/motion_planner.hpp"
#include "channel/setup/interpreter_setup.hpp"
#include "channel/setup/motion_setup.hpp"
#include "channel/wire/channel_outputs.hpp"
#include "channel/wire/channel_peers.hpp"
#include "channel/wire/plc_link.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/text/text_lines.hpp"
#include "common/trace/trace_writer.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace std::chrono_literals;
using namespace mcnc;

namespace {

// What the operator asked for, as the trace's `text` (escaped).
struct EscapedText {
  char text[2 * process::OperatorRequest::kTextSize + 8] = {};
};

EscapedText escaped(const char* text) noexcept {
  EscapedText e;
  trace::json_escape(text, e.text, sizeof e.text);
  return e;
}

}  // namespace

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

  // The channel's axes, in program order: its own, those it may acquire (G141), then its
  // spindle's C axis (on the spindle's node).
  std::vector<const config::AxisConfig*> axes;
  channel::ChannelSetup setup;
  for (const std::string& name : ch->program_axes()) {
    const config::AxisConfig* a = machine.find_axis(name);
    if (!a->spindle.empty()) {
      setup.spindle_c_slot = axes.size();
    }
    axes.push_back(a);
    setup.in_position.push_back(a->in_position);
    const bool exchange_slot = axes.size() > ch->axes.size() && a->spindle.empty();
    setup.slots.push_back(channel::AxisSlot{
        a->address, exchange_slot, static_cast<std::uint32_t>(machine.find_channel(a->channel)->id),
        static_cast<std::uint32_t>(a->id), a->sync_slave,
        static_cast<std::uint32_t>(a->sync_master), a->sync_at_power_on && !exchange_slot});
  }
  for (const config::AxisConfig& a : machine.axes) {
    setup.machine_axes.push_back(channel::MachineAxis{
        a.type == config::AxisType::spindle  ? channel::MachineAxisKind::spindle
        : a.type == config::AxisType::rotary ? channel::MachineAxisKind::rotary
                                             : channel::MachineAxisKind::linear,
        a.sync_slave});
  }
  setup.axis_count = axes.size();
  setup.spindle_count = ch->spindles.size();
  setup.cycle_s = machine.cycle_s();
  setup.channel_id = static_cast<std::uint32_t>(ch->id);
  setup.plc = machine.plc.present;
  setup.call_wait_cycles = machine.cycles_of(machine.call_wait_timeout_ms);
  // The slaves of the G114.1 groups this channel commands (its spindle is their master): their
  // feedback follows the channel's spindles' (their slots come last, as config::fed_axes has
  // them); G114.1 ends when they are in phase.
  std::size_t sync_slaves = 0;
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    setup.spindle_may_follow =
        setup.spindle_may_follow ||
        (!ch->spindles.empty() && machine.find_axis(ch->spindles.front())->id == g.slave);
  }
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    if (g.channel == ch->id) {
      setup.spindle_groups.push_back(
          channel::SpindleGroupSetup{g.group, axes.size() + ch->spindles.size() + sync_slaves++});
    }
  }

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
  interp_config.shared_variables = &shared_variables;
  interp_config.shared_sink = &shared_writes;
  if (!program_dir.empty()) {
    interp_config.program_dir = program_dir;
  }
  interp::InterpreterSource interpreter(interp_config);
  std::vector<std::string> program_lines;
  std::string program_name;
  std::optional<interp::ProgramAlarm> load_alarm;
  if (!program_path.empty()) {
    std::ifstream file(program_path);
    std::stringstream content;
    content << file.rdbuf();
    program_lines = text::split_lines(content.str());
    program_name = program_path.substr(program_path.find_last_of('/') + 1);
    load_alarm = interpreter.load(content.str(), program_name);
  }
  // Programs the operator selects and MDI blocks are checked off the cycle.
  channel::ProgramLoader loader(interp_config);
  std::optional<channel::LoadedProgram> loaded;  // checked, waiting for the channel to stand
  std::uint64_t mdi_epoch = 0;  // the controller's run epoch when the MDI blocks were asked for
  motion::MotionPlanner planner(channel::motion_config_for(machine, *ch), interp::AxisVector{});
  setup.shared_writes = &shared_writes;
  channel::ChannelController controller(setup, interpreter, planner);

  try {
    process::ProcessNode node(process::resolve_domain(machine), ch->name,
                              process::cyclic_clock(shell),
                              process::resolve_middleware(machine, ch->name));
    trace::TraceWriter tracer(trace_path, ch->name);
    node.announce(PHASE_STARTING);
    process::Wakeup& wake = node.wakeup();

    // Feedback of the nodes the channel commands (its axes, then its spindles), by cycle, and
    // the lockstep gate over them and the other channels: a node runs cycle N on the channel's
    // setpoint N-1, so the channel must not run ahead of any of them; the channels decide their
    // wait marks from each other's status and arrivals stamped N-1.
    std::vector<const config::AxisConfig*> spindles;
    for (const std::string& name : ch->spindles) {
      spindles.push_back(machine.find_axis(name));
    }
    const std::vector<const config::AxisConfig*> fed = config::fed_axes(machine, *ch);
    const std::vector<std::string> fed_nodes = config::node_keys(fed);
    std::vector<cycle::TrackedInput<AxisFeedback>> feedback =
        cycle::tracked_inputs<AxisFeedback>(0, fed.size());
    const std::size_t plc_input = fed.size() + machine.channels.size() - 1;
    cycle::LockstepGate gate(plc_input + (machine.plc.present ? 1 : 0));
    channel::ChannelPeers peers(node, machine, *ch, gate, fed.size(), shared_variables);
    std::optional<channel::PlcLink> plc;
    if (machine.plc.present) {
      plc.emplace(node, gate, plc_input, static_cast<std::uint32_t>(ch->id));
    }
    // A spindle's feedback is also its C axis's.
    dds::Reader<AxisFeedback> feedback_reader(
        node.participant(), dds::Keys::of(fed_nodes),
        [&](const AxisFeedback& fb, const dds::WriterId& writer) {
          wake.update([&] {
            for (std::size_t slot = 0; slot < fed.size(); ++slot) {
              if (static_cast<std::uint32_t>(fed[slot]->id) == fb.axis()) {
                feedback[slot].on_sample(fb, fb.cycle(), fb.event_seq(), writer, gate);
              }
            }
          });
        },
        [&](const dds::WriterId& writer, bool matched) {
          if (!matched) {
            wake.update([&] {
              for (auto& input : feedback) {
                input.on_unmatched(writer, gate);
              }
            });
          }
        });
    channel::ChannelOutputs outputs(node, tracer, *ch, config::channel_names(machine), axes,
                                    spindles, program_name, program_lines, shared_writes);
    if (!interp_config.program_dir.empty()) {
      outputs.preload_program_dir(interp_config.program_dir.string());
    }

    // Discovery: the feedback writer of every node it reads and the setpoint reader of every node
    // it commands matched.
    spdlog::info("{} axes{}{}", axes.size(), program_path.empty() ? "" : ", program ",
                 program_name);
    process::CycleLoop loop(node, machine.cycle_us);
    if (!loop.start(
            [&] {
              return feedback_reader.matched_writers() >= static_cast<int>(fed_nodes.size()) &&
                     outputs.setpoints_discovered() && peers.discovered() &&
                     (!plc || plc->discovered()) &&
                     outputs.event_readers() >= static_cast<int>(peers.inputs());
            },
            shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();
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
             [&] {
               return std::any_of(feedback.begin(), feedback.end(),
                                  [](const auto& input) { return input.lost(); });
             });
         ++cycle) {
      if (loop.emergency_stop() && !estop_seen) {
        estop_seen = true;
        controller.emergency_stop();
      }
      while (const auto request = node.take_operator_request(cycle)) {
        if (!request->concerns(static_cast<std::uint32_t>(ch->id))) {
          continue;
        }
        using Kind = process::OperatorActionKind;
        switch (request->action) {
          case Kind::reset:
            controller.request_reset();
            break;
          case Kind::cycle_start:
            controller.request_start();
            break;
          case Kind::feed_hold:
            controller.request_feed_hold();
            break;
          case Kind::feed_override:
            controller.set_feed_override(request->value);
            break;
          case Kind::rapid_override:
            controller.set_rapid_override(request->value);
            break;
          case Kind::spindle_override:
            controller.set_spindle_override(request->value);
            break;
          case Kind::single_block:
            controller.set_single_block(request->value != 0.0);
            break;
          case Kind::select_program:
          case Kind::mdi: {
            // Checked off the cycle; the channel takes the result once it stands in reset or
            // idle (a cycle start waits for it).
            const bool mdi = request->action == Kind::mdi;
            const char* refused =
                !controller.may_change_program()
                    ? "programs are selected and MDI blocks run only in reset or idle"
                : loaded || !loader.submit(mdi, request->text.data())
                    ? "another program or MDI block is still being checked"
                    : nullptr;
            mdi_epoch = mdi && refused == nullptr ? controller.run_epoch() : mdi_epoch;
            tracer.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\",\"text\":\"%s\"%s%s%s",
                        ch->name.c_str(), process::to_string(request->action),
                        escaped(request->text.data()).text, refused ? ",\"refused\":\"" : "",
                        refused ? refused : "", refused ? "\"" : "");
            continue;
          }
          case Kind::alarm_ack:  // for the HMIs: which alarms an operator has seen
          case Kind::none:
            continue;
        }
        if (request->action == Kind::reset || request->action == Kind::cycle_start ||
            request->action == Kind::feed_hold) {
          tracer.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\"", ch->name.c_str(),
                      process::to_string(request->action));
        } else {
          tracer.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\",\"value\":%.3f",
                      ch->name.c_str(), process::to_string(request->action), request->value);
        }
      }

      // An axis node leaving may be the end of the run, not a failure. In realtime, feedback
      // older than the deadline counts as the axis being gone (ARCHITECTURE.md §6).
      bool newly_lost = false;
      wake.update([&] {
        for (std::size_t i = 0; i < fed.size(); ++i) {
          const AxisFeedback* latest = feedback[i].latest();
          if (!lockstep && latest != nullptr &&
              controller.state() != channel::ChannelState::reset &&
              latest->cycle() + static_cast<std::uint64_t>(machine.deadline_cycles) < cycle) {
            feedback[i].lose(gate);
          }
          newly_lost = newly_lost || feedback[i].loss_pending();
        }
      });
      if (newly_lost && node.stop_arrives_within(300ms)) {
        break;
      }
      wake.update([&] {
        for (std::size_t i = 0; i < fed.size(); ++i) {
          const AxisFeedback* fb = feedback[i].for_cycle(cycle, lockstep);
          if (fb != nullptr) {
            views[i] = channel::AxisFeedbackView{
                fb->cmd(),   fb->act(),         fb->enabled(),    fb->alarm(),          true,
                fb->owner(), fb->released_by(), fb->coupled_to(), fb->coupling_locked()};
          }
          if (feedback[i].take_loss()) {
            controller.axis_lost(i);
          }
        }
      });

      if (!loaded) {
        loaded = loader.take();
      }
      if (loaded && loaded->mdi && controller.run_epoch() != mdi_epoch) {
        // A reset or another run came while the blocks were checked: they no longer run.
        tracer.emit(cycle, "operator",
                    "\"ch\":\"%s\",\"action\":\"mdi\",\"text\":\"%s\",\"refused\":\"a reset "
                    "or another run came first\"",
                    ch->name.c_str(), escaped(loaded->program.text.c_str()).text);
        loaded.reset();
      }
      if (loaded && controller.may_change_program()) {
        if (loaded->program.alarm) {
          controller.report_alarm(*loaded->program.alarm);  // the program selected stays
        } else if (loaded->mdi) {
          outputs.set_mdi_lines(std::move(loaded->lines));
          interpreter.prepare_mdi(std::move(loaded->program));
          controller.request_mdi();
        } else {
          tracer.emit(cycle, "program", "\"ch\":\"%s\",\"prog\":\"%s\",\"blocks\":%zu",
                      ch->name.c_str(), escaped(loaded->program.name.c_str()).text,
                      loaded->program.block_count);
          outputs.set_program(loaded->program.name, std::move(loaded->lines));
          interpreter.adopt(std::move(loaded->program));
        }
        loaded.reset();
      }
      controller.set_program_pending(loaded.has_value() || loader.busy());

      peers.apply(cycle, lockstep, controller);
      if (plc) {
        plc->apply(cycle, controller);
      }
      const channel::ChannelOutput& out = controller.cycle(cycle, views);
      outputs.publish(cycle, controller, out, views,
                      static_cast<std::uint32_t>(interpreter.block_count()),
                      interpreter.has_program());
    }
    tracer.flush();
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
