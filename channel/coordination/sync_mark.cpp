#include "channel/coordination/sync_mark.hpp"

namespace mcnc::coordination {

void SyncMark::begin(bool has_p, std::int32_t p, const ChannelSet& participants,
                     bool all_channels) noexcept {
  has_p_ = has_p;
  p_ = p;
  participants_ = participants;
  all_channels_ = all_channels;
  arrived_ = false;
  arrived_now_ = false;
}

void SyncMark::abandon() noexcept {
  barrier_.cancel();
  arrived_ = false;
  arrived_now_ = false;
}

SyncMarkStep SyncMark::step(const SyncMarkInputs& in) noexcept {
  arrived_now_ = false;
  if (!has_p_) {
    return SyncMarkStep::done;
  }
  if (!arrived_) {
    if (in.writes_pending) {
      return SyncMarkStep::pending;  // the shared writes before the mark go out first
    }
    (void)barrier_.arrive(p_, participants_, all_channels_);
    arrived_ = true;
    arrived_now_ = true;
  }
  std::uint32_t other = 0;  // the channel the alarm names
  int number = 0;
  const char* what = nullptr;
  switch (barrier_.evaluate(in.active, in.halted)) {
    case SyncState::none:
    case SyncState::waiting: {
      const ChannelSet gone = barrier_.missing() & in.lost;
      if (gone.none()) {
        return SyncMarkStep::waiting;
      }
      other = 1;
      while (!gone.test(other)) {
        ++other;
      }
      number = kAlarmSyncPartnerLost;
      what = "is gone while this channel waits for it";
      break;
    }
    case SyncState::mismatch:
      other = barrier_.conflict_channel();
      number = kAlarmSyncMismatch;
      what = "waits at the same mark with other participants (sync mismatch)";
      break;
    case SyncState::deadlock:
      other = barrier_.conflict_channel();
      number = kAlarmSyncDeadlock;
      what = "waits at another mark that can never be released (sync deadlock)";
      break;
    case SyncState::full:
      other = barrier_.conflict_channel();
      number = kAlarmSyncTableFull;
      what = "has more different marks than the table holds (128)";
      break;
    case SyncState::released:
      arrived_ = false;
      return SyncMarkStep::released;
  }
  alarm_.set(number, "G04.1 P%d: channel %u %s", p_, other, what);
  return SyncMarkStep::alarm;
}

}  // namespace mcnc::coordination
