#include "channel/wire/channel_peers.hpp"

#include "channel/wire/channel_mask.hpp"
#include "common/config/cyclic_routes.hpp"

namespace mcnc::channel {

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
                           std::size_t first_input, interp::macro::VariableStore& shared_variables)
    : node_(node),
      gate_(gate),
      first_input_(first_input),
      self_(static_cast<std::uint32_t>(self.id)),
      shared_(shared_variables),
      peers_(peers_of(machine, self)),
      status_reader_(
          node.participant(), dds::Partitions::of(config::other_channels(machine, self)),
          [this](const ::mcnc::ChannelStatus& status, const dds::WriterId& writer) {
            Peer* peer = find(status.channel());
            if (peer == nullptr) {
              return;
            }
            node_.wakeup().update([&] {
              peer->status.put(status.cycle(), status);
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
      ++dropped_;  // counted as received, so lockstep goes on to the alarm
    } else {
      peer->queue[(peer->head + peer->count) % kQueue] = event;
      ++peer->count;
    }
    gate_.on_event(first_input_ + static_cast<std::size_t>(peer - peers_.data()), event.seq());
  });
}

void ChannelPeers::apply(std::uint64_t cycle, bool lockstep, ChannelController& controller) {
  node_.wakeup().with_lock([&] {
    for (Peer& peer : peers_) {
      while (peer.count > 0 && peer.queue[peer.head].cycle() < cycle) {
        deliver(peer.queue[peer.head], controller);
        peer.head = (peer.head + 1) % kQueue;
        --peer.count;
      }
      const ::mcnc::ChannelStatus* status = cycle > 0 ? peer.status.at(cycle - 1) : nullptr;
      if (status == nullptr && !lockstep) {
        status = peer.status.latest();
      }
      PartnerStatus p;
      if (status != nullptr && !peer.lost) {
        p.known = true;
        p.state = static_cast<ChannelState>(static_cast<int>(status->state()));
        p.call_id = status->call_id();
        p.call_caller = status->call_caller();
      }
      controller.set_partner(peer.id, p);
      if (peer.lost && !peer.lost_told) {
        peer.lost_told = true;
        controller.partner_lost(peer.id);
      }
    }
    if (dropped_ > dropped_told_) {
      dropped_told_ = dropped_;
      controller.coordination_lost();
    }
  });
}

void ChannelPeers::apply_remaining_writes() {
  node_.wakeup().with_lock([&] {
    for (Peer& peer : peers_) {
      for (; peer.count > 0; --peer.count, peer.head = (peer.head + 1) % kQueue) {
        const ::mcnc::CoordinationEvent& e = peer.queue[peer.head];
        if (e.kind() == COORD_VAR_WRITE) {
          apply_write(e);
        }
      }
    }
  });
}

void ChannelPeers::apply_write(const ::mcnc::CoordinationEvent& e) const {
  if (interp::macro::VariableStore::is_shared(e.var())) {
    (void)shared_.write(e.var(), e.value_null() ? interp::macro::MacroValue::null()
                                                : interp::macro::MacroValue::of(e.value()));
  }
}

void ChannelPeers::deliver(const ::mcnc::CoordinationEvent& e,
                           ChannelController& controller) const {
  switch (e.kind()) {
    case COORD_SYNC_ARRIVE: {
      coordination::SyncArrival a;
      a.channel = e.channel();
      a.p = e.p();
      a.generation = e.generation();
      a.all_active = e.all_channels();
      a.participants = from_mask(e.channels());
      controller.on_arrival(a);
      break;
    }
    case COORD_SUBCALL: {
      if (e.target() != self_) {
        break;
      }
      SubCall call;
      call.call_id = e.call_id();
      call.caller = e.caller();
      call.target = e.target();
      call.program = e.program();
      call.wait = e.wait();
      call.repeat = e.repeat();
      for (std::size_t i = 0; i < call.args.size(); ++i) {
        call.args[i] = e.args()[i];
      }
      call.args_given = e.args_given();
      controller.on_call(call);
      break;
    }
    case COORD_VAR_WRITE:
      apply_write(e);
      break;
    case COORD_SUBCALL_RELEASE:
      if (e.caller() == self_) {
        controller.on_call_release(
            CallRelease{e.call_id(), e.caller(), e.channel(),
                        static_cast<CallOutcome>(static_cast<int>(e.outcome()))});
      }
      break;
    case COORD_AXIS_REQUEST:
    case COORD_AUX_REQUEST:
    case COORD_SPINDLE_SYNC:
    case COORD_AXIS_SYNC:
      break;  // for the axis nodes and the PLC: their answers come on their own topics
  }
}

}  // namespace mcnc::channel
