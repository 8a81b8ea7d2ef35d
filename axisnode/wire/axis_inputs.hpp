#pragma once
// What an axis node hears over DDS (ARCHITECTURE.md §5): the setpoints of the channels that may
// own its axis, their coordination events (G140-G142, G51.4, G114.1), and, for a slave, its
// coupling channel's status and its masters' feedback. An adapter: its callbacks translate each
// sample into the core's types and hand it to the AxisNode under the node's wake-up lock, which
// the cycle also holds when it takes its inputs.
#include "axisnode/node/axis_node.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"

#include <optional>

namespace mcnc::axisnode {

class AxisInputs {
 public:
  AxisInputs(process::ProcessNode& node, const config::MachineConfig& machine,
             const config::AxisConfig& axis, AxisNode& core);
  AxisInputs(const AxisInputs&) = delete;
  AxisInputs& operator=(const AxisInputs&) = delete;

  // Every writer the node expects has matched: each candidate's setpoints and events, and a
  // slave's coupling channel and masters.
  [[nodiscard]] bool discovered() const;
  // Setpoint writers still matched (the channels have not all left).
  [[nodiscard]] int setpoint_writers() const { return setpoints_.matched_writers(); }

 private:
  process::ProcessNode& node_;
  AxisNode& core_;
  dds::Reader<::mcnc::AxisSetpoint> setpoints_;
  std::optional<dds::Reader<::mcnc::CoordinationEvent>> events_;
  std::optional<dds::Reader<::mcnc::ChannelStatus>> sync_channel_;
  std::optional<dds::Reader<::mcnc::AxisFeedback>> sync_master_;
  std::optional<dds::Reader<::mcnc::AxisFeedback>> leaders_;
};

}  // namespace mcnc::axisnode
