#include "channel/wire/plc_link.hpp"

#include <cstdio>

namespace mcnc::channel {

PlcLink::PlcLink(process::ProcessNode& node, cycle::LockstepGate& gate, std::size_t input,
                 std::uint32_t self)
    : node_(node),
      gate_(gate),
      self_(self),
      status_(input),
      status_reader_(
          node.participant(),
          [this](const ::mcnc::PlcStatus& status, const dds::WriterId& writer) {
            node_.wakeup().update([&] {
              status_.on_sample(status, status.cycle(), status.event_seq(), writer, gate_);
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              node_.wakeup().update([&] { status_.on_unmatched(writer, gate_); });
            }
          }),
      ack_reader_(node.participant(), [this](const ::mcnc::AuxAck& ack, const dds::WriterId&) {
        node_.wakeup().update([&] {
          status_.on_event(ack.seq(), gate_);
          if (ack.channel() == self_) {
            (void)answers_.push(ack, ack.cycle());
          }
        });
      }) {}

bool PlcLink::discovered() const noexcept {
  return status_reader_.matched_writers() >= 1 && ack_reader_.matched_writers() >= 1;
}

void PlcLink::apply(std::uint64_t cycle, bool lockstep, ChannelController& controller) {
  node_.wakeup().with_lock([&] {
    if (const ::mcnc::PlcStatus* status = status_.for_cycle(cycle, lockstep)) {
      controller.set_plc_inputs(status->inputs());
    }
    answers_.take_due(cycle, [&](const ::mcnc::AuxAck& ack) {
      PlcAnswer answer;
      answer.id = ack.aux_id();
      answer.outcome = static_cast<AuxOutcome>(static_cast<int>(ack.outcome()));
      std::snprintf(answer.reason.data(), answer.reason.size(), "%s", ack.reason().c_str());
      controller.on_aux_answer(answer);
    });
    if (status_.take_loss()) {
      controller.plc_lost();
    }
  });
}

}  // namespace mcnc::channel
