#include "plcnode/wire/plc_outputs.hpp"

#include <cstdio>

namespace mcnc::plc {

namespace {

// "M10", "T0101": the code as the program wrote it.
void code_text(const AuxRequest& r, char (&text)[16]) {
  if (r.kind == AuxKind::t_code) {
    std::snprintf(text, sizeof text, "T%04d", r.code);
  } else {
    std::snprintf(text, sizeof text, "M%02d", r.code);
  }
}

}  // namespace

PlcOutputs::PlcOutputs(process::ProcessNode& node, const config::MachineConfig& machine,
                       trace::TraceWriter& tracer)
    : machine_(machine),
      tracer_(tracer),
      status_writer_(node.participant()),
      ack_writer_(node.participant()) {}

bool PlcOutputs::discovered() const {
  const auto channels = static_cast<int>(machine_.channels.size());
  return status_writer_.matched_readers() >= channels && ack_writer_.matched_readers() >= channels;
}

void PlcOutputs::publish(std::uint64_t cycle, const PlcOutput& out) {
  char code[16];
  for (std::size_t i = 0; i < out.started_count; ++i) {
    const AuxRequest& r = out.started[i];
    code_text(r, code);
    tracer_.emit(cycle, "aux", "\"ch\":\"%s\",\"code\":\"%s\"",
                 machine_.channels[r.channel - 1].name.c_str(), code);
  }
  for (std::size_t i = 0; i < out.answer_count; ++i) {
    const AuxResult& a = out.answers[i];
    ::mcnc::AuxAck ack;
    ack.seq(++ack_seq_);
    ack.cycle(cycle);
    ack.channel(a.request.channel);
    ack.aux_id(a.request.id);
    ack.kind(a.request.kind == AuxKind::t_code ? ::mcnc::AUX_T : ::mcnc::AUX_M);
    ack.code(a.request.code);
    ack.outcome(static_cast<::mcnc::AuxOutcome>(static_cast<int>(a.outcome)));
    ack.reason(a.reason.data());
    ack_writer_.write(ack);
    code_text(a.request, code);
    tracer_.emit(cycle, "aux_done", "\"ch\":\"%s\",\"code\":\"%s\",\"outcome\":\"%s\"%s%s%s",
                 machine_.channels[a.request.channel - 1].name.c_str(), code, to_string(a.outcome),
                 a.reason[0] != 0 ? ",\"reason\":\"" : "", a.reason.data(),
                 a.reason[0] != 0 ? "\"" : "");
  }
  ::mcnc::PlcStatus status;
  status.cycle(cycle);
  status.event_seq(ack_seq_);
  status.outputs(out.outputs);
  status.inputs(out.inputs);
  status.busy(static_cast<std::uint32_t>(out.busy));
  status_writer_.write(status);
}

}  // namespace mcnc::plc
