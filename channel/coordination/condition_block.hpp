#pragma once
// A G04 I or G04 PS block (spec dafeng L1220-1254): what it waits for, read from the machine's
// state each cycle (a PLC input in a state, or a spindle's actual speed within the arrival
// width of param 1057), over a ConditionWait. An input port the PLC lacks, the PLC gone, or a
// spindle without feedback is an alarm; a condition that never comes times out as an alarm,
// unless the block has a dwell time, which then ends it (decision 68). Pure: one step() per
// cycle; no allocation, nothing throws.
#include "channel/coordination/condition_wait.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <cstdint>

namespace mcnc::coordination {

inline constexpr int kAlarmInputTimeout = 1271;  // G04 I: the input did not come within J
inline constexpr int kAlarmSpeedTimeout = 1272;  // G04 PS: the speed not reached (param 1059)

struct ConditionSpec {
  bool input = true;  // G04 I; false: G04 PS
  int port = 0;       // G04 I: the input port, wanted on (or off)
  bool on = true;
  double timeout_s = -1.0;  // G04 I J (< 0: none)
  double width_s = -1.0;    // G04 I K (< 0: one cycle)
  int spindle = 1;          // G04 PS: the spindle and its speed
  double rpm = 0.0;
  double dwell_s = -1.0;  // P/X/U ORed with the condition (< 0: none)
};

struct ConditionSetup {
  double speed_arrival_rpm = 10.0;        // param 1057
  double speed_arrival_timeout_s = 10.0;  // param 1059
  double cycle_s = 0.001;
};

struct ConditionInputs {
  int input_bit = -1;  // the bit of the PLC's inputs the port reads (-1: none)
  std::uint64_t plc_inputs = 0;
  bool plc_gone = false;
  bool spindle_present = false;  // feedback of the spindle arrives
  double spindle_vel = 0.0;      // its actual velocity, degrees/s
};

enum class ConditionStep : std::uint8_t { waiting, done, alarm };

class ConditionBlock {
 public:
  ConditionBlock(const ConditionSpec& spec, const ConditionSetup& setup) noexcept;
  ConditionStep step(const ConditionInputs& in) noexcept;
  [[nodiscard]] const ConditionSpec& spec() const noexcept { return spec_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  ConditionSpec spec_;
  ConditionSetup setup_;
  ConditionWait wait_;
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
