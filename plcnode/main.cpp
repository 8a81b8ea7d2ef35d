// mcnc-plcnode: the machine's PLC. Aux requests from the channels (M and T codes) in, answers
// (FIN) and the I/O image out, over DDS, in the machine's cycle. Wiring only: the behaviour is
// in MachinePlc.
#include "common/config/cyclic_routes.hpp"
#include "common/cycle/cycle_buffer.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"
#include "plcnode/logic/machine_plc.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace mcnc;

namespace {

// "M10", "T0101": the code as the program wrote it.
void code_text(const plc::AuxRequest& r, char (&text)[16]) {
  if (r.kind == plc::AuxKind::t_code) {
    std::snprintf(text, sizeof text, "T%04d", r.code);
  } else {
    std::snprintf(text, sizeof text, "M%02d", r.code);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mcnc PLC node: M and T codes, FIN, interlocks and the I/O image of the machine"};
  process::ShellOptions shell;
  std::string trace_path;
  process::add_shell_options(app, shell);
  app.add_option("--trace", trace_path, "write this process's trace events to FILE");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  if (!machine.plc.present) {
    std::fprintf(stderr, "error: machine file %s has no plc section\n", shell.machine_path.c_str());
    return 2;
  }
  process::start_process("PLC", shell);
  process::require_roudi_or_exit(machine, "PLC");

  try {
    process::ProcessNode node(process::resolve_domain(machine), "PLC", process::cyclic_clock(shell),
                              process::resolve_middleware(machine, "PLC"));
    trace::TraceWriter tracer(trace_path, "PLC");
    node.announce(PHASE_STARTING);
    process::Wakeup& wake = node.wakeup();

    // Lockstep inputs: every channel's status N-1 with the events it announces (the requests),
    // and the feedback N-1 of the spindles an interlock looks at.
    const std::size_t channels = machine.channels.size();
    // The spindles an interlock looks at, and the G114.1 partners of those (a pair in phase
    // may open a chuck while it turns).
    std::vector<int> spindles;  // axis ids
    auto watch = [&](int id) {
      if (id != 0 && std::find(spindles.begin(), spindles.end(), id) == spindles.end()) {
        spindles.push_back(id);
      }
    };
    for (const config::PlcMCode& m : machine.plc.m_codes) {
      watch(m.spindle_stopped);
    }
    for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
      if (std::find(spindles.begin(), spindles.end(), g.master) != spindles.end() ||
          std::find(spindles.begin(), spindles.end(), g.slave) != spindles.end()) {
        watch(g.master);
        watch(g.slave);
      }
    }
    cycle::LockstepGate gate(channels + spindles.size());
    std::vector<dds::WriterId> status_writer(channels);
    std::vector<bool> status_writer_known(channels, false);
    dds::Reader<ChannelStatus> status_reader(
        node.participant(), dds::Partitions::of(config::channel_names(machine)),
        [&](const ChannelStatus& s, const dds::WriterId& writer) {
          if (s.channel() < 1 || s.channel() > channels) {
            return;
          }
          wake.update([&] {
            gate.on_sample(s.channel() - 1, s.cycle(), s.event_seq());
            status_writer[s.channel() - 1] = writer;
            status_writer_known[s.channel() - 1] = true;
          });
        },
        [&](const dds::WriterId& writer, bool matched) {
          if (matched) {
            return;
          }
          wake.update([&] {
            for (std::size_t c = 0; c < channels; ++c) {
              if (status_writer_known[c] && status_writer[c] == writer) {
                gate.set_expected(c, false);  // a channel gone: the others go on
              }
            }
          });
        });
    constexpr std::size_t kQueue = 256;
    std::array<plc::AuxRequest, kQueue> queue{};
    std::size_t queued = 0;
    std::uint64_t dropped = 0;
    dds::Reader<CoordinationEvent> event_reader(
        node.participant(), [&](const CoordinationEvent& e, const dds::WriterId&) {
          if (e.channel() < 1 || e.channel() > channels) {
            return;
          }
          wake.update([&] {
            gate.on_event(e.channel() - 1, e.seq());
            if (e.kind() != COORD_AUX_REQUEST) {
              return;
            }
            if (queued == kQueue) {
              ++dropped;
              return;
            }
            queue[queued++] =
                plc::AuxRequest{e.channel(),
                                e.aux_id(),
                                e.aux_kind() == AUX_T ? plc::AuxKind::t_code : plc::AuxKind::m_code,
                                static_cast<int>(e.aux_code()),
                                static_cast<int>(e.aux_spindle()),
                                e.cycle()};
          });
        });
    std::vector<cycle::CycleBuffer<AxisFeedback, 8>> spindle_feedback(spindles.size());
    std::vector<dds::WriterId> spindle_writer(spindles.size());
    std::vector<bool> spindle_writer_known(spindles.size(), false);
    std::vector<bool> spindle_lost(spindles.size(), false);
    std::vector<std::string> spindle_names;
    for (const int id : spindles) {
      spindle_names.push_back(machine.axes[static_cast<std::size_t>(id - 1)].name);
    }
    dds::Reader<AxisFeedback> feedback_reader(
        node.participant(), dds::Partitions::of(spindle_names),
        [&](const AxisFeedback& fb, const dds::WriterId& writer) {
          for (std::size_t k = 0; k < spindles.size(); ++k) {
            if (static_cast<int>(fb.axis()) == spindles[k]) {
              wake.update([&] {
                spindle_feedback[k].put(fb.cycle(), fb);
                spindle_writer[k] = writer;
                spindle_writer_known[k] = true;
                gate.on_sample(channels + k, fb.cycle(), 0);
              });
            }
          }
        },
        [&](const dds::WriterId& writer, bool matched) {
          if (matched) {
            return;
          }
          wake.update([&] {
            for (std::size_t k = 0; k < spindles.size(); ++k) {
              if (spindle_writer_known[k] && spindle_writer[k] == writer) {
                spindle_lost[k] = true;  // not known to stand: its interlocks hold
                gate.set_expected(channels + k, false);
              }
            }
          });
        });
    dds::Writer<PlcStatus> status_writer_out(node.participant());
    dds::Writer<AuxAck> ack_writer(node.participant());

    const int n_channels = static_cast<int>(channels);
    process::CycleLoop loop(node, machine.cycle_us);
    spdlog::info("{} signals, {} M codes", machine.plc.signals.size(), machine.plc.m_codes.size());
    if (!loop.start(
            [&] {
              return status_reader.matched_writers() >= n_channels &&
                     event_reader.matched_writers() >= n_channels &&
                     feedback_reader.matched_writers() >= static_cast<int>(spindles.size()) &&
                     status_writer_out.matched_readers() >= n_channels &&
                     ack_writer.matched_readers() >= n_channels;
            },
            shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();

    plc::MachinePlc plc(machine.plc, machine.cycle_us);
    std::vector<plc::SpindleView> views(spindles.size());
    std::uint64_t ack_seq = 0;
    for (std::uint64_t cycle = 0; loop.next(
             cycle, [&](std::uint64_t c) { return c == 0 || gate.may_run(c); },
             [] { return false; });
         ++cycle) {
      wake.update([&] {
        for (std::size_t i = 0; i < queued; ++i) {
          plc.request(queue[i]);
        }
        queued = 0;
        for (std::size_t k = 0; k < spindles.size(); ++k) {
          const AxisFeedback* fb = cycle > 0 ? spindle_feedback[k].at(cycle - 1) : nullptr;
          if (fb == nullptr && (!lockstep || spindle_lost[k])) {
            fb = spindle_feedback[k].latest();
          }
          // Turning: more than a tenth of a revolution per second either way; without
          // feedback (or with its node gone) not known to stand.
          const bool known = fb != nullptr && !spindle_lost[k];
          views[k] = plc::SpindleView{spindles[k], !known || std::abs(fb->vel()) > 36.0,
                                      known ? static_cast<int>(fb->coupled_to()) : 0,
                                      known && fb->coupling_locked()};
        }
      });
      const plc::PlcOutput& out = plc.cycle(cycle, views);
      char code[16];
      for (std::size_t i = 0; i < out.started_count; ++i) {
        const plc::AuxRequest& r = out.started[i];
        code_text(r, code);
        tracer.emit(cycle, "aux", "\"ch\":\"%s\",\"code\":\"%s\"",
                    machine.channels[r.channel - 1].name.c_str(), code);
      }
      for (std::size_t i = 0; i < out.answer_count; ++i) {
        const plc::AuxAnswer& a = out.answers[i];
        AuxAck ack;
        ack.seq(++ack_seq);
        ack.cycle(cycle);
        ack.channel(a.request.channel);
        ack.aux_id(a.request.id);
        ack.kind(a.request.kind == plc::AuxKind::t_code ? AUX_T : AUX_M);
        ack.code(a.request.code);
        ack.outcome(static_cast<AuxOutcome>(static_cast<int>(a.outcome)));
        ack.reason(a.reason.data());
        ack_writer.write(ack);
        code_text(a.request, code);
        tracer.emit(cycle, "aux_done", "\"ch\":\"%s\",\"code\":\"%s\",\"outcome\":\"%s\"%s%s%s",
                    machine.channels[a.request.channel - 1].name.c_str(), code,
                    plc::to_string(a.outcome), a.reason[0] != 0 ? ",\"reason\":\"" : "",
                    a.reason.data(), a.reason[0] != 0 ? "\"" : "");
      }
      PlcStatus status;
      status.cycle(cycle);
      status.event_seq(ack_seq);
      status.outputs(out.outputs);
      status.inputs(out.inputs);
      status.busy(static_cast<std::uint32_t>(out.busy));
      status_writer_out.write(status);
    }
    tracer.flush();
    if (dropped > 0) {
      spdlog::warn("{} aux requests dropped (queue full)", dropped);
    }
    node.announce_stopped();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
