#include "channel/coordination/sub_call.hpp"

#include <algorithm>

namespace mcnc::coordination {

const char* to_string(CallOutcome outcome) noexcept {
  switch (outcome) {
    case CallOutcome::released:
      return "released";
    case CallOutcome::refused:
      return "refused";
    case CallOutcome::failed:
      return "failed";
    case CallOutcome::aborted:
      return "aborted";
  }
  return "released";
}

void SubCall::set_partner(std::uint32_t channel, const PartnerStatus& status) noexcept {
  if (channel < 1 || channel > kMaxChannels) {
    return;
  }
  partners_[channel] = status;
  // A call of ours the target now runs: from here its status says whose call it runs.
  if (outstanding_[channel] != 0 && status.call_id == outstanding_[channel]) {
    outstanding_[channel] = 0;
  }
}

std::optional<CallRelease> SubCall::on_call(const CallRequest& call) noexcept {
  if (incoming_count_ < kMaxIncoming) {
    incoming_[incoming_count_++] = call;
    return std::nullopt;
  }
  return refusal(call);
}

void SubCall::on_release(const CallRelease& release) noexcept {
  for (std::uint64_t& o : outstanding_) {
    if (o == release.call_id) {
      o = 0;
    }
  }
  if (active_ && sent_ && call_.call_id == release.call_id) {
    ended_ = release;
  } else if (release.outcome == CallOutcome::refused) {
    refused_ = release;  // a call without wait: an alarm all the same
  }
}

void SubCall::begin(const CallRequest& call) noexcept {
  active_ = true;
  call_ = call;
  sent_ = false;
  waiting_for_target_ = false;
  waiting_since_ = 0;
}

void SubCall::abandon() noexcept {
  active_ = false;
  sent_ = false;
  ended_.reset();
}

std::uint32_t SubCall::waiting_for() const noexcept {
  return active_ && sent_ && call_.wait ? call_.target : 0;
}

const CoordinationAlarm* SubCall::take_refusal() noexcept {
  if (!refused_) {
    return nullptr;
  }
  refusal_.set(kAlarmCallRefused, "G144: channel %u refused the call (it was busy)",
               refused_->target);
  refused_.reset();
  return &refusal_;
}

void SubCall::serve(const CallRequest& call) noexcept {
  serving_ = ServedCall{call, std::max(call.repeat, 1) - 1, false};
}

std::optional<CallRelease> SubCall::release_caller(CallOutcome outcome) noexcept {
  if (!serving_ || serving_->released) {
    return std::nullopt;
  }
  serving_->released = true;
  return CallRelease{serving_->call.call_id, serving_->call.caller, self_, outcome};
}

bool SubCall::repeat_served() noexcept {
  if (serving_ && serving_->repeats_left > 0) {
    --serving_->repeats_left;
    return true;
  }
  serving_.reset();
  return false;
}

bool SubCall::calls_back(std::uint32_t target) const noexcept {
  // The chain of callers that wait for their call, from this channel's up: each partner's
  // status names its own caller, and a caller that waits is in state waiting. A caller that
  // did not wait (H0) or was released (G145) may be called: it is no circle.
  std::uint32_t caller =
      serving_ && serving_->call.wait && !serving_->released ? serving_->call.caller : 0;
  for (std::size_t step = 0; step < kMaxChannels && caller != 0; ++step) {
    if (caller == target) {
      return true;
    }
    const PartnerStatus& p = caller <= kMaxChannels ? partners_[caller] : partners_[0];
    const std::uint32_t next = p.known && p.call_id != 0 ? p.call_caller : 0;
    const bool next_waits = next != 0 && next <= kMaxChannels && partners_[next].known &&
                            partners_[next].state == ChannelState::waiting;
    caller = next_waits ? next : 0;
  }
  return false;
}

CallStep SubCall::step(std::uint64_t cycle, const ChannelSet& lost, bool writes_pending) noexcept {
  return sent_ ? step_sent(lost) : step_reached(cycle, lost, writes_pending);
}

CallStep SubCall::step_reached(std::uint64_t cycle, const ChannelSet& lost,
                               bool writes_pending) noexcept {
  const std::uint32_t target = call_.target;
  if (target == self_ || calls_back(target)) {
    alarm_.set(kAlarmCallCycle, "G144 N%u: channel %u %s: a call cycle", target, target,
               target == self_ ? "is this channel"
                               : "waits for the call this channel runs (directly or through "
                                 "others)");
    return CallStep::alarm;
  }
  const PartnerStatus none{};
  const PartnerStatus& t = target >= 1 && target <= kMaxChannels ? partners_[target] : none;
  const bool outstanding = target <= kMaxChannels && outstanding_[target] != 0;
  if (target <= kMaxChannels && lost.test(target)) {
    alarm_.set(kAlarmCallFailed, "G144 N%u: channel %u is gone", target, target);
    return CallStep::alarm;
  }
  const bool free = t.known && t.state == ChannelState::idle && t.call_id == 0 && !outstanding;
  if (!free) {
    // Still finishing a call of ours (after its G145, on the way to M99), or not up yet: wait
    // until it is idle (spec dafeng §3.4 decide 1). Anything else is busy.
    const bool finishing_ours =
        t.known && t.call_id != 0 && t.call_caller == self_ && t.state != ChannelState::alarm;
    if (outstanding || finishing_ours || !t.known || t.state == ChannelState::reset) {
      if (!waiting_for_target_) {
        waiting_for_target_ = true;
        waiting_since_ = cycle;
      }
      if (wait_cycles_ != 0 && cycle - waiting_since_ >= wait_cycles_) {
        alarm_.set(kAlarmCallTimeout, "G144 N%u: channel %u did not become free in time", target,
                   target);
        return CallStep::alarm;
      }
      return CallStep::waiting;
    }
    alarm_.set(kAlarmCallBusy, "G144 N%u: channel %u is busy (%s)", target, target,
               t.call_id != 0 ? "running a program another channel called" : to_string(t.state));
    return CallStep::alarm;
  }
  if (writes_pending) {
    return CallStep::pending;
  }
  call_.call_id = (std::uint64_t{self_} << 40) | ++calls_made_;
  outstanding_[target] = call_.call_id;
  sent_ = call_.wait;
  active_ = call_.wait;  // H0: the block ends with the call
  return CallStep::send;
}

CallStep SubCall::step_sent(const ChannelSet& lost) noexcept {
  if (!ended_ && call_.target <= kMaxChannels && lost.test(call_.target)) {
    alarm_.set(kAlarmCallFailed, "G144: channel %u is gone before it released this channel",
               call_.target);
    return CallStep::alarm;
  }
  if (!ended_) {
    return CallStep::pending;  // H1: until the called channel's G145 or end
  }
  const CallOutcome outcome = ended_->outcome;
  ended_.reset();
  if (outcome != CallOutcome::released) {
    alarm_.set(outcome == CallOutcome::refused ? kAlarmCallRefused : kAlarmCallFailed,
               outcome == CallOutcome::refused
                   ? "G144: channel %u refused the call (it was busy)"
                   : (outcome == CallOutcome::failed
                          ? "G144: the program called in channel %u stopped with an alarm"
                          : "G144: channel %u was reset before it released this channel"),
               call_.target);
    return CallStep::alarm;
  }
  active_ = false;
  sent_ = false;
  return CallStep::done;
}

}  // namespace mcnc::coordination
