#pragma once
// M, S and T codes the PLC handles (ARCHITECTURE.md §5): one request at a time, the block ends
// with the PLC's answer (FIN). A spindle start (M03/M04) is asked too, so that the PLC may
// refuse it, and a spindle that follows another one (G114.1 slave) is not started at all. Pure
// and deterministic: a block begins, step() runs once per cycle, answers come in between; no
// allocation, nothing throws.
#include "channel/coordination/coordination_alarm.hpp"

#include <array>
#include <cstdint>

namespace mcnc::coordination {

// M and T codes for the PLC node (and M03/M04, which it must allow).
enum class AuxKind : std::uint8_t { m_code, t_code };
struct AuxRequestOut {
  std::uint64_t id = 0;  // channel << 40 | the channel's count of requests
  AuxKind kind = AuxKind::m_code;
  int code = 0;
};
enum class AuxOutcome : std::uint8_t { done, refused, timed_out };
struct PlcAnswer {
  std::uint64_t id = 0;
  AuxOutcome outcome = AuxOutcome::done;
  std::array<char, 96> reason{};
};

struct AuxInputs {
  bool plc = false;              // a PLC node runs aux codes at all
  bool spindle_follows = false;  // the channel's first spindle follows a master (G114.1)
};

enum class AuxStep : std::uint8_t {
  waiting,  // for the answer (FIN)
  send,     // request() goes out this cycle
  done,     // answered (a spindle start: it may turn now)
  alarm,    // alarm() says why; the block does not end
};

class AuxHandshake {
 public:
  explicit AuxHandshake(std::uint32_t channel) noexcept : channel_(channel) {}

  // A block with an aux code reached the front (the blocks before it ended).
  void begin(AuxKind kind, int code, bool spindle_start) noexcept;
  // One cycle of the block under way.
  AuxStep step(const AuxInputs& in) noexcept;
  // The PLC's answer; one to another request (abandoned by a reset) is ignored.
  void on_answer(const PlcAnswer& answer) noexcept;
  // The PLC node is gone: the request waiting for it, and every later one, is refused.
  void plc_lost() noexcept { plc_lost_ = true; }
  // No block under way any more (reset, new run): a late answer is ignored.
  void abandon() noexcept;

  [[nodiscard]] const AuxRequestOut& request() const noexcept { return request_; }
  // The request is out and its answer not yet taken (the FIN wait).
  [[nodiscard]] bool sent() const noexcept { return active_ && sent_; }
  [[nodiscard]] bool spindle_start() const noexcept { return spindle_; }
  [[nodiscard]] bool plc_gone() const noexcept { return plc_lost_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  std::uint32_t channel_;
  std::uint64_t requests_ = 0;  // requests made over the process's life: their ids
  bool plc_lost_ = false;
  bool active_ = false;
  AuxRequestOut request_{};
  bool spindle_ = false;
  bool sent_ = false;
  bool answered_ = false;
  PlcAnswer answer_{};
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
