#pragma once
// The node of an axis that a channel couples to its master spindle (G51.2's polygon axis,
// G51.8's cam slave), as the channel's tests see it: it takes a request in the cycle after it
// was sent (the channel sees that a cycle later) and has answered `catch_up` cycles after it was
// sent, following the master locked (on) or free (off). A rig records each request the channel
// sent (record) and lets the node answer on the slave's feedback (answer), once per cycle.
#include "channel_rig.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace mcnc::channel {

template <class Request>
class CouplingNodeRig {
 public:
  CouplingNodeRig(std::uint32_t master, std::uint64_t catch_up)
      : master_(master), catch_up_(catch_up) {}

  // Before this cycle's request is recorded: true in the cycle the node's answer shows.
  bool answer(std::uint64_t cycle, AxisFeedbackView& slave) {
    if (since_ && cycle == *since_ + 1) {
      slave.coupled_to = on_ ? master_ : slave.coupled_to;
      slave.coupling_locked = false;
    }
    if (!since_ || cycle != *since_ + catch_up_) {
      return false;
    }
    slave.coupled_to = on_ ? master_ : 0;
    slave.coupling_locked = on_;
    locked_at = on_ ? cycle : locked_at;
    since_.reset();
    return true;
  }
  void record(std::uint64_t cycle, const Request& request) {
    sent.push_back(request);
    sent_at.push_back(cycle);
    on_ = request.on;
    since_ = cycle;
  }
  [[nodiscard]] bool coupling_on() const { return on_; }

  std::vector<Request> sent;
  std::vector<std::uint64_t> sent_at;
  std::uint64_t locked_at = 0;

 private:
  std::uint32_t master_;
  std::uint64_t catch_up_;
  std::optional<std::uint64_t> since_;
  bool on_ = false;
};

}  // namespace mcnc::channel
