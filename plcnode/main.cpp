// mcnc-plcnode: the machine's PLC. Aux requests from the channels (M and T codes) in, answers
// (FIN) and the I/O image out, over DDS, in the machine's cycle. Wiring only: the behaviour is
// in MachinePlc.
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"
#include "plcnode/logic/machine_plc.hpp"
#include "plcnode/wire/plc_inputs.hpp"

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

    // Lockstep inputs: every channel's status N-1 with the events it announces (the requests),
    // and the feedback N-1 of the spindles an interlock looks at.
    plc::PlcInputs inputs(node, machine);
    dds::Writer<PlcStatus> status_writer_out(node.participant());
    dds::Writer<AuxAck> ack_writer(node.participant());

    const int n_channels = static_cast<int>(machine.channels.size());
    process::CycleLoop loop(node, machine.cycle_us);
    spdlog::info("{} signals, {} M codes", machine.plc.signals.size(), machine.plc.m_codes.size());
    if (!loop.start(
            [&] {
              return inputs.discovered() && status_writer_out.matched_readers() >= n_channels &&
                     ack_writer.matched_readers() >= n_channels;
            },
            shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();

    plc::MachinePlc plc(machine.plc, machine.cycle_us);
    std::vector<plc::SpindleView> views(inputs.spindles().size());
    std::uint64_t ack_seq = 0;
    for (std::uint64_t cycle = 0; loop.next(
             cycle, [&](std::uint64_t c) { return inputs.may_run(c); }, [] { return false; });
         ++cycle) {
      inputs.apply(cycle, lockstep, plc, views);
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
    if (inputs.dropped() > 0) {
      spdlog::warn("{} aux requests dropped (queue full)", inputs.dropped());
    }
    node.announce_stopped();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
