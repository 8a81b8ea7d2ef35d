#include "axisnode/canopen/heartbeat.hpp"

namespace mcnc::canopen {

HeartbeatConsumer::Event HeartbeatConsumer::on_frame(const can::CanFrame& frame,
                                                     std::uint64_t now_us) noexcept {
  if (frame.id != kHeartbeatBase + node_) {
    return Event::none;
  }
  const auto state = decode_heartbeat(frame);
  if (!state) {
    ++malformed_;
    return Event::none;
  }
  state_ = *state;
  last_us_ = now_us;
  heard_ = true;
  lost_ = false;
  return *state == NmtState::bootup ? Event::bootup : Event::heard;
}

HeartbeatConsumer::Event HeartbeatConsumer::on_time(std::uint64_t now_us) noexcept {
  if (!heard_ || lost_ || consumer_time_us_ == 0 || now_us - last_us_ <= consumer_time_us_) {
    return Event::none;
  }
  lost_ = true;
  return Event::lost;
}

bool HeartbeatProducer::due(std::uint64_t now_us, NmtState state, can::CanFrame& out) noexcept {
  if (producer_time_us_ == 0 || now_us < next_us_) {
    return false;
  }
  out = encode_heartbeat(node_, state);
  // Keep the period, not the moment of the call: a late call does not shift the next one.
  next_us_ = next_us_ == 0 ? now_us + producer_time_us_ : next_us_ + producer_time_us_;
  if (next_us_ <= now_us) {
    next_us_ = now_us + producer_time_us_;
  }
  return true;
}

}  // namespace mcnc::canopen
