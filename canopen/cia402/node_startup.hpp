#pragma once
// How a master brings one CiA 402 node up (CiA 301 boot-up, then configuration by SDO):
// NMT reset communication, wait for the boot-up, check the device type, set the node's
// heartbeat producer time, map its PDOs, set the mode of operation, NMT start. A refused or
// unanswered SDO stops the start-up with a message naming the object and the reason. Pure:
// frames and time in, frames out, no allocation.
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/sdo_client.hpp"

#include <array>
#include <cstdint>

namespace mcnc::canopen {

struct NodeStartupConfig {
  std::uint8_t node = 1;
  std::uint32_t device_type = 0x00020192;  // CiA 402 servo drive; 0: not checked
  std::uint16_t heartbeat_ms = 100;        // the node's producer time (0x1017); 0: off
  PdoLayout pdos = axis_pdos(false, false, false);
  std::int8_t mode = 8;                       // 0x6060: 8 CSP, 9 CSV, 6 homing
  std::int8_t homing_method = 0;              // 0x6098 written when not 0 (with 0x607C)
  std::int32_t home_offset = 0;               // 0x607C, counts
  std::uint32_t quick_stop_deceleration = 0;  // 0x6085 written when not 0, counts/s^2
  std::uint64_t bootup_timeout_us = 500000;   // per attempt; the reset is repeated
  int bootup_attempts = 4;
  std::uint64_t sdo_timeout_us = 100000;
  // A request the node did not answer in time is aborted and sent again, up to this many
  // times in all: one lost frame on a loaded bus does not fail the start-up. Every write of
  // the start-up sets a value, so sending it twice does no harm.
  int sdo_attempts = 3;
};

class NodeStartup {
 public:
  enum class Status : std::uint8_t { running, done, failed };

  explicit NodeStartup(const NodeStartupConfig& config) noexcept;

  // Starts over: `out` is the NMT reset communication to send. False, and failed with nothing to
  // send, when a PDO of the layout cannot be mapped (error() names it and says why, e.g. longer
  // than a CAN frame's 8 bytes).
  bool begin(std::uint64_t now_us, can::CanFrame& out) noexcept;
  // A frame from the bus; true when `out` must be sent.
  bool on_frame(const can::CanFrame& in, std::uint64_t now_us, can::CanFrame& out) noexcept;
  // Time passes; true when `out` must be sent (a repeated reset, an SDO abort).
  bool on_time(std::uint64_t now_us, can::CanFrame& out) noexcept;

  [[nodiscard]] Status status() const noexcept { return status_; }
  // Why it failed, e.g. "node 3: writing 0x6060:00 (modes of operation) = 8 was refused:
  // value of parameter written too high (SDO abort 0x06090031)".
  [[nodiscard]] const char* error() const noexcept { return error_.data(); }
  [[nodiscard]] std::uint32_t abort_code() const noexcept { return sdo_.abort_code(); }

 private:
  enum class Phase : std::uint8_t { bootup, device_type, writes, started };
  bool next_request(std::uint64_t now_us, can::CanFrame& out) noexcept;
  bool send_request(std::uint64_t now_us, can::CanFrame& out) noexcept;
  void fail_sdo(const char* doing) noexcept;

  NodeStartupConfig config_;
  SdoClient sdo_;
  Status status_ = Status::running;
  Phase phase_ = Phase::bootup;
  std::uint64_t attempt_started_us_ = 0;
  int attempts_ = 0;
  std::array<SdoWrite, 48> writes_{};
  std::size_t write_count_ = 0;
  std::size_t next_write_ = 0;
  int sdo_tries_ = 0;           // of the request under way
  bool retry_pending_ = false;  // the abort of a timed-out request went out; resend next
  std::array<char, 200> error_{};
  const char* refused_pdo_ = nullptr;  // the first PDO of the layout that cannot be mapped
  const char* refused_why_ = nullptr;
};

// The name of a communication or drive-profile object, for messages.
const char* object_name(std::uint16_t index) noexcept;

}  // namespace mcnc::canopen
