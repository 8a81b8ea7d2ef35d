#include "channel/coordination/condition_wait.hpp"

namespace mcnc::coordination {

bool ConditionWait::reached(std::uint64_t cycles, double seconds) const noexcept {
  return static_cast<double>(cycles) * cycle_s_ >= seconds - cycle_s_ * 1e-6;
}

WaitOutcome ConditionWait::step(bool holds) noexcept {
  if (outcome_ != WaitOutcome::waiting) {
    return outcome_;
  }
  ++cycles_;
  held_cycles_ = holds ? held_cycles_ + 1 : 0;
  // The condition first: met in the cycle the time runs out, it is met (the block's purpose).
  if (held_cycles_ > 0 && (limits_.width_s <= 0.0 || reached(held_cycles_, limits_.width_s))) {
    outcome_ = WaitOutcome::met;
  } else if (limits_.dwell_s >= 0.0 && reached(cycles_, limits_.dwell_s)) {
    outcome_ = WaitOutcome::dwell_over;
  } else if (limits_.timeout_s >= 0.0 && reached(cycles_, limits_.timeout_s)) {
    outcome_ = WaitOutcome::timed_out;
  }
  return outcome_;
}

}  // namespace mcnc::coordination
