#pragma once
// G10 L14 P2-P5 and P20-P51 (spec dafeng L4770-4849): the load timers 2-5 (diagnostics
// 0530-0533). P2-P5 start a timer from 0 over the axes named, each at its reference load (% of
// the motor's rated torque, as the drive reports it, 0x6077); it counts, per axis, the time the
// load stays above the reference while a move of the axis is under way: P2/P3 in G01 moves,
// P4/P5 in every move. A run above the reference counts once it lasted the filter time J (then
// in full). No alarm: format ② (P20-P51) compares the counted time with its own per axis, less
// (P20/P30/P40/P50) or more (P21/P31/P41/P51), and the axes that meet it go to the program.
// Pure: one call per cycle; no allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"
#include "channel/coordination/load_monitor.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::coordination {

// G10 L14 P20-P51 without R: an axis met the condition.
inline constexpr int kAlarmLoadTime = 1281;

class LoadTimers {
 public:
  static constexpr int kFirst = 2;  // P2 ... P5
  static constexpr int kLast = 5;
  static constexpr std::size_t kMaxAxes = LoadMonitor::kMaxAxes;
  using Values = LoadMonitor::Percent;

  // `slots` name the channel's axes in the alarms (by number where none is given).
  explicit LoadTimers(std::span<const AxisSlot> slots) noexcept;

  // G10 L14 P`timer` reached the front: the timer starts from 0 over the axes of `axes` (bit i)
  // at `reference[i]` %, a run above it counting once it lasted `filter_cycles` (at least 1);
  // `axes` 0 stops it. A timer outside 2-5 is ignored.
  void start(int timer, std::uint32_t axes, const Values& reference,
             std::uint64_t filter_cycles) noexcept;
  // Every timer stops and reads 0 (a new run, a reset).
  void clear() noexcept;
  // One cycle, with the feedback the channel holds. False when a timed axis under way does not
  // report its load (alarm()): its time would be wrong unseen.
  bool step(std::span<const AxisFeedbackView> feedback, const MoveUnderWay& move) noexcept;

  // The time timer `timer` counted for channel axis `axis`, in cycles.
  [[nodiscard]] std::uint64_t cycles(int timer, std::size_t axis) const noexcept;
  // Format ②: the axes of `axes` whose time (cycles of `cycle_s` seconds) is less than
  // `seconds[i]` (`longer` false) or more (`longer` true). Without `variable` (R) any axis
  // that meets it sets alarm() (kAlarmLoadTime) with the first.
  std::uint32_t check(int timer, bool longer, std::uint32_t axes, const Values& seconds,
                      double cycle_s, bool variable) noexcept;

  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  struct Timer {
    std::uint32_t axes = 0;
    Values reference{};
    std::uint64_t filter_cycles = 1;
    std::array<std::uint64_t, kMaxAxes> above{};    // cycles in a row above the reference
    std::array<std::uint64_t, kMaxAxes> counted{};  // the timer's value
  };
  std::array<Timer, kLast - kFirst + 1> timers_{};
  CoordinationAlarm alarm_{};
  std::array<char, kMaxAxes> names_{};  // 0: by number

  static bool valid(int timer) noexcept { return timer >= kFirst && timer <= kLast; }
  void axis_name(std::size_t axis, char (&name)[8]) const noexcept;
};

}  // namespace mcnc::coordination
