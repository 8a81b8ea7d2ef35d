#pragma once
// The operator's requests to a channel (from the HMI or `--operator`, as process::ProcessNode
// queues them by cycle) applied to its ChannelController, each told to the trace. A program the
// operator selects, and MDI blocks, are checked off the cycle by the ProgramLoader; the channel
// takes the result once it stands in reset or idle (a cycle start waits for it), and drops MDI
// blocks that a reset or another run overtook. An adapter: the process's queue and the trace on
// one side, the controller and the interpreter on the other.
#include "channel/control/channel_controller.hpp"
#include "channel/interp/command_source.hpp"
#include "channel/loading/program_loader.hpp"
#include "channel/wire/channel_outputs.hpp"
#include "common/config/machine_config.hpp"
#include "common/process/process_node.hpp"
#include "common/trace/trace_writer.hpp"

#include <cstdint>
#include <optional>

namespace mcnc::channel {

class OperatorRequests {
 public:
  OperatorRequests(process::ProcessNode& node, trace::TraceWriter& tracer,
                   const config::ChannelConfig& channel, ProgramLoader& loader,
                   ChannelController& controller, interp::CommandSource& source,
                   ChannelOutputs& outputs) noexcept;

  // The requests of cycle `cycle` that concern this channel.
  void apply(std::uint64_t cycle);
  // Before the controller's cycle, once it has seen its axes: a checked program or MDI blocks
  // the channel may take now.
  void take_loaded(std::uint64_t cycle);

 private:
  void select(std::uint64_t cycle, const process::OperatorRequest& request);

  process::ProcessNode& node_;
  trace::TraceWriter& tracer_;
  const config::ChannelConfig& channel_;
  ProgramLoader& loader_;
  ChannelController& controller_;
  interp::CommandSource& source_;  // the channel's, which takes the programs checked
  ChannelOutputs& outputs_;
  std::optional<LoadedProgram> loaded_;  // checked, waiting for the channel to stand
  std::uint64_t mdi_epoch_ = 0;  // the controller's run epoch when the MDI blocks were asked for
};

}  // namespace mcnc::channel
