#pragma once
// What the PLC node tells the machine each cycle (docs/plc.md): its answers to the channels'
// aux requests (FIN, refused, timed out) as events, its I/O image as its cyclic status (which
// announces the answers sent so far), and the trace's `aux` and `aux_done` lines. An adapter
// between MachinePlc's output and DDS.
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/trace/trace_writer.hpp"
#include "plcnode/logic/machine_plc.hpp"

#include <cstdint>

namespace mcnc::plc {

class PlcOutputs {
 public:
  PlcOutputs(process::ProcessNode& node, const config::MachineConfig& machine,
             trace::TraceWriter& tracer);
  PlcOutputs(const PlcOutputs&) = delete;
  PlcOutputs& operator=(const PlcOutputs&) = delete;

  // Every channel reads the status and the answers.
  [[nodiscard]] bool discovered() const;
  // The cycle's output: the requests started and answered (trace), the answers, the status.
  void publish(std::uint64_t cycle, const PlcOutput& out);

 private:
  const config::MachineConfig& machine_;
  trace::TraceWriter& tracer_;
  dds::Writer<::mcnc::PlcStatus> status_writer_;
  dds::Writer<::mcnc::AuxAck> ack_writer_;
  std::uint64_t ack_seq_ = 0;
};

}  // namespace mcnc::plc
