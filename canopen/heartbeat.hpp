#pragma once
// Heartbeat (CiA 301 §7.2.8.3.2): the producer sends its NMT state every producer time; a
// consumer that hears nothing from a node for its consumer time reports it lost, once, until
// the node is heard again. A boot-up (state 0) is told apart. Pure: frames and time in; time
// in any monotonic unit (microseconds, or cycles in a lockstep run), the same for both.
#include "canopen/frames.hpp"

#include <cstdint>

namespace mcnc::canopen {

class HeartbeatConsumer {
 public:
  enum class Event : std::uint8_t { none, heard, bootup, lost };

  HeartbeatConsumer(std::uint8_t node, std::uint64_t consumer_time) noexcept
      : node_(node), consumer_time_(consumer_time) {}

  // A frame from the bus: heard / bootup for this node's heartbeat, none for anything else.
  Event on_frame(const can::CanFrame& frame, std::uint64_t now) noexcept;
  // A heartbeat of the node was heard (told by whoever decodes the frames).
  void heard(std::uint64_t now) noexcept;
  // lost once when the consumer time, and `slack` beyond it, has passed since the last
  // heartbeat; the time starts at the first heartbeat (CiA 301: monitoring starts with the first
  // one received).
  Event on_time(std::uint64_t now, std::uint64_t slack = 0) noexcept;
  // Monitoring starts again from `now` (an operator reset): a node heard before and still
  // silent is reported lost again after the consumer time.
  void restart(std::uint64_t now) noexcept;

  [[nodiscard]] bool alive() const noexcept { return heard_ && !lost_; }
  [[nodiscard]] NmtState state() const noexcept { return state_; }
  [[nodiscard]] std::uint64_t malformed() const noexcept { return malformed_; }

 private:
  std::uint8_t node_;
  std::uint64_t consumer_time_;
  std::uint64_t last_ = 0;
  bool heard_ = false;
  bool lost_ = false;
  NmtState state_ = NmtState::bootup;
  std::uint64_t malformed_ = 0;
};

class HeartbeatProducer {
 public:
  HeartbeatProducer(std::uint8_t node, std::uint64_t producer_time) noexcept
      : node_(node), producer_time_(producer_time) {}
  // True with the heartbeat in `out` when one is due (the first at once). A producer time of
  // 0 disables it.
  bool due(std::uint64_t now, NmtState state, can::CanFrame& out) noexcept;

 private:
  std::uint8_t node_;
  std::uint64_t producer_time_;
  std::uint64_t next_ = 0;
  bool started_ = false;
};

}  // namespace mcnc::canopen
