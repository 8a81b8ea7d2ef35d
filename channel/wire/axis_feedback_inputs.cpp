#include "channel/wire/axis_feedback_inputs.hpp"

#include "common/config/cyclic_routes.hpp"
#include "common/cycle/channel_bit.hpp"

#include <algorithm>
#include <utility>

namespace mcnc::channel {

AxisFeedbackInputs::AxisFeedbackInputs(process::ProcessNode& node,
                                       std::vector<const config::AxisConfig*> fed,
                                       cycle::LockstepGate& gate, int deadline_cycles,
                                       std::uint32_t channel_id)
    : node_(node),
      gate_(gate),
      fed_(std::move(fed)),
      writers_(config::node_keys(fed_).size()),
      deadline_cycles_(static_cast<std::uint64_t>(deadline_cycles)),
      self_bit_(cycle::channel_bit(channel_id)),
      feedback_(cycle::tracked_inputs<::mcnc::AxisFeedback>(0, fed_.size())),
      reader_(
          node.participant(), dds::Keys::of(config::node_keys(fed_)),
          [this](const ::mcnc::AxisFeedback& fb, const dds::WriterId& writer) {
            node_.wakeup().update([&] {
              for (std::size_t slot = 0; slot < fed_.size(); ++slot) {
                if (static_cast<std::uint32_t>(fed_[slot]->id) == fb.axis()) {
                  feedback_[slot].on_sample(fb, fb.cycle(), fb.event_seq(), writer, gate_);
                }
              }
            });
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              node_.wakeup().update([&] {
                for (auto& input : feedback_) {
                  input.on_unmatched(writer, gate_);
                }
              });
            }
          }) {}

bool AxisFeedbackInputs::discovered() const {
  return reader_.matched_writers() >= static_cast<int>(writers_);
}

bool AxisFeedbackInputs::any_lost() const noexcept {
  return std::any_of(feedback_.begin(), feedback_.end(),
                     [](const auto& input) { return input.lost(); });
}

bool AxisFeedbackInputs::check_losses(std::uint64_t cycle, bool lockstep, bool watch_deadline) {
  bool newly_lost = false;
  node_.wakeup().update([&] {
    for (auto& input : feedback_) {
      const ::mcnc::AxisFeedback* latest = input.latest();
      if (!lockstep && watch_deadline && latest != nullptr &&
          latest->cycle() + deadline_cycles_ < cycle) {
        input.lose(gate_);
      }
      newly_lost = newly_lost || input.loss_pending();
    }
  });
  return newly_lost;
}

namespace {

// A value the wire does not know is no probe.
ProbeSeen probe_of(std::uint8_t wire) noexcept {
  return wire <= 2 ? static_cast<ProbeSeen>(wire) : ProbeSeen::off;
}

}  // namespace

void AxisFeedbackInputs::take(std::uint64_t cycle, bool lockstep,
                              std::vector<AxisFeedbackView>& views, ChannelController& controller) {
  node_.wakeup().update([&] {
    for (std::size_t i = 0; i < feedback_.size(); ++i) {
      if (const ::mcnc::AxisFeedback* fb = feedback_[i].for_cycle(cycle, lockstep)) {
        views[i] = AxisFeedbackView{fb->cmd(),
                                    fb->act(),
                                    fb->enabled(),
                                    fb->alarm(),
                                    true,
                                    fb->owner(),
                                    fb->released_by(),
                                    fb->coupled_to(),
                                    fb->coupling_locked(),
                                    (fb->refused_channels() & self_bit_) != 0,
                                    (fb->full_channels() & self_bit_) != 0,
                                    probe_of(fb->probe()),
                                    fb->probe_pos(),
                                    fb->vel(),
                                    fb->load_known(),
                                    fb->load(),
                                    fb->probe_count(),
                                    fb->superimposed()};
      }
      if (feedback_[i].take_loss()) {
        controller.axis_lost(i);
      }
    }
  });
}

}  // namespace mcnc::channel
