#include "plcnode/logic/machine_plc.hpp"

#include "common/config/machine_config.hpp"
#include "common/cycle/decision_order.hpp"

#include <cstdio>

namespace mcnc::plc {

const char* to_string(AuxOutcome outcome) noexcept {
  switch (outcome) {
    case AuxOutcome::done:
      return "done";
    case AuxOutcome::refused:
      return "refused";
    case AuxOutcome::timed_out:
      return "timed_out";
  }
  return "done";
}

using config::cycles_of;

MachinePlc::MachinePlc(const config::PlcConfig& config, int cycle_us) noexcept
    : config_(config), cycle_us_(cycle_us) {
  for (const config::PlcSignal& s : config_.signals) {
    if (s.initial) {
      state_ |= std::uint64_t{1} << s.index;
    }
  }
  // A following input starts where its output puts it: the machine was switched on at rest.
  for (const config::PlcSignal& s : config_.signals) {
    if (s.follows_index >= 0) {
      const bool on = signal(s.follows_index) != s.invert;
      state_ =
          on ? state_ | (std::uint64_t{1} << s.index) : state_ & ~(std::uint64_t{1} << s.index);
    }
  }
}

void MachinePlc::request(const AuxRequest& request) noexcept {
  if (!cycle::insert_in_decision_order(queue_, queue_count_, request) &&
      overflow_count_ < overflow_.size()) {
    overflow_[overflow_count_++] = request;
  }
}

bool MachinePlc::synchronised(int spindle, std::span<const AxisView> spindles) noexcept {
  for (const AxisView& v : spindles) {
    if (v.locked && v.coupled_to != 0 && (v.axis == spindle || v.coupled_to == spindle)) {
      return true;
    }
  }
  return false;
}

bool MachinePlc::turning(int spindle, std::uint64_t cycle,
                         std::span<const AxisView> spindles) const noexcept {
  for (const Start& s : starts_) {
    if (s.spindle == spindle && cycle < s.cycle + kStartBridgeCycles) {
      return true;
    }
  }
  for (const AxisView& v : spindles) {
    if (v.axis == spindle) {
      return v.turning;
    }
  }
  return true;  // never heard of: not known to stand
}

bool MachinePlc::holds(std::span<const config::PlcCondition> conditions) const noexcept {
  for (const config::PlcCondition& c : conditions) {
    if (signal(c.signal) != c.on) {
      return false;
    }
  }
  return true;
}

const char* MachinePlc::unmet(std::span<const config::PlcCondition> conditions,
                              std::array<char, 64>& text) const noexcept {
  for (const config::PlcCondition& c : conditions) {
    if (signal(c.signal) != c.on) {
      std::snprintf(text.data(), text.size(), "%s=%d",
                    config_.signals[static_cast<std::size_t>(c.signal)].name.c_str(), c.on ? 1 : 0);
      return text.data();
    }
  }
  return nullptr;
}

void MachinePlc::answer(const AuxRequest& r, AuxOutcome outcome, const char* reason) noexcept {
  if (out_.answer_count == out_.answers.size()) {
    return;  // more than a cycle holds: cannot happen with one request per channel
  }
  AuxResult& a = out_.answers[out_.answer_count++];
  a.request = r;
  a.outcome = outcome;
  std::snprintf(a.reason.data(), a.reason.size(), "%s", reason != nullptr ? reason : "");
}

void MachinePlc::update_inputs(std::uint64_t cycle, std::span<const AxisView> axes) noexcept {
  const auto set = [&](int index, bool on) {
    state_ = on ? state_ | (std::uint64_t{1} << index) : state_ & ~(std::uint64_t{1} << index);
  };
  for (const config::PlcSignal& s : config_.signals) {
    if (s.output) {
      continue;
    }
    if (s.at_axis != 0) {
      // A sensor the axis reaches: on at or beyond `at`; an axis not heard of keeps it as it was.
      for (const AxisView& v : axes) {
        if (v.axis == s.at_axis && v.known) {
          const bool beyond = s.at_side > 0 ? v.position >= s.at : v.position <= s.at;
          set(s.index, beyond != s.invert);
        }
      }
      continue;
    }
    if (s.follows_index < 0) {
      continue;
    }
    const auto k = static_cast<std::size_t>(s.follows_index);
    if (cycle >= changed_at_[k] + cycles_of(s.delay_ms, cycle_us_)) {
      set(s.index, signal(s.follows_index) != s.invert);
    }
  }
}

void MachinePlc::start(const AuxRequest& r, std::uint64_t cycle,
                       std::span<const AxisView> spindles) noexcept {
  // A channel waits for one request at a time: one still running is one a reset abandoned.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < active_count_; ++i) {
    if (active_[i].request.channel != r.channel) {
      active_[kept++] = active_[i];
    }
  }
  active_count_ = kept;
  char reason[96];
  std::array<char, 64> cond{};
  if (r.kind == AuxKind::t_code) {
    if (active_count_ < active_.size()) {
      active_[active_count_++] = Active{r, nullptr, cycle};
    } else {
      answer(r, AuxOutcome::refused, "the PLC runs too many requests");
    }
    return;
  }
  if (r.code == 3 || r.code == 4) {
    // Spindle start (M03/M04): only the machine file's spindle start interlocks; the channel
    // turns the spindle itself once they hold.
    for (const config::PlcSpindleStart& s : config_.spindle_start) {
      if (const char* missing = s.spindle == r.spindle ? unmet(s.requires_, cond) : nullptr) {
        std::snprintf(reason, sizeof reason, "M%02d interlock: the spindle needs %s", r.code,
                      missing);
        answer(r, AuxOutcome::refused, reason);
        return;
      }
    }
    for (Start& s : starts_) {
      if (s.spindle == r.spindle || s.spindle == 0) {
        s = Start{r.spindle, cycle};
        break;
      }
    }
    answer(r, AuxOutcome::done, nullptr);
    return;
  }
  const config::PlcMCode* entry = config_.find_m_code(r.code, static_cast<int>(r.channel));
  if (entry == nullptr) {
    std::snprintf(reason, sizeof reason, "M%d is not in the PLC's M-code table for this channel",
                  r.code);
    answer(r, AuxOutcome::refused, reason);
    return;
  }
  if (const char* missing = unmet(entry->requires_, cond)) {
    std::snprintf(reason, sizeof reason, "M%d interlock: needs %s", r.code, missing);
    answer(r, AuxOutcome::refused, reason);
    return;
  }
  // No chuck open while its spindle turns, unless the spindles are synchronised for a
  // transfer (spec dafeng §3.7).
  if (entry->spindle_stopped != 0 && turning(entry->spindle_stopped, cycle, spindles) &&
      !synchronised(entry->spindle_stopped, spindles)) {
    std::snprintf(reason, sizeof reason, "M%d interlock: the spindle turns", r.code);
    answer(r, AuxOutcome::refused, reason);
    return;
  }
  for (const config::PlcCondition& c : entry->set) {
    const std::uint64_t bit = std::uint64_t{1} << c.signal;
    if (signal(c.signal) != c.on) {
      state_ = c.on ? state_ | bit : state_ & ~bit;
      changed_at_[static_cast<std::size_t>(c.signal)] = cycle;
    }
  }
  if (active_count_ < active_.size()) {
    active_[active_count_++] = Active{r, entry, cycle};
  } else {
    answer(r, AuxOutcome::refused, "the PLC runs too many requests");
  }
}

