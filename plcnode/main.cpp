// mcnc-plcnode: the machine's PLC. Aux requests from the channels (M and T codes) in, answers
// (FIN) and the I/O image out, over DDS, in the machine's cycle. Wiring only: the behaviour is
// in MachinePlc, the DDS adapters in plcnode/wire/.
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"
#include "plcnode/logic/machine_plc.hpp"
#include "plcnode/wire/plc_inputs.hpp"
#include "plcnode/wire/plc_outputs.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <vector>

using namespace mcnc;

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
  std::optional<security::IdentityFiles> identity =
      process::resolve_security_or_exit(machine, "PLC");

  try {
    process::ProcessNode node(process::resolve_domain(machine), "PLC", process::cyclic_clock(shell),
                              process::resolve_middleware(machine, "PLC"),
                              dds::LocalTransport::shared_memory, std::move(identity));
    trace::TraceWriter tracer(trace_path, "PLC");
    node.announce(PHASE_STARTING);

    // Lockstep inputs: every channel's status N-1 with the events it announces (the requests),
    // and the feedback N-1 of the axes it watches (spindles, the axes of position inputs).
    plc::PlcInputs inputs(node, machine);
    plc::PlcOutputs outputs(node, machine, tracer);

    process::CycleLoop loop(node, machine.cycle_us);
    spdlog::info("{} signals, {} M codes", machine.plc.signals.size(), machine.plc.m_codes.size());
    if (!loop.start([&] { return inputs.discovered() && outputs.discovered(); }, shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();

    plc::MachinePlc plc(machine.plc, machine.cycle_us);
    std::vector<plc::AxisView> views(inputs.axes().size());
    for (std::uint64_t cycle = 0; loop.next(
             cycle, [&](std::uint64_t c) { return inputs.may_run(c); }, [] { return false; });
         ++cycle) {
      inputs.apply(cycle, lockstep, plc, views);
      outputs.publish(cycle, plc.cycle(cycle, views));
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
