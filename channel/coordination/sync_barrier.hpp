#pragma once
// G04.1 wait marks as one channel sees them (ARCHITECTURE.md §5): a decentralised barrier.
// Every channel publishes its arrivals {channel, P, participants, generation}; a channel that
// arrived waits until every participant has arrived at the same barrier in the same round. A
// barrier is a P with its participants (ARCHITECTURE.md §5): the same P may serve different
// groups of channels. The round (generation) counts a channel's arrivals at each barrier, so a
// fast channel that comes back to it does not pass a barrier meant for the previous round. From
// the same arrivals every channel can tell two conditions that would otherwise hang for ever, and
// raises them as alarms:
//  - mismatch: a channel this one waits for waits at the same P for this one, but names other
//    participants;
//  - deadlock: the channels this one waits for are themselves waiting at other marks that can
//    never be released (e.g. CH1 at P1 Q12 while CH2 waits at P2 Q12).
// Pure and fixed-size: arrivals in, a state out; no allocation, no exceptions.
#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>

namespace mcnc::coordination {

inline constexpr std::size_t kMaxChannels = 64;
using ChannelSet = std::bitset<kMaxChannels + 1>;  // bit c: channel c (1-based); bit 0 unused

struct SyncArrival {
  std::uint32_t channel = 0;
  std::int32_t p = 0;
  std::uint64_t generation = 0;  // the channel's n-th arrival at this P, from 1
  // P without Q, or Q-1: every channel in automatic operation takes part (the set is then
  // what is running when the barrier is evaluated); else `participants`.
  bool all_active = false;
  ChannelSet participants;
};

enum class SyncState : std::uint8_t {
  none,      // not at a wait mark
  waiting,   // arrived, participants missing
  released,  // every participant arrived: go on
  mismatch,  // another channel at this P and round names other participants
  deadlock,  // waiting for channels that wait at marks that can never be released
  full,      // more distinct P values than the table holds (an alarm)
};

class SyncBarrier {
 public:
  // Distinct marks (P with its participants) remembered per channel over a run of the process.
  static constexpr std::size_t kMarksPerChannel = 128;

  explicit SyncBarrier(std::uint32_t self) noexcept : self_(self) {}

  // This channel reached G04.1 P with its participants: the arrival to publish. Its wait
  // starts; evaluate() says when it ends.
  SyncArrival arrive(std::int32_t p, const ChannelSet& participants, bool all_active) noexcept;
  // An arrival of any channel (this channel's own coming back is harmless). False when the
  // sender's table is full (alarm).
  bool on_arrival(const SyncArrival& arrival) noexcept;
  // This channel's wait, given the channels in automatic operation now (running a program,
  // waiting at a mark or for a sub-call) and the channels an alarm stopped (they stand where
  // they are: at an unreleased mark they still take part in a mismatch or a deadlock, so each
  // channel involved gets the alarm, not only the first to see it). Released and alarm states
  // end the wait.
  SyncState evaluate(const ChannelSet& active, const ChannelSet& halted = {}) noexcept;
  // The wait ends without release (reset).
  void cancel() noexcept { waiting_ = false; }

  [[nodiscard]] bool waiting() const noexcept { return waiting_; }
  [[nodiscard]] const SyncArrival& current() const noexcept { return mine_; }
  // The participants this channel still waits for (valid while waiting).
  [[nodiscard]] const ChannelSet& missing() const noexcept { return missing_; }
  // The channel of the conflict (mismatch, deadlock), 0 when none.
  [[nodiscard]] std::uint32_t conflict_channel() const noexcept { return conflict_; }

 private:
  // One barrier a channel arrived at: P with its participants (or "all").
  struct Mark {
    std::int32_t p = 0;
    bool all_active = false;
    ChannelSet participants;
    std::uint64_t generation = 0;  // highest round seen (0: never)
    [[nodiscard]] bool same_barrier(const Mark& o) const noexcept {
      return p == o.p && all_active == o.all_active &&
             (all_active || participants == o.participants);
    }
  };
  struct Channel {
    std::array<Mark, kMarksPerChannel> marks{};
    std::size_t count = 0;
    Mark latest{};  // the channel's last arrival
    bool arrived = false;
  };

  [[nodiscard]] const Mark* find(std::uint32_t channel, const Mark& barrier) const noexcept;
  [[nodiscard]] std::uint64_t round_at(std::uint32_t channel, const Mark& barrier) const noexcept;
  [[nodiscard]] ChannelSet participants_of(const Mark& m, const ChannelSet& active,
                                           std::uint32_t owner) const noexcept;
  [[nodiscard]] bool released(const Mark& m, std::uint32_t owner,
                              const ChannelSet& active) const noexcept;

  std::uint32_t self_;
  std::array<Channel, kMaxChannels + 1> channels_{};
  SyncArrival mine_{};
  Mark own_{};
  bool waiting_ = false;
  bool overflow_ = false;
  std::uint32_t overflow_channel_ = 0;  // whose marks did not fit
  ChannelSet missing_;
  std::uint32_t conflict_ = 0;
};

}  // namespace mcnc::coordination