const PlcOutput& MachinePlc::cycle(std::uint64_t cycle, std::span<const AxisView> axes) noexcept {
  out_.started_count = 0;
  out_.answer_count = 0;
  for (std::size_t i = 0; i < overflow_count_; ++i) {
    answer(overflow_[i], AuxOutcome::refused, "the PLC's request queue is full");
  }
  overflow_count_ = 0;
  update_inputs(cycle, axes);
  // Requests sent before this cycle start now, in order.
  std::size_t taken = 0;
  while (taken < queue_count_ && queue_[taken].sent_cycle < cycle) {
    const AuxRequest& r = queue_[taken++];
    if (out_.started_count < out_.started.size()) {
      out_.started[out_.started_count++] = r;
    }
    start(r, cycle, axes);
  }
  for (std::size_t i = taken; i < queue_count_; ++i) {
    queue_[i - taken] = queue_[i];
  }
  queue_count_ -= taken;
  // Running requests end on FIN or time out.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < active_count_; ++i) {
    const Active& a = active_[i];
    bool ended = false;
    if (a.entry == nullptr) {
      ended = cycle >= a.started + cycles_of(config_.tool_change_ms, cycle_us_);
      if (ended) {
        answer(a.request, AuxOutcome::done, nullptr);
      }
    } else if (holds(a.entry->wait)) {
      answer(a.request, AuxOutcome::done, nullptr);
      ended = true;
    } else if (cycle >= a.started + cycles_of(a.entry->timeout_ms, cycle_us_)) {
      std::array<char, 64> cond{};
      char reason[96];
      std::snprintf(reason, sizeof reason, "M%d: no FIN within %d ms (waits for %s)",
                    a.request.code, a.entry->timeout_ms, unmet(a.entry->wait, cond));
      answer(a.request, AuxOutcome::timed_out, reason);
      ended = true;
    }
    if (!ended) {
      active_[kept++] = a;
    }
  }
  active_count_ = kept;
  out_.outputs = 0;
  out_.inputs = 0;
  for (const config::PlcSignal& s : config_.signals) {
    if (signal(s.index)) {
      (s.output ? out_.outputs : out_.inputs) |= std::uint64_t{1} << s.index;
    }
  }
  out_.busy = active_count_ + queue_count_;
  return out_;
}

}  // namespace mcnc::plc
