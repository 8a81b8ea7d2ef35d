#include "channel/coordination/axis_exchange.hpp"

#include "channel/interp/program_alarms.hpp"

#include <cmath>
#include <cstdio>

namespace mcnc::coordination {

const char* to_string(AxisRequestKind kind) noexcept {
  switch (kind) {
    case AxisRequestKind::release:
      return "release";
    case AxisRequestKind::acquire:
      return "acquire";
    case AxisRequestKind::restore:
      return "restore";
    case AxisRequestKind::withdraw:
      return "withdraw";
  }
  return "release";
}

AxisExchange::AxisExchange(ExchangeSetup setup) : setup_(std::move(setup)) {
  for (std::size_t i = 0; i < setup_.slots.size() && i < use_.size(); ++i) {
    const AxisSlot& slot = setup_.slots[i];
    use_[i] = slot.exchange_slot      ? SlotUse::virtual_axis
              : slot.follows_at_start ? SlotUse::follows
                                      : SlotUse::commanded;
  }
  if (setup_.spindle_c_slot && *setup_.spindle_c_slot < use_.size()) {
    use_[*setup_.spindle_c_slot] = SlotUse::speed_control;  // the spindle starts turnable
  }
}

void AxisExchange::push(AxisRequestKind kind, std::size_t slot, bool force) noexcept {
  if (request_count_ < requests_.size()) {
    requests_[request_count_++] = AxisRequestOut{kind, slot, force};
  }
}

std::optional<SlotLoss> AxisExchange::update(std::size_t s, const AxisFeedbackView& f) noexcept {
  if (!exchanges() || s >= setup_.axis_count || s >= kMaxSlots || s == setup_.spindle_c_slot) {
    return std::nullopt;  // the spindle is the channel's for good; SpindleMode decides
  }
  const std::uint32_t self = setup_.channel_id;
  // A borrowed axis granted after the channel stopped waiting for it (its withdraw crossed the
  // grant): given back at once, so that nobody waits for a channel that does not use it.
  const bool asked = active_ && sent_ && kind_ == AxisRequestKind::acquire && slot_ == s;
  if (f.present && setup_.slots[s].exchange_slot && use_[s] == SlotUse::virtual_axis &&
      f.owner == self && !asked && !unasked_released_[s]) {
    unasked_released_[s] = true;
    push(AxisRequestKind::release, s, false);
  }
  unasked_released_[s] = unasked_released_[s] && f.owner == self;
  SlotLoss loss;
  loss.slot = s;
  if (f.present && use_[s] == SlotUse::commanded && setup_.slots[s].may_follow &&
      f.coupled_to != 0) {
    // Its node follows a master (a G51.4 whose block a reset forgot): not the program's.
    use_[s] = SlotUse::follows;
    std::snprintf(loss.why.data(), loss.why.size(), "%s",
                  "follows another axis (G51.4): this program still moves it");
    return loss;
  }
  if (!f.present || use_[s] != SlotUse::commanded || f.owner == self) {
    return std::nullopt;
  }
  // Another channel has the axis now (G141 P1 takes it at rest): the channel stops commanding
  // it, and a block still queued that moves it cannot run.
  use_[s] = SlotUse::away;
  std::snprintf(loss.why.data(), loss.why.size(),
                "was taken by channel %u: this program still moves it", f.owner);
  return loss;
}

void AxisExchange::settle(std::span<const AxisFeedbackView> feedback,
                          std::span<double> commanded) noexcept {
  if (!exchanges()) {
    return;
  }
  for (std::size_t s = 0; s < setup_.axis_count && s < feedback.size() && s < kMaxSlots; ++s) {
    if (s == setup_.spindle_c_slot) {
      continue;  // commanded only between M18 and M17 (SpindleMode)
    }
    const AxisFeedbackView& f = feedback[s];
    if (f.present && f.owner == setup_.channel_id) {
      if ((setup_.slots[s].may_follow || setup_.slots[s].polygon) && f.coupled_to != 0) {
        // G51.4 outlives a reset and a restart of the channel; a polygon axis that a reset let
        // go is the channel's once it stands.
        use_[s] = SlotUse::follows;
      } else if (use_[s] != SlotUse::commanded) {
        commanded[s] = f.channel_cmd();  // the machine position travels with the axis
        use_[s] = SlotUse::commanded;
      }
    } else {
      use_[s] = setup_.slots[s].exchange_slot ? SlotUse::virtual_axis : SlotUse::away;
    }
  }
}

std::optional<std::size_t> AxisExchange::foreign_slot(std::span<const double> from,
                                                      std::span<const double> to) const noexcept {
  if (!exchanges()) {
    return std::nullopt;
  }
  for (std::size_t s = 0; s < setup_.axis_count && s < from.size() && s < to.size(); ++s) {
    if ((use_[s] == SlotUse::away || use_[s] == SlotUse::follows ||
         use_[s] == SlotUse::speed_control) &&
        std::fabs(to[s] - from[s]) > 1e-9) {
      return s;
    }
  }
  return std::nullopt;
}

CoordinationAlarm AxisExchange::foreign_move_alarm(
    std::size_t slot, std::span<const AxisFeedbackView> feedback) const noexcept {
  CoordinationAlarm alarm;
  const char address = setup_.slots[slot].address;
  const AxisFeedbackView none{};
  const AxisFeedbackView& f = slot < feedback.size() ? feedback[slot] : none;
  if (use_[slot] == SlotUse::speed_control) {
    alarm.set(interp::alarm::kSpindleControl,
              "%c is the spindle under speed control: position control first", address);
  } else if (use_[slot] == SlotUse::follows && setup_.slots[slot].polygon) {
    alarm.set(kAlarmAxisFollows,
              "%c is the polygon axis, turning with its master spindle (G51.2): G50.2 before the "
              "program moves it",
              address);
  } else if (use_[slot] == SlotUse::follows) {
    alarm.set(kAlarmAxisFollows,
              "%c follows axis %u (G51.4): G50.4 Q%u before the program moves it", address,
              f.coupled_to, setup_.slots[slot].id);
  } else if (f.owner == setup_.channel_id) {
    alarm.set(kAlarmAxisAway,
              "%c came back to this channel during the program: G141 or G142 takes it over "
              "before it moves",
              address);
  } else {
    alarm.set(kAlarmAxisAway, "%c is %s%.0u: acquire it (G141) or restore (G142) before moving it",
              address, f.owner == 0 ? "released and no channel has it" : "with channel ", f.owner);
  }
  return alarm;
}

void AxisExchange::begin(AxisRequestKind kind, std::size_t slot, bool force) noexcept {
  active_ = true;
  kind_ = kind;
  slot_ = slot;
  force_ = force;
  sent_ = false;
  took_over_ = false;
}

int AxisExchange::waiting_g() const noexcept {
  if (!active_ || !sent_) {
    return 0;
  }
  return kind_ == AxisRequestKind::release ? 140 : kind_ == AxisRequestKind::acquire ? 141 : 142;
}

void AxisExchange::withdraw() noexcept {
  if (!active_ || !sent_ || kind_ == AxisRequestKind::release) {
    return;
  }
  sent_ = false;
  push(AxisRequestKind::withdraw,
       kind_ == AxisRequestKind::acquire ? slot_ : AxisRequestOut::kAllSlots, false);
}

bool AxisExchange::away_on_own_account(std::size_t s, const AxisFeedbackView& f) const noexcept {
  const std::uint32_t self = setup_.channel_id;
  const std::uint32_t home = setup_.slots[s].home;
  return home == self ? f.owner != self
                      : f.owner == self || (f.released_by == self && f.owner != home);
}

bool AxisExchange::refused(std::span<const AxisFeedbackView> feedback) noexcept {
  const int g = waiting_g();
  for (std::size_t s = 0; s < setup_.axis_count && s < feedback.size(); ++s) {
    const AxisFeedbackView& f = feedback[s];
    if (kind_ != AxisRequestKind::restore && s != slot_) {
      continue;
    }
    // G142 goes to every exchangeable axis: a node where the channel has no say refuses it, and
    // only one whose axis is away on this channel's account matters.
    const bool no =
        f.request_refused && (kind_ != AxisRequestKind::restore || away_on_own_account(s, f));
    if (!f.request_full && !no) {
      continue;
    }
    alarm_.set(kAlarmRequestRefused,
               f.request_full
                   ? "G%d %c: the axis node could not keep the request (more channels wait for "
                     "the axis than it holds)"
                   : "G%d %c: the axis node refused the request (the axis is not this "
                     "channel's to release or restore; channel %u has it)",
               g, setup_.slots[s].address, f.owner);
    alarm_.axis = static_cast<int>(s + 1);
    return true;
  }
  return false;
}

ExchangeStep AxisExchange::step(std::uint64_t cycle, std::span<const AxisFeedbackView> feedback,
                                std::span<double> commanded) noexcept {
  const std::uint32_t self = setup_.channel_id;
  const bool one_slot = kind_ != AxisRequestKind::restore;
  const AxisFeedbackView none{};
  const AxisFeedbackView& f = one_slot && slot_ < feedback.size() ? feedback[slot_] : none;
  if (!sent_) {
    bool done = !exchanges();  // no exchange in this channel: G142 has nothing to restore
    if (kind_ == AxisRequestKind::release && !done &&
        (use_[slot_] != SlotUse::commanded || f.owner != self)) {
      alarm_.set(kAlarmNotOwner, "G140 %c: the axis is not this channel's (%s%.0u has it)",
                 setup_.slots[slot_].address, f.owner == 0 ? "nobody" : "channel ", f.owner);
      alarm_.axis = static_cast<int>(slot_ + 1);
      return ExchangeStep::alarm;
    }
    if (kind_ == AxisRequestKind::acquire && use_[slot_] == SlotUse::commanded && f.owner == self) {
      done = true;  // already this channel's
    }
    if (done) {
      active_ = false;
      return ExchangeStep::done;
    }
    push(kind_, one_slot ? slot_ : AxisRequestOut::kAllSlots, force_);
    sent_ = true;
    sent_cycle_ = cycle;
    return ExchangeStep::sent;
  }
  if (!answer_visible(sent_cycle_, cycle)) {
    return ExchangeStep::waiting;
  }
  if (refused(feedback)) {
    return ExchangeStep::alarm;
  }
  switch (kind_) {
    case AxisRequestKind::release:
      if (f.owner == self) {
        return ExchangeStep::waiting;
      }
      use_[slot_] = setup_.slots[slot_].exchange_slot ? SlotUse::virtual_axis : SlotUse::away;
      break;
    case AxisRequestKind::acquire:
      if (f.owner != self) {
        return ExchangeStep::waiting;  // until the owner releases (or, P1, the axis is at rest)
      }
      settle(feedback, commanded);
      took_over_ = true;
      break;
    default:
      // G142 ends once no axis is away on this channel's account (spec dafeng §3.3 decide 1):
      // its own axes are back, none borrowed is still its, none it released is elsewhere.
      for (std::size_t s = 0; s < setup_.axis_count && s < feedback.size(); ++s) {
        if (away_on_own_account(s, feedback[s])) {
          return ExchangeStep::waiting;
        }
      }
      settle(feedback, commanded);
      took_over_ = true;
      break;
  }
  active_ = false;
  return ExchangeStep::done;
}

}  // namespace mcnc::coordination
