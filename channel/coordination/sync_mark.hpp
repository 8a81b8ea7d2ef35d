#pragma once
// A G04.1 block as one channel runs it (ARCHITECTURE.md §5): once every block before it ended
// and the channel's shared writes before it are out, the channel arrives at the mark (the arrival
// to publish), then waits until its SyncBarrier releases it. A mismatch, a deadlock, a full mark
// table or a participant whose process is gone while the channel waits for it is an alarm. G04.1
// without P only stops read-ahead. Pure: one step() per cycle; no allocation, nothing throws.
#include "channel/coordination/coordination_alarm.hpp"
#include "channel/coordination/sync_barrier.hpp"

#include <cstdint>

namespace mcnc::coordination {

inline constexpr int kAlarmSyncMismatch = 1210;     // G04.1: partners name other participants
inline constexpr int kAlarmSyncDeadlock = 1211;     // G04.1: waits in a circle
inline constexpr int kAlarmSyncTableFull = 1212;    // G04.1: more marks than the table holds
inline constexpr int kAlarmSyncPartnerLost = 1213;  // G04.1: a partner's process is gone

struct SyncMarkInputs {
  ChannelSet active;            // channels in automatic operation (their status stamped N-1)
  ChannelSet halted;            // channels an alarm stopped
  ChannelSet lost;              // channels whose process is gone
  bool writes_pending = false;  // shared writes before the mark not out yet
};

enum class SyncMarkStep : std::uint8_t {
  pending,   // the writes before the mark go out first
  waiting,   // arrived (arrived_now(): in this cycle), participants missing
  released,  // every participant arrived: the block ends
  done,      // G04.1 without P: the block ends
  alarm,
};

class SyncMark {
 public:
  explicit SyncMark(std::uint32_t self) noexcept : barrier_(self) {}

  // A block G04.1 [P with its participants] reached the front.
  void begin(bool has_p, std::int32_t p, const ChannelSet& participants,
             bool all_channels) noexcept;
  SyncMarkStep step(const SyncMarkInputs& in) noexcept;
  // The wait ends without release (reset, new run).
  void abandon() noexcept;
  // Another channel's arrival (or this channel's own, harmlessly).
  void on_arrival(const SyncArrival& arrival) noexcept { (void)barrier_.on_arrival(arrival); }

  // The channel arrived in the last step(): barrier().current() is the arrival to publish.
  [[nodiscard]] bool arrived_now() const noexcept { return arrived_now_; }
  [[nodiscard]] const SyncBarrier& barrier() const noexcept { return barrier_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  SyncBarrier barrier_;
  bool has_p_ = false;
  std::int32_t p_ = 0;
  ChannelSet participants_;
  bool all_channels_ = false;
  bool arrived_ = false;
  bool arrived_now_ = false;
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
