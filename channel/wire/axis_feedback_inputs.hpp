#pragma once
// The feedback of the nodes a channel commands (its axes, then its spindles, then the slaves of
// the G114.1 groups it leads; config::fed_axes) as lockstep inputs: a node runs cycle N on the
// channel's setpoint N-1, so the channel runs cycle N only once every such node's feedback
// stamped N-1 is in. In realtime, feedback older than the deadline counts as the node being
// gone (ARCHITECTURE.md §6). An adapter between DDS and ChannelController: its callbacks run
// under the node's wake-up lock; a spindle's feedback is also its C axis's.
#include "channel/control/channel_controller.hpp"
#include "common/config/machine_config.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/process/process_node.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mcnc::channel {

class AxisFeedbackInputs {
 public:
  // The nodes take the gate's inputs 0 .. fed.size() - 1. `channel_id`: the channel's number,
  // whose refused or unkept G140-G142 requests the views tell.
  AxisFeedbackInputs(process::ProcessNode& node, std::vector<const config::AxisConfig*> fed,
                     cycle::LockstepGate& gate, int deadline_cycles, std::uint32_t channel_id);
  AxisFeedbackInputs(const AxisFeedbackInputs&) = delete;
  AxisFeedbackInputs& operator=(const AxisFeedbackInputs&) = delete;

  [[nodiscard]] std::size_t inputs() const noexcept { return fed_.size(); }
  // Every node's feedback writer matched.
  [[nodiscard]] bool discovered() const;
  // A node's writer left (under the wake-up lock: the cycle loop's "feed gone").
  [[nodiscard]] bool any_lost() const noexcept;
  // Realtime, while the channel is not in reset: feedback older than the deadline is a node
  // gone. True when a node was lost and the controller has not been told yet.
  bool check_losses(std::uint64_t cycle, bool lockstep, bool watch_deadline);
  // The feedback cycle `cycle` runs with into `views` (one per node; a view keeps its last value
  // when nothing new came), and each node lost since the last call to the controller.
  void take(std::uint64_t cycle, bool lockstep, std::vector<AxisFeedbackView>& views,
            ChannelController& controller);

 private:
  process::ProcessNode& node_;
  cycle::LockstepGate& gate_;
  std::vector<const config::AxisConfig*> fed_;
  std::size_t writers_;  // one per node (a spindle and its C axis share one)
  std::uint64_t deadline_cycles_;
  std::uint64_t self_bit_;  // the channel's bit in a node's refused_channels and full_channels
  std::vector<cycle::TrackedInput<::mcnc::AxisFeedback>> feedback_;
  dds::Reader<::mcnc::AxisFeedback> reader_;
};

}  // namespace mcnc::channel
