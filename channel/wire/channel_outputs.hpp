#pragma once
// The channel's outputs on the wire: each cycle's setpoints and status over DDS, its G04.1
// arrivals to the other channels (sent before the status that announces them), and its events
// in the trace (state, block, block-end positions, alarm, end, sync) with alarms also published.
// An adapter between ChannelController and DDS / the trace; the shell only wires it.
#include "channel/control/channel_controller.hpp"
#include "channel/control/shared_write_log.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/trace/trace_writer.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::channel {

class ChannelOutputs {
 public:
  ChannelOutputs(process::ProcessNode& node, trace::TraceWriter& tracer,
                 const config::ChannelConfig& channel, std::vector<std::string> channel_names,
                 std::vector<const config::AxisConfig*> axes,
                 std::vector<const config::AxisConfig*> spindles, std::string program_name,
                 SharedWriteLog& writes);

  // Publishes this cycle's setpoints (axes in position, spindles in velocity: the first turns
  // as the program commands, the others stand) and status and records its events. `views` is the
  // feedback the controller saw (for the act of block-end positions).
  void publish(std::uint64_t cycle, const ChannelController& controller, const CycleOutput& out,
               std::span<const AxisFeedbackView> views, std::uint32_t block_total,
               bool program_loaded);
  // Other channels matched on the coordination event topic, for discovery.
  [[nodiscard]] int event_readers() const noexcept { return events_.matched_readers(); }
  // Every node the channel commands has matched its setpoint writer, for discovery.
  [[nodiscard]] bool setpoints_discovered() const noexcept;
  // The channel's own program is another file now (the operator selected it): the status and
  // the trace name it from now on.
  void set_program(std::string name) noexcept;

 private:
  void record(std::uint64_t cycle, const ChannelController& controller, const ChannelEvent& event,
              std::span<const AxisFeedbackView> views);
  // The next CoordinationEvent of this channel (numbered, stamped).
  CoordinationEvent event(std::uint64_t cycle, CoordinationKind kind);
  [[nodiscard]] const char* channel_name(std::uint32_t id) const;
  // The file of the executing block, for the status (cut to fit).
  void set_program_now(std::string_view name) noexcept;

  process::ProcessNode& node_;
  trace::TraceWriter& tracer_;
  const config::ChannelConfig& channel_;
  std::vector<const config::AxisConfig*> axes_;
  std::vector<const config::AxisConfig*> spindles_;
  double spindle_rpm_ = 0.0;       // signed, as last traced
  bool spindle_position_ = false;  // the first spindle under position control, as last traced
  std::size_t c_slot_ = ~std::size_t{0};  // the slot of that spindle's C axis (none: past the end)
  std::string program_name_;
  std::array<char, 64> program_now_{};
  // One per node, in its partition (config/cyclic_routes.hpp): by slot of axes_ (none for the
  // C axis, which the spindle's carries), then by spindle.
  std::vector<std::unique_ptr<dds::Writer<AxisSetpoint>>> axis_setpoints_;
  std::vector<std::unique_ptr<dds::Writer<AxisSetpoint>>> spindle_setpoints_;
  dds::Writer<::mcnc::ChannelStatus> status_;
  dds::Writer<::mcnc::CoordinationEvent> events_;
  std::uint64_t event_seq_ = 0;  // the last CoordinationEvent sent
  // G51.8's event, its table's room taken at start: a cycle that sends it does not allocate.
  ::mcnc::CoordinationEvent cam_event_;
  CallRequest out_call_{};  // this cycle's G144 call, for its trace event
  SharedWriteLog& writes_;
  std::vector<std::string> channel_names_;  // by channel id - 1
  char escaped_[512] = {};
  char escaped_name_[160] = {};
};

}  // namespace mcnc::channel
