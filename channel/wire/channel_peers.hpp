#pragma once
// What a channel hears from the other channels of its machine: their cyclic ChannelStatus (in
// automatic operation or not; in lockstep every channel runs cycle N only once every other
// channel's status stamped N-1 is in) and their CoordinationEvents (G04.1 arrivals, G144 calls
// and their releases, writes to the shared macro variables). An adapter:
// DDS callbacks fill it under the node's wake-up lock; apply() hands the controller, in the
// cycle, exactly what was sent before that cycle, so every channel decides its barriers from
// the same facts at the same cycle.
#include "channel/control/channel_controller.hpp"
#include "channel/loading/read_ahead.hpp"
#include "common/config/machine_config.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/pending_events.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/process/process_node.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcnc::channel {

class ChannelPeers {
 public:
  // The peers take the gate's inputs first_input .. first_input + channels - 2.
  ChannelPeers(process::ProcessNode& node, const config::MachineConfig& machine,
               const config::ChannelConfig& self, cycle::LockstepGate& gate,
               std::size_t first_input, ReadAhead& read_ahead);
  ChannelPeers(const ChannelPeers&) = delete;
  ChannelPeers& operator=(const ChannelPeers&) = delete;

  // Gate inputs the peers need (one per other channel).
  [[nodiscard]] std::size_t inputs() const noexcept { return peers_.size(); }
  // Every other channel's status writer and event writer matched.
  [[nodiscard]] bool discovered() const noexcept;

  // Before the controller's cycle `cycle`, under no lock: arrivals sent before `cycle` in the
  // order sent, the channels in automatic operation or in alarm at cycle-1 (realtime: as last
  // heard), and peers whose process is gone. No allocation.
  void apply(std::uint64_t cycle, bool lockstep, ChannelController& controller);
  // When the run ends, after the read-ahead stopped: the shared variable writes received and
  // not yet applied, so that the copy saved to the retained file has every channel's last
  // writes.
  void apply_remaining_writes();
  // Events that did not fit the receive queue (a peer far ahead): counted, never silent.
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_; }

 private:
  static constexpr std::size_t kQueue = 1024;  // cycles of a peer's events, also in bursts
  struct Peer {
    std::uint32_t id = 0;
    cycle::TrackedInput<::mcnc::ChannelStatus> status;
    cycle::PendingEvents<::mcnc::CoordinationEvent, kQueue> events;
  };
  static std::vector<Peer> peers_of(const config::MachineConfig& machine,
                                    const config::ChannelConfig& self, std::size_t first_input);
  [[nodiscard]] Peer* find(std::uint32_t channel) noexcept;
  void on_event(const ::mcnc::CoordinationEvent& event);
  // One event to the controller: arrivals from all, calls to this channel, releases of its
  // calls.
  void deliver(const ::mcnc::CoordinationEvent& event, ChannelController& controller);
  // A write to a shared variable, for the interpreter at its next read-ahead stop; one that
  // does not fit is counted dropped.
  void apply_write(const ::mcnc::CoordinationEvent& event);

  process::ProcessNode& node_;
  cycle::LockstepGate& gate_;
  std::uint32_t self_;
  ReadAhead& read_ahead_;  // the others' writes to the machine-wide variables go there
  std::vector<Peer> peers_;
  std::uint64_t dropped_ = 0;
  std::uint64_t dropped_told_ = 0;
  dds::Reader<::mcnc::ChannelStatus> status_reader_;
  dds::Reader<::mcnc::CoordinationEvent> event_reader_;
};

}  // namespace mcnc::channel
