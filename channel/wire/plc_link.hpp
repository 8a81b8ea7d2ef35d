#pragma once
// The channel's side of the PLC node (docs/plc.md): the PLC's cyclic status as a lockstep input
// (a channel runs cycle N with the PLC's status N-1 and the answers it announces), and the
// answers to this channel's aux requests, applied from the cycle after they were sent. An
// adapter between DDS and ChannelController.
#include "channel/control/channel_controller.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/pending_events.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/process/process_node.hpp"

#include <cstddef>
#include <cstdint>

namespace mcnc::channel {

class PlcLink {
 public:
  // The PLC takes the gate's input `input`.
  PlcLink(process::ProcessNode& node, cycle::LockstepGate& gate, std::size_t input,
          std::uint32_t self);
  PlcLink(const PlcLink&) = delete;
  PlcLink& operator=(const PlcLink&) = delete;

  // The PLC's status writer and answer writer matched.
  [[nodiscard]] bool discovered() const noexcept;
  // Before the controller's cycle `cycle`: the PLC's inputs stamped cycle-1, the answers sent
  // before it; a PLC that is gone.
  void apply(std::uint64_t cycle, bool lockstep, ChannelController& controller);

 private:
  process::ProcessNode& node_;
  cycle::LockstepGate& gate_;
  std::uint32_t self_;
  cycle::TrackedInput<::mcnc::PlcStatus> status_;
  // One request at a time: a few answers at most.
  cycle::PendingEvents<::mcnc::AuxAck, 64> answers_;
  dds::Reader<::mcnc::PlcStatus> status_reader_;
  dds::Reader<::mcnc::AuxAck> ack_reader_;
};

}  // namespace mcnc::channel
