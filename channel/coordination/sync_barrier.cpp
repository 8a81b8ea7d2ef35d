#include "channel/coordination/sync_barrier.hpp"

namespace mcnc::coordination {

SyncArrival SyncBarrier::arrive(std::int32_t p, const ChannelSet& participants,
                                bool all_active) noexcept {
  Mark barrier;
  barrier.p = p;
  barrier.all_active = all_active;
  barrier.participants = all_active ? ChannelSet{} : participants;
  SyncArrival a;
  a.channel = self_;
  a.p = p;
  a.generation = round_at(self_, barrier) + 1;
  a.all_active = all_active;
  a.participants = barrier.participants;
  mine_ = a;
  barrier.generation = a.generation;
  own_ = barrier;
  waiting_ = true;
  conflict_ = 0;
  (void)on_arrival(a);
  return a;
}

bool SyncBarrier::on_arrival(const SyncArrival& a) noexcept {
  if (a.channel == 0 || a.channel > kMaxChannels) {
    return true;  // not a channel of this machine: nothing to wait for from it
  }
  Channel& c = channels_[a.channel];
  Mark barrier;
  barrier.p = a.p;
  barrier.all_active = a.all_active;
  barrier.participants = a.all_active ? ChannelSet{} : a.participants;
  Mark* mark = nullptr;
  for (std::size_t i = 0; i < c.count && mark == nullptr; ++i) {
    if (c.marks[i].same_barrier(barrier)) {
      mark = &c.marks[i];
    }
  }
  if (mark == nullptr) {
    if (c.count == c.marks.size()) {
      overflow_ = true;
      overflow_channel_ = a.channel;
      return false;
    }
    mark = &c.marks[c.count++];
    *mark = barrier;
  }
  if (a.generation < mark->generation) {
    return true;  // an old round, delivered late
  }
  mark->generation = a.generation;
  c.latest = *mark;
  c.arrived = true;
  return true;
}

const SyncBarrier::Mark* SyncBarrier::find(std::uint32_t channel,
                                           const Mark& barrier) const noexcept {
  const Channel& c = channels_[channel];
  for (std::size_t i = 0; i < c.count; ++i) {
    if (c.marks[i].same_barrier(barrier)) {
      return &c.marks[i];
    }
  }
  return nullptr;
}

std::uint64_t SyncBarrier::round_at(std::uint32_t channel, const Mark& barrier) const noexcept {
  const Mark* m = find(channel, barrier);
  return m == nullptr ? 0 : m->generation;
}

ChannelSet SyncBarrier::participants_of(const Mark& m, const ChannelSet& active,
                                        std::uint32_t owner) const noexcept {
  ChannelSet s = m.all_active ? active : m.participants;
  s.set(owner);
  s.reset(0);
  return s;
}

bool SyncBarrier::released(const Mark& m, std::uint32_t owner,
                           const ChannelSet& active) const noexcept {
  const ChannelSet s = participants_of(m, active, owner);
  for (std::uint32_t q = 1; q <= kMaxChannels; ++q) {
    if (s.test(q) && round_at(q, m) < m.generation) {
      return false;
    }
  }
  return true;
}

SyncState SyncBarrier::evaluate(const ChannelSet& others_active,
                                const ChannelSet& halted) noexcept {
  // This channel waits at a mark: it is in automatic operation itself, and so a participant
  // of every other channel's "all" mark.
  ChannelSet active = others_active;
  active.set(self_);
  if (overflow_) {
    conflict_ = overflow_channel_;
    return SyncState::full;
  }
  if (!waiting_) {
    return SyncState::none;
  }
  const ChannelSet mine = participants_of(own_, active, self_);
  missing_.reset();
  for (std::uint32_t q = 1; q <= kMaxChannels; ++q) {
    if (mine.test(q) && round_at(q, own_) < own_.generation) {
      missing_.set(q);
    }
  }
  if (missing_.none()) {
    waiting_ = false;
    return SyncState::released;
  }

  // Which channels wait at a barrier that is not released yet.
  ChannelSet stuck;
  for (std::uint32_t q = 1; q <= kMaxChannels; ++q) {
    const Channel& c = channels_[q];
    if (q != self_ && c.arrived && (active.test(q) || halted.test(q)) &&
        !released(c.latest, q, active)) {
      stuck.set(q);
    }
  }
  // Mismatch: a channel this one misses waits at the same P for this one, with other
  // participants.
  for (std::uint32_t q = 1; q <= kMaxChannels; ++q) {
    if (!missing_.test(q) || !stuck.test(q)) {
      continue;
    }
    const Mark& theirs = channels_[q].latest;
    if (theirs.p == own_.p && participants_of(theirs, active, q).test(self_)) {
      conflict_ = q;
      waiting_ = false;
      return SyncState::mismatch;
    }
  }
  // Deadlock: from every waiting channel keep those that cannot go on. A waiting channel can go
  // on once each channel it misses can still arrive: is not waiting, or waits at a barrier that
  // can itself go on.
  stuck.set(self_);
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t x = 1; x <= kMaxChannels; ++x) {
      if (!stuck.test(x)) {
        continue;
      }
      const Mark& m = x == self_ ? own_ : channels_[x].latest;
      const ChannelSet s = participants_of(m, active, x);
      bool can_go_on = true;
      for (std::uint32_t r = 1; r <= kMaxChannels && can_go_on; ++r) {
        if (r != x && s.test(r) && stuck.test(r) && round_at(r, m) < m.generation) {
          can_go_on = false;  // r waits elsewhere and cannot come
        }
      }
      if (can_go_on) {
        stuck.reset(x);
        changed = true;
      }
    }
  }
  if (stuck.test(self_)) {
    for (std::uint32_t q = 1; q <= kMaxChannels; ++q) {
      if (missing_.test(q) && stuck.test(q)) {
        conflict_ = q;
        break;
      }
    }
    waiting_ = false;
    return SyncState::deadlock;
  }
  return SyncState::waiting;
}

}  // namespace mcnc::coordination
