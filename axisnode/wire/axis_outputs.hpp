#pragma once
// What an axis node tells the machine each cycle (ARCHITECTURE.md §5, docs/trace.md): its
// feedback over DDS, its alarms, and its trace events, formatted from what the AxisNode
// returns. An adapter: names come from the machine file, values from the core and the drive.
#include "axisnode/link/drive_interface.hpp"
#include "axisnode/node/axis_node.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/trace/trace_writer.hpp"

#include <cstdint>

namespace mcnc::axisnode {

class AxisOutputs {
 public:
  AxisOutputs(process::ProcessNode& node, const config::MachineConfig& machine,
              const config::AxisConfig& axis, trace::TraceWriter& tracer, int trace_pos_every);
  AxisOutputs(const AxisOutputs&) = delete;
  AxisOutputs& operator=(const AxisOutputs&) = delete;

  // Every channel that reads this axis's feedback has matched.
  [[nodiscard]] bool discovered() const;

  // Cycle 0: the configured owner, and a coupling from power-on.
  void trace_start(const AxisNode& core) noexcept;
  // What take_inputs() decided: couplings, the owner, whom the node follows.
  void trace_decisions(std::uint64_t cycle, const AxisNode& core) noexcept;
  void trace_reset(std::uint64_t cycle) noexcept;
  // Realtime, every K cycles: when the cycle was due on this host's clock, the host's offset
  // against machine time, and how late the wake-up came (the hosts' alignment, from the trace);
  // the SYNC producer's also the latest SYNC it sent (`sync`, null for the others).
  void trace_tick(std::uint64_t cycle, std::int64_t due_ns, std::int64_t woke_ns,
                  const SentSync* sync = nullptr) noexcept;
  // The cycle's feedback (with the drive's own values where TPDO2 carries them), then its mode
  // and state changes, a new alarm (raised to the machine too) and every K cycles its position.
  // `in_run` false: a stopping node after its run (drive_stop.hpp): its feedback still goes
  // out, but its stop is no part of the run's record: no alarm raised to the machine (the
  // caller reports what happened meanwhile) and nothing traced, so that a run's trace ends
  // where it ended before the node stopped its drive.
  void publish(std::uint64_t cycle, const AxisNode& core, const DriveSample& drive,
               bool in_run = true) noexcept;

 private:
  [[nodiscard]] const char* channel_name(std::uint32_t id) const noexcept;
  [[nodiscard]] const char* axis_name(std::uint32_t id) const noexcept;

  process::ProcessNode& node_;
  const config::MachineConfig& machine_;
  const config::AxisConfig& axis_;
  trace::TraceWriter& tracer_;
  int trace_pos_every_;
  int fed_channels_;
  dds::Writer<::mcnc::AxisFeedback> feedback_;
};

}  // namespace mcnc::axisnode
