#include "canopen/cia402/node_startup.hpp"

#include "canopen/frames.hpp"
#include "canopen/sdo_abort.hpp"

#include <cstdio>
#include <cstring>

namespace mcnc::canopen {

const char* object_name(std::uint16_t index) noexcept {
  if (index >= 0x1400 && index <= 0x1403) {
    return "RPDO communication parameter";
  }
  if (index >= 0x1600 && index <= 0x1603) {
    return "RPDO mapping";
  }
  if (index >= 0x1800 && index <= 0x1803) {
    return "TPDO communication parameter";
  }
  if (index >= 0x1A00 && index <= 0x1A03) {
    return "TPDO mapping";
  }
  switch (index) {
    case 0x1000:
      return "device type";
    case 0x1008:
      return "device name";
    case 0x1017:
      return "producer heartbeat time";
    case 0x6040:
      return "controlword";
    case 0x6041:
      return "statusword";
    case 0x6060:
      return "modes of operation";
    case 0x6061:
      return "modes of operation display";
    case 0x6064:
      return "position actual value";
    case 0x606C:
      return "velocity actual value";
    case 0x607A:
      return "target position";
    case 0x607C:
      return "home offset";
    case 0x6085:
      return "quick stop deceleration";
    case 0x6098:
      return "homing method";
    case 0x60F4:
      return "following error actual value";
    case 0x60FF:
      return "target velocity";
    default:
      return "object";
  }
}

NodeStartup::NodeStartup(const NodeStartupConfig& config) noexcept
    : config_(config), sdo_(config.node, config.sdo_timeout_us) {
  // Everything written after the boot-up, in order.
  const auto add = [&](std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                       std::uint8_t size) {
    if (write_count_ < writes_.size()) {
      writes_[write_count_++] = SdoWrite{index, sub, value, size};
    }
  };
  add(0x1017, 0, config.heartbeat_ms, 2);
  const struct {
    const PdoMapping* pdo;
    const char* name;
  } pdos[] = {{&config.pdos.rpdo1, "RPDO1"},
              {&config.pdos.rpdo2, "RPDO2"},
              {&config.pdos.tpdo1, "TPDO1"},
              {&config.pdos.tpdo2, "TPDO2"}};
  for (const auto& [pdo, name] : pdos) {
    if (const char* why = pdo_error(*pdo); why != nullptr && refused_pdo_ == nullptr) {
      refused_pdo_ = name;
      refused_why_ = why;
    }
    SdoWriteList list;
    if (pdo->count > 0 && pdo_configuration(config.node, *pdo, list)) {
      for (std::size_t i = 0; i < list.count; ++i) {
        add(list.writes[i].index, list.writes[i].sub, list.writes[i].value, list.writes[i].size);
      }
    }
  }
  if (config.quick_stop_deceleration != 0) {
    add(0x6085, 0, config.quick_stop_deceleration, 4);
  }
  if (config.homing_method != 0) {
    add(0x6098, 0, static_cast<std::uint8_t>(config.homing_method), 1);
    add(0x607C, 0, static_cast<std::uint32_t>(config.home_offset), 4);
  }
  add(0x6060, 0, static_cast<std::uint8_t>(config.mode), 1);
}

bool NodeStartup::begin(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (refused_pdo_ != nullptr) {
    status_ = Status::failed;
    std::snprintf(error_.data(), error_.size(), "node %u: %s cannot be mapped: %s", config_.node,
                  refused_pdo_, refused_why_);
    return false;
  }
  status_ = Status::running;
  phase_ = Phase::bootup;
  attempts_ = 1;
  attempt_started_us_ = now_us;
  next_write_ = 0;
  sdo_tries_ = 0;
  retry_pending_ = false;
  error_[0] = '\0';
  out = encode_nmt(NmtCommand::reset_communication, config_.node);
  return true;
}

void NodeStartup::fail_sdo(const char* doing) noexcept {
  status_ = Status::failed;
  const std::uint32_t code = sdo_.abort_code();
  std::snprintf(error_.data(), error_.size(),
                "node %u: %s 0x%04X:%02X (%s) %s: %s (SDO abort 0x%08X)", config_.node, doing,
                sdo_.index(), sdo_.sub(), object_name(sdo_.index()),
                sdo_.aborted_by_server() ? "was refused" : "failed", sdo_abort_text(code), code);
  if (sdo_tries_ > 1) {
    const std::size_t used = std::strlen(error_.data());
    std::snprintf(error_.data() + used, error_.size() - used, " %d times", sdo_tries_);
  }
}

// The request of the current step: the device type, or the write before next_write_.
bool NodeStartup::send_request(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (phase_ == Phase::device_type) {
    return sdo_.upload(0x1000, 0, now_us, out);
  }
  const SdoWrite& w = writes_[next_write_ - 1];
  const std::uint8_t bytes[4] = {
      static_cast<std::uint8_t>(w.value), static_cast<std::uint8_t>(w.value >> 8),
      static_cast<std::uint8_t>(w.value >> 16), static_cast<std::uint8_t>(w.value >> 24)};
  return sdo_.download(w.index, w.sub, bytes, w.size, now_us, out);
}

// The next SDO request after the one that just completed, or NMT start after the last.
bool NodeStartup::next_request(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (next_write_ >= write_count_) {
    phase_ = Phase::started;
    status_ = Status::done;
    out = encode_nmt(NmtCommand::start, config_.node);
    return true;
  }
  ++next_write_;
  sdo_tries_ = 1;
  return send_request(now_us, out);
}

bool NodeStartup::on_frame(const can::CanFrame& in, std::uint64_t now_us,
                           can::CanFrame& out) noexcept {
  if (status_ != Status::running) {
    return false;
  }
  if (phase_ == Phase::bootup) {
    if (in.id != kHeartbeatBase + config_.node || decode_heartbeat(in) != NmtState::bootup) {
      return false;
    }
    if (config_.device_type != 0) {
      phase_ = Phase::device_type;
      sdo_tries_ = 1;
      return send_request(now_us, out);
    }
    phase_ = Phase::writes;
    return next_request(now_us, out);
  }
  if (retry_pending_) {
    return false;  // a late answer to the request given up on; it is sent again
  }
  const bool send = sdo_.on_frame(in, now_us, out);
  if (sdo_.state() == SdoClient::State::aborted) {
    fail_sdo(phase_ == Phase::device_type ? "reading" : "writing");
    return send;  // our abort, if the client sent one
  }
  if (sdo_.state() != SdoClient::State::done) {
    return send;
  }
  if (phase_ == Phase::device_type) {
    const SdoValue& v = sdo_.value();
    const std::uint32_t type = v.size >= 4 ? static_cast<std::uint32_t>(v.bytes[0]) |
                                                 (static_cast<std::uint32_t>(v.bytes[1]) << 8) |
                                                 (static_cast<std::uint32_t>(v.bytes[2]) << 16) |
                                                 (static_cast<std::uint32_t>(v.bytes[3]) << 24)
                                           : 0;
    if (type != config_.device_type) {
      status_ = Status::failed;
      std::snprintf(
          error_.data(), error_.size(),
          "node %u: device type 0x1000 is 0x%08X, expected 0x%08X (a CiA 402 servo drive)",
          config_.node, type, config_.device_type);
      return false;
    }
    phase_ = Phase::writes;
  }
  return next_request(now_us, out);
}

bool NodeStartup::on_time(std::uint64_t now_us, can::CanFrame& out) noexcept {
  if (status_ != Status::running) {
    return false;
  }
  if (phase_ == Phase::bootup) {
    if (now_us - attempt_started_us_ <= config_.bootup_timeout_us) {
      return false;
    }
    if (attempts_ >= config_.bootup_attempts) {
      status_ = Status::failed;
      std::snprintf(error_.data(), error_.size(),
                    "node %u: no boot-up after %d NMT resets of communication", config_.node,
                    attempts_);
      return false;
    }
    ++attempts_;
    attempt_started_us_ = now_us;
    out = encode_nmt(NmtCommand::reset_communication, config_.node);
    return true;
  }
  if (retry_pending_) {
    retry_pending_ = false;
    ++sdo_tries_;
    return send_request(now_us, out);
  }
  const bool send = sdo_.on_time(now_us, out);
  if (sdo_.state() == SdoClient::State::aborted) {
    if (!sdo_.aborted_by_server() && sdo_.abort_code() == sdo_abort::kTimeout &&
        sdo_tries_ < config_.sdo_attempts) {
      retry_pending_ = true;
      return send;
    }
    fail_sdo(phase_ == Phase::device_type ? "reading" : "writing");
  }
  return send;
}

}  // namespace mcnc::canopen
