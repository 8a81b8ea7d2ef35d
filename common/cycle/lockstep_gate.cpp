#include "common/cycle/lockstep_gate.hpp"

namespace mcnc::cycle {

LockstepGate::LockstepGate(std::size_t inputs) : inputs_(inputs) {}

void LockstepGate::on_sample(std::size_t input, std::uint64_t cycle,
                             std::uint64_t announced_event_seq) noexcept {
  if (input < inputs_.size()) {
    inputs_[input].announced.put(cycle, announced_event_seq);
  }
}

void LockstepGate::on_event(std::size_t input, std::uint64_t seq) noexcept {
  if (input >= inputs_.size()) {
    return;
  }
  Input& in = inputs_[input];
  if (seq <= in.events_contiguous) {
    return;  // duplicate
  }
  if (seq == in.events_contiguous + 1) {
    in.events_contiguous = seq;
    // Absorb the events that had arrived ahead of this one.
    while ((in.events_ahead & 1U) != 0U) {
      in.events_ahead >>= 1U;
      ++in.events_contiguous;
    }
    in.events_ahead >>= 1U;
    return;
  }
  const std::uint64_t distance = seq - in.events_contiguous - 2;  // bit index
  if (distance < 64) {
    in.events_ahead |= std::uint64_t{1} << distance;
  }
}

void LockstepGate::set_expected(std::size_t input, bool expected) noexcept {
  if (input < inputs_.size()) {
    inputs_[input].expected = expected;
  }
}

bool LockstepGate::input_ready(std::size_t input, std::uint64_t cycle) const noexcept {
  const Input& in = inputs_[input];
  if (!in.expected || cycle == 0) {
    return true;
  }
  const std::uint64_t* announced = in.announced.at(cycle - 1);
  return announced != nullptr && in.events_contiguous >= *announced;
}

bool LockstepGate::may_run(std::uint64_t cycle) const noexcept {
  return !first_missing(cycle).has_value();
}

std::optional<std::size_t> LockstepGate::first_missing(std::uint64_t cycle) const noexcept {
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    if (!input_ready(i, cycle)) {
      return i;
    }
  }
  return std::nullopt;
}

std::optional<LockstepGate::Wait> LockstepGate::wait(std::uint64_t cycle) const noexcept {
  const std::optional<std::size_t> input = first_missing(cycle);
  if (!input) {
    return std::nullopt;
  }
  const Input& in = inputs_[*input];
  Wait w;
  w.input = *input;
  const std::uint64_t* announced = in.announced.at(cycle - 1);
  w.sample_missing = announced == nullptr;
  w.any_sample = !in.announced.empty();
  w.latest_cycle = in.announced.latest_cycle();
  w.events_announced = announced != nullptr ? *announced : 0;
  w.events_received = in.events_contiguous;
  return w;
}

std::uint64_t LockstepGate::events_received(std::size_t input) const noexcept {
  return input < inputs_.size() ? inputs_[input].events_contiguous : 0;
}

}  // namespace mcnc::cycle
