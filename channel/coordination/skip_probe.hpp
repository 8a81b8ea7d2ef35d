#pragma once
// G31 (skip) as the channel runs it with its drives' touch probes: the move waits until every
// probe on the block's skip input reports itself armed (an alarm if none is on that input, or
// one does not arm in time), then runs; the first probe that latches stops it, and the skip
// position is where that drive latched, the other axes where the same feedback shows them. A
// move that ends without the signal ends where it was programmed to.
// G31 P1-P8 skips on a PLC signal (G0014.0-7) instead: the move starts once the signal is seen
// off (a signal already on would skip where the move starts), and the skip position is where
// the axes' feedback stood in the cycle the signal is seen on, not a drive's latch (decision
// 360). G160 skips where its axis's node reports the torque at the limit and the following
// error beyond the deviation, a latch as a touch probe's, at the axis's actual position then
// (decision 100). G31 P98/P99 skip where an axis is held back at its load ratio the same way,
// P99 also on the touch probes of its input (decision 116). G31.8 arms its axis's probe to latch
// every edge; the move goes on past each, up to the most edges, and keeps each latched
// position, counted by the drive so that none is taken twice or missed unseen. Pure: one call per
// cycle with the feedback of that cycle; no allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::coordination {

inline constexpr int kAlarmProbeNotArmed = 1270;  // G31: a drive's touch probe did not arm
inline constexpr int kAlarmEdgesLost = 1273;      // G31.8: more edges in a cycle than reported
// G31.8 keeps at most this many positions (interp::kMaxMultiSkipSignals).
inline constexpr std::size_t kMaxLatches = 100;

enum class SkipPhase : std::uint8_t { arming, moving, stopping };
enum class SkipArming : std::uint8_t { waiting, armed, alarm };

class SkipProbe {
 public:
  static constexpr std::size_t kMaxAxes = 8;
  using Position = std::array<double, kMaxAxes>;

  SkipProbe(std::size_t axis_count, std::uint64_t arm_cycles) noexcept
      : axis_count_(axis_count), arm_cycles_(arm_cycles) {}

  // A G31 block on skip input `input` reached the front.
  void begin(int input) noexcept;
  // G160 of channel axis `axis` reached the front; arm() and watch() take the axis's bit.
  void begin_torque(std::size_t axis) noexcept;
  // G31 P98 (`or_input` false: the load alone) or P99 (its input or the load) reached the
  // front; arm() and watch() take the bits of the axes it limits besides the input's probes.
  void begin_load(int input, bool or_input) noexcept;
  // Arming, one cycle. `probes`: bit i, the touch probe of axis i is on the block's input.
  SkipArming arm(std::span<const AxisFeedbackView> feedback, std::uint32_t probes) noexcept;
  void start_moving() noexcept { phase_ = SkipPhase::moving; }
  // Moving, one cycle: true when a probe latched now (the move must stop at once).
  bool watch(std::span<const AxisFeedbackView> feedback, std::uint32_t probes) noexcept;

  // G31.8 on skip input `input` reached the front: the touch probe of channel axis `axis`
  // latches every edge, and the move stops at the `most`-th (1..kMaxLatches).
  void begin_multi(int input, std::size_t axis, int most) noexcept;
  // Moving a G31.8, one cycle: true when the move must stop at once (the most edges came, or
  // more edges came in one cycle than the drive holds positions of: the alarm, lost()).
  bool watch_multi(std::span<const AxisFeedbackView> feedback) noexcept;
  // G31.8: the positions latched, in order.
  [[nodiscard]] std::span<const double> latched() const noexcept {
    return {latched_.data(), latch_count_};
  }

  // G31 P `signal` (1-8) reached the front.
  void begin_signal(int signal) noexcept;
  // Arming on a PLC signal, one cycle: `on` the signal as the PLC's status shows it, `gone` the
  // PLC node is gone.
  SkipArming arm_signal(bool on, bool gone) noexcept;
  // Moving on a PLC signal, one cycle: true when the signal is on now (the move must stop at
  // once); `gone` stops it too, with the alarm.
  bool watch_signal(std::span<const AxisFeedbackView> feedback, bool on, bool gone) noexcept;

  [[nodiscard]] SkipPhase phase() const noexcept { return phase_; }
  [[nodiscard]] bool skipped() const noexcept { return skipped_; }
  // Where the skip happened, or `end` (where the move ended) without the signal.
  [[nodiscard]] Position where(const Position& end) const noexcept {
    return skipped_ ? skip_at_ : end;
  }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }
  // The PLC node went away during a G31 P move, or a G31.8's drive latched edges faster than it
  // reports them: the move stopped and this alarm is to raise.
  [[nodiscard]] bool lost() const noexcept { return lost_; }

 private:
  std::size_t axis_count_;
  std::uint64_t arm_cycles_;
  int input_ = 0;
  int signal_ = 0;       // G31 P: the PLC's skip signal (1-8); 0: touch probes
  bool torque_ = false;  // G160: the torque skip of axis torque_axis_
  int load_ = 0;         // G31 P98 / P99: the load skips of the axes with a load ratio
  std::size_t torque_axis_ = 0;
  bool multi_ = false;  // G31.8: every edge of torque_axis_'s probe, up to most_
  std::size_t most_ = 0;
  std::uint32_t seen_count_ = 0;  // the drive's edge count as last taken
  std::array<double, kMaxLatches> latched_{};
  std::size_t latch_count_ = 0;
  SkipPhase phase_ = SkipPhase::arming;
  std::uint64_t waited_ = 0;  // cycles arming
  bool skipped_ = false;
  bool lost_ = false;
  Position skip_at_{};
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
