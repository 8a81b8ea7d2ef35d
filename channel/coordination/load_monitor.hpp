#pragma once
// G10 L14 P0/P1 (spec dafeng L4770-4849): the load of each axis watched against its reference,
// in percent of the motor's rated torque, as its drive reports it (0x6077). P0 watches every
// move of the axis, P1 its G01 moves only; the load above the reference for the filter time J
// (s; J0: at once) is the overload alarm, and the channel stops. A new P0/P1 replaces the set
// (L4860: "cancel Z, set X"); P0/P1 without axes cancels it (L4866). An axis whose drive does
// not report its load while it is watched is an alarm too: unwatched, it could overload
// unseen. Pure: one call per cycle; no allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::coordination {

inline constexpr int kAlarmOverload = 1280;  // G10 L14 P0/P1: an axis's load above its reference
// G10 L14 P7/P8: a drilling or tapping cycle's in-feed overloaded; the tool went back to R.
inline constexpr int kAlarmCycleOverload = 1282;

// Which moves P0/P1 watch: none, every move of the axis (P0), its G01 moves (P1).
enum class LoadWatch : std::uint8_t { off, every_move, feed_moves };

// What runs in a cycle, for each axis: whether a move of it is under way and whether that is a
// G01.
struct MoveUnderWay {
  std::uint32_t moves = 0;  // bit i: the block under way moves axis i
  bool feed = false;        // that block is a G01
};

class LoadMonitor {
 public:
  static constexpr std::size_t kMaxAxes = 32;
  using Percent = std::array<double, kMaxAxes>;

  // `slots` name the channel's axes in the alarms (by number where none is given).
  explicit LoadMonitor(std::span<const AxisSlot> slots) noexcept;

  // G10 L14 P0/P1 reached the front: the axes of `axes` (bit i) watched at `reference[i]` %,
  // for `filter_cycles` cycles in a row (at least 1); `axes` 0 cancels every check. `p` names
  // the G10 L14 P in the alarm (-1: P0 or P1, as `watch` says; P7/P8 watch a cycle's in-feed).
  void set(LoadWatch watch, std::uint32_t axes, const Percent& reference,
           std::uint64_t filter_cycles, int p = -1) noexcept;
  void cancel() noexcept { set(LoadWatch::off, 0, {}, 1); }
  // One cycle, with the feedback the channel holds: true when an axis overloaded now (alarm()).
  bool step(std::span<const AxisFeedbackView> feedback, const MoveUnderWay& move) noexcept;

  [[nodiscard]] LoadWatch watch() const noexcept { return watch_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  LoadWatch watch_ = LoadWatch::off;
  std::uint32_t axes_ = 0;
  Percent reference_{};
  std::uint64_t filter_cycles_ = 1;
  int p_ = -1;
  std::array<std::uint64_t, kMaxAxes> over_{};  // cycles in a row above the reference
  CoordinationAlarm alarm_{};
  std::array<char, kMaxAxes> names_{};  // 0: by number

  void raise(std::size_t axis, const char* why, double load) noexcept;
};

}  // namespace mcnc::coordination
