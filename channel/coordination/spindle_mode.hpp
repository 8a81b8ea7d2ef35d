#pragma once
// M18 / M17 (GSK M14 / M15): the channel's first spindle goes to position control (its C axis)
// or back to speed control. Position control takes the spindle over only at rest, since a
// spindle still coasting down from M05 would be stopped by the position loop at once: a few
// cycles in a row below C's in-position width, within a time limit. C starts within 0-360
// degrees: C = the spindle's position - c_base(), c_base() in whole turns. A spindle that follows
// another one (G114.1 slave) cannot be taken over. Pure: one step() per cycle with the spindle's
// feedback; no allocation, nothing throws.
#include "channel/coordination/coordination_alarm.hpp"

#include <cstdint>

namespace mcnc::coordination {

struct SpindleModeInputs {
  bool has_c_axis = false;  // the spindle has a C axis with feedback
  double act = 0.0;         // the spindle's actual position, degrees
  bool follows = false;     // it follows a master spindle (G114.1)
};

enum class SpindleModeStep : std::uint8_t {
  waiting,  // for the spindle to come to rest
  done,     // the block ends: position_control() says in which mode the spindle is now
  alarm,
};

class SpindleMode {
 public:
  // `rest_width`: C's in-position width, degrees per cycle.
  SpindleMode(double rest_width, double cycle_s) noexcept
      : rest_width_(rest_width), cycle_s_(cycle_s) {}

  // A block M18 (`position`) or M17 reached the front.
  void begin(bool position) noexcept;
  SpindleModeStep step(const SpindleModeInputs& in) noexcept;
  // Speed control, at once (no program runs, M17).
  void leave() noexcept { position_ = false; }

  [[nodiscard]] bool position_control() const noexcept { return position_; }
  // The spindle's position at C = 0 (whole turns) of the last position control (0: none yet).
  [[nodiscard]] double c_base() const noexcept { return c_base_; }
  // Where C stands when position control took the spindle over.
  [[nodiscard]] double c_start() const noexcept { return c_start_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

  static constexpr int kStillCycles = 5;        // in a row below the width: at rest
  static constexpr double kRestTimeout = 10.0;  // s: a spindle coasting down from any speed is in

 private:
  double rest_width_;
  double cycle_s_;
  bool position_ = false;
  double c_base_ = 0.0;
  double c_start_ = 0.0;
  // The block under way.
  bool to_position_ = false;
  int still_cycles_ = 0;
  std::uint64_t waited_ = 0;  // cycles M18 waited for the spindle to rest
  bool seen_ = false;
  double last_act_ = 0.0;
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
