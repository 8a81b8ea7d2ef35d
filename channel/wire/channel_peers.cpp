#include "channel/wire/channel_peers.hpp"

#include "channel/wire/channel_mask.hpp"
#include "common/config/cyclic_routes.hpp"

#include <limits>

namespace mcnc::channel {

std::vector<ChannelPeers::Peer> ChannelPeers::peers_of(const config::MachineConfig& machine,
                                                       const config::ChannelConfig& self,
                                                       std::size_t first_input) {
  std::vector<Peer> peers(machine.channels.size() - 1);
  std::size_t k = 0;
  for (const config::ChannelConfig& c : machine.channels) {
    if (c.id != self.id) {
      peers[k].id = static_cast<std::uint32_t>(c.id);
      peers[k].status = cycle::TrackedInput<::mcnc::ChannelStatus>(first_input + k);
      ++k;
    }
  }
  return peers;
}

ChannelPeers::ChannelPeers(process::ProcessNode& node, const config::MachineConfig& machine,
                           const config::ChannelConfig& self, cycle::LockstepGate& gate,
                           std::size_t first_input, ReadAhead& read_ahead)
    : node_(node),
      gate_(gate),
      self_(static_cast<std::uint32_t>(self.id)),
      read_ahead_(read_ahead),
      peers_(peers_of(machine, self, first_input)),
      status_reader_(
          node.participant(), dds::Keys::of(config::other_channels(machine, self)),
          [this](const ::mcnc::ChannelStatus& status, const dds::WriterId& writer) {
            Peer* peer = find(status.channel());
            if (peer == nullptr) {
              return;
            }
            node_.wakeup().update([&] {
              peer->status.on_sample(status, status.cycle(), status.event_seq(), writer, gate_);
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (matched) {
              return;
            }
            node_.wakeup().update([&] {
              for (Peer& peer : peers_) {
                peer.status.on_unmatched(writer, gate_);
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
    if (!peer->events.push(event, event.cycle())) {
      ++dropped_;  // counted as received, so lockstep goes on to the alarm
    }
    peer->status.on_event(event.seq(), gate_);
  });
}

void ChannelPeers::apply(std::uint64_t cycle, bool lockstep, ChannelController& controller) {
  node_.wakeup().with_lock([&] {
    for (Peer& peer : peers_) {
      peer.events.take_due(
          cycle, [&](const ::mcnc::CoordinationEvent& event) { deliver(event, controller); });
      const ::mcnc::ChannelStatus* status = peer.status.for_cycle(cycle, lockstep);
      PartnerStatus p;
      if (status != nullptr && !peer.status.lost()) {
        p.known = true;
        p.state = static_cast<ChannelState>(static_cast<int>(status->state()));
        p.call_id = status->call_id();
        p.call_caller = status->call_caller();
      }
      controller.set_partner(peer.id, p);
      if (peer.status.take_loss()) {
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
      peer.events.take_due(std::numeric_limits<std::uint64_t>::max(),
                           [&](const ::mcnc::CoordinationEvent& e) {
                             if (e.kind() == COORD_VAR_WRITE) {
                               apply_write(e);
                             }
                           });
    }
  });
}

void ChannelPeers::apply_write(const ::mcnc::CoordinationEvent& e) {
  if (interp::macro::VariableStore::is_shared(e.var()) &&
      !read_ahead_.peer_write(e.var(), e.value_null() ? interp::macro::MacroValue::null()
                                                      : interp::macro::MacroValue::of(e.value()))) {
    ++dropped_;
  }
}

void ChannelPeers::deliver(const ::mcnc::CoordinationEvent& e, ChannelController& controller) {
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
      CallRequest call;
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
    case COORD_POLYGON_SYNC:
    case COORD_CAM_SYNC:
    case COORD_EGB_SYNC:
      break;  // for the axis nodes and the PLC: their answers come on their own topics
  }
}

}  // namespace mcnc::channel
