#include "canopen/heartbeat.hpp"

namespace mcnc::canopen {

void HeartbeatConsumer::heard(std::uint64_t now) noexcept {
  last_ = now;
  heard_ = true;
  lost_ = false;
}

void HeartbeatConsumer::restart(std::uint64_t now) noexcept {
  if (heard_) {
    last_ = now;
    lost_ = false;
  }
}

HeartbeatConsumer::Event HeartbeatConsumer::on_frame(const can::CanFrame& frame,
                                                     std::uint64_t now) noexcept {
  if (frame.id != kHeartbeatBase + node_) {
    return Event::none;
  }
  const auto state = decode_heartbeat(frame);
  if (!state) {
    ++malformed_;
    return Event::none;
  }
  state_ = *state;
  heard(now);
  return *state == NmtState::bootup ? Event::bootup : Event::heard;
}

HeartbeatConsumer::Event HeartbeatConsumer::on_time(std::uint64_t now,
                                                    std::uint64_t slack) noexcept {
  if (!heard_ || lost_ || consumer_time_ == 0 || now - last_ <= consumer_time_ + slack) {
    return Event::none;
  }
  lost_ = true;
  return Event::lost;
}

bool HeartbeatProducer::due(std::uint64_t now, NmtState state, can::CanFrame& out) noexcept {
  if (producer_time_ == 0 || (started_ && now < next_)) {
    return false;
  }
  out = encode_heartbeat(node_, state);
  // Keep the period, not the moment of the call: a late call does not shift the next one.
  next_ = started_ ? next_ + producer_time_ : now + producer_time_;
  if (next_ <= now) {
    next_ = now + producer_time_;
  }
  started_ = true;
  return true;
}

}  // namespace mcnc::canopen
