#include "channel/coordination/aux_handshake.hpp"

namespace mcnc::coordination {

void AuxHandshake::begin(AuxKind kind, int code, bool spindle_start) noexcept {
  active_ = true;
  request_ = AuxRequestOut{0, kind, code};
  spindle_ = spindle_start;
  sent_ = false;
  answered_ = false;
}

void AuxHandshake::abandon() noexcept {
  active_ = false;
  sent_ = false;
  answered_ = false;
}

void AuxHandshake::on_answer(const PlcAnswer& answer) noexcept {
  if (active_ && sent_ && request_.id == answer.id) {
    answer_ = answer;
    answered_ = true;
  }
}

AuxStep AuxHandshake::step(const AuxInputs& in) noexcept {
  if (spindle_ && !sent_ && in.spindle_follows) {
    alarm_.set(kAlarmSlaveSpindle,
               "the spindle follows another spindle (G114.1): its master's channel cancels that "
               "with G113 first");
    return AuxStep::alarm;
  }
  if (spindle_ && !in.plc) {
    active_ = false;  // no PLC to ask: it turns now
    return AuxStep::done;
  }
  if (!sent_) {
    request_.id = (std::uint64_t{channel_} << 40) | ++requests_;
    sent_ = true;
    return AuxStep::send;
  }
  if (!answered_ && plc_lost_) {
    answer_ = PlcAnswer{request_.id, AuxOutcome::refused, {}};
    std::snprintf(answer_.reason.data(), answer_.reason.size(), "the PLC node is gone");
    answered_ = true;
  }
  if (!answered_) {
    return AuxStep::waiting;  // FIN wait
  }
  answered_ = false;
  if (answer_.outcome != AuxOutcome::done) {
    const bool t = request_.kind == AuxKind::t_code;
    alarm_.set(answer_.outcome == AuxOutcome::refused ? kAlarmAuxRefused : kAlarmAuxTimeout,
               "%c%0*d %s by the PLC: %s", t ? 'T' : 'M', t ? 4 : 2, request_.code,
               answer_.outcome == AuxOutcome::refused ? "refused" : "not done",
               answer_.reason.data());
    return AuxStep::alarm;
  }
  active_ = false;
  return AuxStep::done;
}

}  // namespace mcnc::coordination
