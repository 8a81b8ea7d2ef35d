#include "channel/wire/plc_link.hpp"

#include <cstdio>

namespace mcnc::channel {

PlcLink::PlcLink(process::ProcessNode& node, cycle::LockstepGate& gate, std::size_t input,
                 std::uint32_t self)
    : node_(node),
      gate_(gate),
      input_(input),
      self_(self),
      status_reader_(
          node.participant(),
          [this](const ::mcnc::PlcStatus& status, const dds::WriterId& writer) {
            node_.wakeup().update([&] {
              gate_.on_sample(input_, status.cycle(), status.event_seq());
              writer_ = writer;
              writer_known_ = true;
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (matched) {
              return;
            }
            node_.wakeup().update([&] {
              if (writer_known_ && writer == writer_) {
                lost_ = true;
                gate_.set_expected(input_, false);
              }
            });
          }),
      ack_reader_(node.participant(), [this](const ::mcnc::AuxAck& ack, const dds::WriterId&) {
        node_.wakeup().update([&] {
          gate_.on_event(input_, ack.seq());
          if (ack.channel() == self_ && count_ < kQueue) {
            queue_[count_++] = ack;  // one request at a time: never more than a few
          }
        });
      }) {}

bool PlcLink::discovered() const noexcept {
  return status_reader_.matched_writers() >= 1 && ack_reader_.matched_writers() >= 1;
}

void PlcLink::apply(std::uint64_t cycle, ChannelController& controller) {
  node_.wakeup().with_lock([&] {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count_; ++i) {
      const ::mcnc::AuxAck& ack = queue_[i];
      if (ack.cycle() >= cycle) {
        queue_[kept++] = ack;
        continue;
      }
      AuxAnswer answer;
      answer.id = ack.aux_id();
      answer.outcome = static_cast<AuxOutcome>(static_cast<int>(ack.outcome()));
      std::snprintf(answer.reason.data(), answer.reason.size(), "%s", ack.reason().c_str());
      controller.on_aux_answer(answer);
    }
    count_ = kept;
    if (lost_ && !lost_told_) {
      lost_told_ = true;
      controller.plc_lost();
    }
  });
}

}  // namespace mcnc::channel
