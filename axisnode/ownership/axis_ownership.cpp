#include "axisnode/ownership/axis_ownership.hpp"

#include "common/cycle/channel_bit.hpp"
#include "common/cycle/decision_order.hpp"

namespace mcnc::ownership {

using cycle::channel_bit;

bool AxisOwnership::request(const OwnershipRequest& request) noexcept {
  if (cycle::insert_in_decision_order(incoming_, incoming_count_, request)) {
    return true;
  }
  full_pending_ |= channel_bit(request.channel);  // answered with the cycle's decision
  return false;
}

bool AxisOwnership::waiting(std::uint32_t channel) const noexcept {
  for (std::size_t i = 0; i < waiting_count_; ++i) {
    if (waiting_[i].channel == channel) {
      return true;
    }
  }
  return false;
}

void AxisOwnership::answer(std::uint32_t channel, OwnershipRequestKind kind,
                           OwnershipAnswer a) noexcept {
  if (answer_count_ < answers_.size()) {
    answers_[answer_count_++] = Answer{channel, kind, a};
  }
  if (a == OwnershipAnswer::refused) {
    refused_ |= channel_bit(channel);
  } else if (a == OwnershipAnswer::full) {
    full_ |= channel_bit(channel);
  }
}

void AxisOwnership::wait(const OwnershipRequest& r) noexcept {
  for (std::size_t i = 0; i < waiting_count_; ++i) {
    if (waiting_[i].channel == r.channel && waiting_[i].kind == r.kind) {
      waiting_[i].force = waiting_[i].force || r.force;  // asked again: keeps its place
      return;
    }
  }
  if (waiting_count_ == waiting_.size()) {
    answer(r.channel, r.kind, OwnershipAnswer::full);
    return;
  }
  waiting_[waiting_count_++] = r;
}

void AxisOwnership::drop_waiting(std::uint32_t channel) noexcept {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < waiting_count_; ++i) {
    if (waiting_[i].channel != channel) {
      waiting_[kept++] = waiting_[i];
    }
  }
  waiting_count_ = kept;
}

void AxisOwnership::channel_gone(std::uint32_t channel) noexcept {
  drop_waiting(channel);
}

void AxisOwnership::set_owner(std::uint32_t owner, bool forced) noexcept {
  if (forced) {
    released_by_ = owner_;  // taken from it: it may restore the axis as if it had released it
    change_.forced = true;
  }
  if (owner == home_) {
    released_by_ = 0;  // back in the configured assignment
  }
  owner_ = owner;
  granted_now_ = true;
}

OwnershipChange AxisOwnership::decide(bool at_rest) noexcept {
  answer_count_ = 0;
  granted_now_ = false;
  change_ = OwnershipChange{};
  change_.previous = owner_;

  // One request, now: true when it is done (answered), false when it must wait.
  auto settle = [&](const OwnershipRequest& r) -> bool {
    switch (r.kind) {
      case OwnershipRequestKind::release:
        if (owner_ != r.channel) {
          answer(r.channel, r.kind, OwnershipAnswer::refused);
          return true;
        }
        owner_ = 0;
        released_by_ = r.channel;
        answer(r.channel, r.kind, OwnershipAnswer::released);
        return true;
      case OwnershipRequestKind::acquire:
        if (owner_ == r.channel) {
          answer(r.channel, r.kind, OwnershipAnswer::granted);
          return true;
        }
        // A forced take only from the owner the cycle started with: an axis granted in this
        // decision is not taken away before its new owner has heard of it.
        if (owner_ == 0 || (r.force && at_rest && !granted_now_)) {
          set_owner(r.channel, owner_ != 0);
          answer(r.channel, r.kind, OwnershipAnswer::granted);
          return true;
        }
        return false;
      case OwnershipRequestKind::restore:
        if (owner_ == home_) {
          answer(r.channel, r.kind, OwnershipAnswer::granted);
          return true;
        }
        // The home channel takes its axis back from anyone (the spec's "force restore");
        // another channel restores what it owns or released.
        if (r.channel != home_ && owner_ != r.channel && released_by_ != r.channel) {
          answer(r.channel, r.kind, OwnershipAnswer::refused);  // not this channel's to restore
          return true;
        }
        if (owner_ == 0 || (at_rest && !granted_now_)) {
          set_owner(home_, false);
          answer(r.channel, r.kind, OwnershipAnswer::granted);
          return true;
        }
        return false;
      case OwnershipRequestKind::withdraw:
        return true;  // its waiting requests went before it was settled
    }
    return true;
  };

  // A channel's new request ends what its earlier one came to.
  for (std::size_t i = 0; i < incoming_count_; ++i) {
    refused_ &= ~channel_bit(incoming_[i].channel);
    full_ &= ~channel_bit(incoming_[i].channel);
  }
  refused_ &= ~full_pending_;
  full_ |= full_pending_;
  full_pending_ = 0;
  // A withdraw (the channel was reset or stopped) goes before anything is granted: the waiting
  // line must not serve a channel that no longer waits.
  for (std::size_t i = 0; i < incoming_count_; ++i) {
    if (incoming_[i].kind == OwnershipRequestKind::withdraw) {
      drop_waiting(incoming_[i].channel);
    }
  }
  // The older requests first, then this cycle's, each in order; then the waiting ones again,
  // so that a release of this cycle goes to the first in line at once.
  auto settle_waiting = [&] {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < waiting_count_; ++i) {
      if (!settle(waiting_[i])) {
        waiting_[kept++] = waiting_[i];
      }
    }
    waiting_count_ = kept;
  };
  settle_waiting();
  for (std::size_t i = 0; i < incoming_count_; ++i) {
    const OwnershipRequest& r = incoming_[i];
    if (r.kind == OwnershipRequestKind::restore || r.kind == OwnershipRequestKind::withdraw) {
      drop_waiting(r.channel);  // G142 or a reset ends this channel's own waits for the axis
    }
    if (!settle(r)) {
      wait(r);
    }
    settle_waiting();  // a release goes to the first in line before any newer request
  }
  incoming_count_ = 0;
  settle_waiting();
  change_.owner = owner_;
  change_.changed = owner_ != change_.previous;
  return change_;
}

}  // namespace mcnc::ownership
