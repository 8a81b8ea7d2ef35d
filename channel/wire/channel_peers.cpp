#include "channel/wire/channel_peers.hpp"

#include "channel/wire/channel_mask.hpp"

namespace mcnc::channel {

namespace {

bool in_automatic_operation(::mcnc::ChannelState state) {
  return state == CH_RUNNING || state == CH_HOLD || state == CH_WAITING;
}

}  // namespace

std::vector<ChannelPeers::Peer> ChannelPeers::peers_of(const config::MachineConfig& machine,
                                                       const config::ChannelConfig& self) {
  std::vector<Peer> peers(machine.channels.size() - 1);
  std::size_t k = 0;
  for (const config::ChannelConfig& c : machine.channels) {
    if (c.id != self.id) {
      peers[k++].id = static_cast<std::uint32_t>(c.id);
    }
  }
  return peers;
}

ChannelPeers::ChannelPeers(process::ProcessNode& node, const config::MachineConfig& machine,
                           const config::ChannelConfig& self, cycle::LockstepGate& gate,
                           std::size_t first_input)
    : node_(node),
      gate_(gate),
      first_input_(first_input),
      self_(static_cast<std::uint32_t>(self.id)),
      peers_(peers_of(machine, self)),
      status_reader_(
          node.participant(),
          [this](const ::mcnc::ChannelStatus& status, const dds::WriterId& writer) {
            Peer* peer = find(status.channel());
            if (peer == nullptr) {
              return;
            }
            node_.wakeup().update([&] {
              peer->state.put(status.cycle(), status.state());
              peer->status_writer = writer;
              peer->status_writer_known = true;
              gate_.on_sample(first_input_ + static_cast<std::size_t>(peer - peers_.data()),
                              status.cycle(), status.event_seq());
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (matched) {
              return;
            }
            node_.wakeup().update([&] {
              for (std::size_t i = 0; i < peers_.size(); ++i) {
                if (peers_[i].status_writer_known && peers_[i].status_writer == writer) {
                  peers_[i].lost = true;
                  gate_.set_expected(first_input_ + i, false);
                }
              }
            });
          }),
      event_reader_(node.participant(), [this](const ::mcnc::CoordinationEvent& event,
                                               const dds::WriterId&) { on_event(event); }) {}

ChannelPeers::Peer* ChannelPeers::find(std::uint32_t channel) noexcept {
  for (Peer& p : peers_) {
    if (p.id == channel) {
      return &p;
    }
  }
  return nullptr;
}

bool ChannelPeers::discovered() const noexcept {
  // Both counts may include this channel's own writer; the gate holds every cycle until each
  // peer's status is in, so a peer matched a little later loses nothing.
  const int peers = static_cast<int>(peers_.size());
  return status_reader_.matched_writers() >= peers && event_reader_.matched_writers() >= peers;
}

void ChannelPeers::on_event(const ::mcnc::CoordinationEvent& event) {
  Peer* peer = find(event.channel());
  if (peer == nullptr) {
    return;
  }
  node_.wakeup().update([&] {
    if (peer->count == kQueue) {
      ++dropped_;
      return;
    }
    peer->queue[(peer->head + peer->count) % kQueue] = event;
    ++peer->count;
    gate_.on_event(first_input_ + static_cast<std::size_t>(peer - peers_.data()), event.seq());
  });
}

void ChannelPeers::apply(std::uint64_t cycle, bool lockstep, ChannelController& controller) {
  coordination::ChannelSet active;
  coordination::ChannelSet halted;
  node_.wakeup().with_lock([&] {
    for (Peer& peer : peers_) {
      while (peer.count > 0 && peer.queue[peer.head].cycle() < cycle) {
        const ::mcnc::CoordinationEvent& e = peer.queue[peer.head];
        if (e.kind() == COORD_SYNC_ARRIVE) {
          coordination::SyncArrival a;
          a.channel = e.channel();
          a.p = e.p();
          a.generation = e.generation();
          a.all_active = e.all_channels();
          a.participants = from_mask(e.channels());
          controller.on_arrival(a);
        }
        peer.head = (peer.head + 1) % kQueue;
        --peer.count;
      }
      const ::mcnc::ChannelState* state = cycle > 0 ? peer.state.at(cycle - 1) : nullptr;
      if (state == nullptr && !lockstep) {
        state = peer.state.latest();
      }
      if (state != nullptr && !peer.lost && in_automatic_operation(*state)) {
        active.set(peer.id);
      }
      if (state != nullptr && !peer.lost && *state == CH_ALARM) {
        halted.set(peer.id);
      }
      if (peer.lost && !peer.lost_told) {
        peer.lost_told = true;
        controller.partner_lost(peer.id);
      }
    }
  });
  controller.set_partner_states(active, halted);
}

}  // namespace mcnc::channel
