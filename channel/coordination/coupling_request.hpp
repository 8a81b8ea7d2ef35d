#pragma once
// G114.1 / G113 (spindle synchronisation) and G51.4 / G50.4 (axis synchronisation) as the
// channel asks them of the slave's axis node, which holds the coupling (ARCHITECTURE.md §5). A
// request is checked against the machine's set-up first (a group this channel's spindle leads; a
// slave that may follow, of this channel, not following another master; a master of the same
// kind that is no slave itself), then sent; the block ends once the slave's feedback shows it in
// phase (G114.1), free (G113), following its master (G51.4) or this channel's again (G50.4).
// Pure: one step() per cycle with the feedback of that cycle; no allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mcnc::coordination {

// G114.1 group K (param 1420) whose master is this channel's spindle: the slave's feedback is
// `feedback[slave_view]` (after the channel's axes and spindles).
struct SpindleGroupSetup {
  int group = 1;
  std::size_t slave_view = 0;
};
struct SpindleSyncOut {
  bool on = true;  // G114.1; false: G113
  int group = 0;   // K; 0 with G113: every group of the channel
  int p = 1;
  int q = 1;
  double r = 0.0;
};
// G51.4 (on) or G50.4 to the node of the axis in `slot`.
struct AxisSyncOut {
  bool on = true;
  std::size_t slot = 0;
  std::uint32_t master = 0;  // axis id
};

struct CouplingSetup {
  std::size_t axis_count = 0;
  std::vector<AxisSlot> slots;
  std::vector<SpindleGroupSetup> spindle_groups;
  std::vector<MachineAxis> machine_axes;  // by system number - 1
};

struct CouplingInputs {
  std::uint64_t cycle = 0;
  std::span<const AxisFeedbackView> feedback;  // the channel's axes, spindles, then slaves
  std::span<const SlotUse> slot_use;           // what the channel does with each slot now
};

enum class CouplingStep : std::uint8_t {
  waiting,  // for the slave's node
  send,     // spindle_sync() or axis_sync() (as axis() says) goes out this cycle
  done,     // the block ends; slot_change() says what became of the slave axis
  alarm,
};

// What a G51.4 / G50.4 makes of the slave axis's slot in the channel.
struct SlotChange {
  enum class To : std::uint8_t { none, follows, commanded } to = To::none;
  std::size_t slot = 0;
  double at = 0.0;  // commanded: where the axis stands (its master took it there)
};

class CouplingRequest {
 public:
  explicit CouplingRequest(CouplingSetup setup) : setup_(std::move(setup)) {}

  void begin_spindle(const SpindleSyncOut& sync) noexcept;
  // G51.4 (`on`) / G50.4 Q`slave` [P`master`, 0: the slave's default master].
  void begin_axis(bool on, std::uint32_t master, std::uint32_t slave) noexcept;
  CouplingStep step(const CouplingInputs& in) noexcept;

  [[nodiscard]] bool axis() const noexcept { return axis_; }
  [[nodiscard]] const SpindleSyncOut& spindle_sync() const noexcept { return spindle_; }
  [[nodiscard]] const AxisSyncOut& axis_sync() const noexcept { return axis_sync_; }
  [[nodiscard]] const SlotChange& slot_change() const noexcept { return change_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  enum class Start : std::uint8_t { send, nothing_to_do, refused };
  Start start_spindle() noexcept;
  Start start_axis(const CouplingInputs& in) noexcept;
  [[nodiscard]] bool spindle_done(const CouplingInputs& in) const noexcept;
  bool axis_done(const CouplingInputs& in) noexcept;

  CouplingSetup setup_;
  bool axis_ = false;
  SpindleSyncOut spindle_{};
  AxisSyncOut axis_sync_{};
  std::uint32_t slave_ = 0;  // G51.4 / G50.4 Q: the slave's system number
  bool sent_ = false;
  std::uint64_t sent_cycle_ = 0;
  SlotChange change_{};
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
