#pragma once
// A block that waits for a condition of the machine (G04 I: a PLC input in a state; G04 PS: a
// spindle's actual speed), cycle by cycle: the condition must hold for its width (G04 I K), a
// dwell time given with it ends the wait too (spec dafeng L1220-1254: the two are ORed), and a
// timeout ends it as timed out. Pure and deterministic: one call per cycle with the condition as
// the feedback of that cycle shows it; no allocation, nothing throws.
#include <cstdint>

namespace mcnc::coordination {

struct ConditionWaitLimits {
  double width_s = -1.0;    // the condition must hold this long (< 0: one cycle is enough)
  double dwell_s = -1.0;    // the block ends after this long anyway (< 0: no dwell)
  double timeout_s = -1.0;  // the wait times out after this long (< 0: waits for ever)
};

enum class WaitOutcome : std::uint8_t { waiting, met, dwell_over, timed_out };

class ConditionWait {
 public:
  ConditionWait(ConditionWaitLimits limits, double cycle_s) noexcept
      : limits_(limits), cycle_s_(cycle_s > 0.0 ? cycle_s : 0.001) {}

  // One cycle with the condition as it is now. Once the outcome is not `waiting`, it stays.
  WaitOutcome step(bool holds) noexcept;
  [[nodiscard]] WaitOutcome outcome() const noexcept { return outcome_; }
  [[nodiscard]] double waited_s() const noexcept { return cycle_s_ * static_cast<double>(cycles_); }

 private:
  // Whole cycles that reach `seconds` (a time within a millionth of a cycle counts as reached).
  [[nodiscard]] bool reached(std::uint64_t cycles, double seconds) const noexcept;

  ConditionWaitLimits limits_;
  double cycle_s_;
  std::uint64_t cycles_ = 0;       // cycles waited
  std::uint64_t held_cycles_ = 0;  // cycles in a row the condition held
  WaitOutcome outcome_ = WaitOutcome::waiting;
};

}  // namespace mcnc::coordination
