#pragma once
// G114.1 / G113 (spindle synchronisation), G51.4 / G50.4 (axis synchronisation), G51.2 /
// G50.2 (polygon turning), G51.8 / G50.8 (electronic cam) and G81.4 / G80.4 (electronic gear
// box) as the channel asks them of the
// slave's axis node, which holds the coupling (ARCHITECTURE.md §5). A request is checked against
// the machine's set-up first (a group this channel's spindle leads; a slave that may follow, of
// this channel, not following another master; a master of the same kind that is no slave itself; a
// polygon axis at rest that the master's speed would not take beyond its limit; a cam slave; a
// gear box not on already), then sent; the block ends once the slave's feedback shows it in phase
// (G114.1, G51.2, G81.4), on its lift (G51.8), free (G113, G50.2: at rest; G50.8: the lift taken
// off; G80.4: stopped, the channel taking the angle it reached), following its master (G51.4) or
// this channel's again (G50.4). Pure: one step() per cycle with the feedback of that cycle; no
// allocation, nothing throws.
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coordination_alarm.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
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

// G51.2 / G50.2 to the node of the channel's polygon axis.
struct PolygonOut {
  bool on = true;    // G51.2; false: G50.2
  int p = 1;         // master ratio
  int q = 1;         // polygon axis ratio (sign: direction)
  double r = 0.0;    // the master's start angle, degrees
  bool wait = true;  // G50.2: the block ends once the polygon axis stands (P1 or no P)
};
// The channel's polygon axis (params 5310-5312): the feedback of its master spindle and of
// itself, a spindle of the channel or one of its rotary servo axes (`slave_axis`: slave_view is
// then its slot, which the program does not move while it follows).
struct PolygonSetup {
  std::uint32_t master = 0;  // the master spindle's axis id; 0: the channel has no polygon axis
  std::size_t master_view = 0;
  std::size_t slave_view = 0;
  double max_speed = 0.0;  // deg/s the polygon axis may turn at most (param 5312)
  bool slave_axis = false;
  bool no_wait = false;  // 5300.5: G51.2 ends without waiting for the polygon axis to lock
};

// The most points a cam table has: macro variables #1-#999 (spec dafeng L3048), the bound of
// the coordination event's cam_lift.
inline constexpr std::size_t kMaxCamPoints = 999;

// G51.8 / G50.8 to the node of the channel's cam slave. a and b are the words of H1 (A, B) or
// H2 (D, P); the slave's node makes its profile of them.
struct CamOut {
  bool on = true;          // G51.8; false: G50.8
  std::uint8_t shape = 0;  // 0: the table lift[0, points); 1: H1 ellipse; 2: H2 eccentric circle
  double a = 0.0;
  double b = 0.0;
  double r = 0.0;  // the master angle of the table's first point, degrees
  std::size_t points = 0;
  std::array<double, kMaxCamPoints> lift{};
};
// The channel's cam (params 5350/5351): the master spindle, and the slave, one of its axes.
struct CamSetup {
  std::uint32_t master = 0;  // axis id; 0: the channel has no cam
  std::size_t slave_slot = 0;
};

// G81.4 / G80.4 to the node of the channel's EGB work axis (or, off, a reset's stop or the
// hand-over of the angle it reached).
struct EgbOut {
  enum class Off : std::uint8_t { stop, reset, absorb };
  bool on = true;  // G81.4; false: `off`
  int teeth = 1;
  int threads = 1;
  double helix = 0.0;   // P, degrees (0: a spur gear)
  double module = 0.0;  // Q, mm
  bool phase = false;   // R given
  double r = 0.0;
  Off off = Off::stop;
};
// The channel's gear box (params 5330-5332, 5320.5): the tool spindle, its feedback's view and
// the work axis's slot (one of the channel's axes).
struct EgbSetup {
  std::uint32_t tool = 0;  // axis id; 0: the channel has no gear box
  std::size_t tool_view = 0;
  std::size_t work_slot = 0;
  bool axial = false;    // an axial feed axis (5332): helical gears may be cut
  bool no_wait = false;  // 5320.5: G81.4 ends without waiting for the work axis to lock
};

struct CouplingSetup {
  std::size_t axis_count = 0;
  std::vector<AxisSlot> slots;
  std::vector<SpindleGroupSetup> spindle_groups;
  std::vector<MachineAxis> machine_axes;  // by system number - 1
  PolygonSetup polygon{};
  CamSetup cam{};
  EgbSetup egb{};
};

struct CouplingInputs {
  std::uint64_t cycle = 0;
  std::span<const AxisFeedbackView> feedback;  // the channel's axes, spindles, then slaves
  std::span<const SlotUse> slot_use;           // what the channel does with each slot now
};

enum class CouplingStep : std::uint8_t {
  waiting,  // for the slave's node
  send,     // spindle_sync(), axis_sync() or polygon() (as kind() says) goes out this cycle
  done,     // the block ends; slot_change() says what became of the slave axis
  alarm,
};

// What a G51.4 / G50.4 makes of the slave axis's slot in the channel.
struct SlotChange {
  enum class To : std::uint8_t { none, follows, commanded } to = To::none;
  std::size_t slot = 0;
  double at = 0.0;  // commanded: where the axis stands (its master took it there)
};

enum class CouplingKind : std::uint8_t { spindle, axis, polygon, cam, egb };

class CouplingRequest {
 public:
  explicit CouplingRequest(CouplingSetup setup) : setup_(std::move(setup)) {}

  void begin_spindle(const SpindleSyncOut& sync) noexcept;
  // G51.4 (`on`) / G50.4 Q`slave` [P`master`, 0: the slave's default master].
  void begin_axis(bool on, std::uint32_t master, std::uint32_t slave) noexcept;
  void begin_polygon(const PolygonOut& polygon) noexcept;
  void begin_cam(const CamOut& cam) noexcept;
  void begin_egb(const EgbOut& egb) noexcept;
  CouplingStep step(const CouplingInputs& in) noexcept;

  [[nodiscard]] CouplingKind kind() const noexcept { return kind_; }
  [[nodiscard]] bool axis() const noexcept { return kind_ == CouplingKind::axis; }
  [[nodiscard]] const SpindleSyncOut& spindle_sync() const noexcept { return spindle_; }
  [[nodiscard]] const AxisSyncOut& axis_sync() const noexcept { return axis_sync_; }
  [[nodiscard]] const PolygonOut& polygon() const noexcept { return polygon_; }
  [[nodiscard]] const CamOut& cam() const noexcept { return cam_; }
  [[nodiscard]] const EgbOut& egb() const noexcept { return egb_; }
  // A reset or an emergency stop: the gear box, if it runs or was asked for, stops as param
  // 5320.4 says (the work axis's node knows how); the G80.4 to send, if any (egb() holds it).
  [[nodiscard]] bool egb_on_reset(std::span<const AxisFeedbackView> feedback) noexcept;
  // Once per cycle: the gear box the channel asked for stopped without a G80.4 (the work axis
  // off the ratio too long, params 5336/5337, or the tool spindle lost): true once, with the
  // alarm set.
  [[nodiscard]] bool egb_lost(const CouplingInputs& in) noexcept;
  // The work axis stands where a stopped gear box left it, off the channel's commanded position:
  // the channel takes that angle (its slot, where), and tells the node (egb() holds the
  // hand-over).
  [[nodiscard]] std::optional<SlotChange> egb_hand_over(
      std::span<const AxisFeedbackView> feedback) noexcept;
  // A reset: the cam, if it runs or was asked for, ends (param 5340.2 = 1): the G50.8 to send,
  // if any (cam() holds it).
  [[nodiscard]] bool cam_on_reset(std::span<const AxisFeedbackView> feedback) noexcept;
  // A reset: the polygon axis, if it follows or was asked to, is released (spec dafeng
  // L2933-2939, param 5300.4 = 1: at once, decelerating); what to send, if anything.
  [[nodiscard]] std::optional<PolygonOut> polygon_on_reset(
      std::span<const AxisFeedbackView> feedback) noexcept;
  // A G51.2 or G81.4 that ended without waiting (params 5300.5 / 5320.5 = 1) and whose slave
  // is not locked yet: the next cutting block waits for it (spec dafeng L2917-2919, L3331-3333).
  [[nodiscard]] bool lock_pending(const CouplingInputs& in) noexcept;
  [[nodiscard]] const SlotChange& slot_change() const noexcept { return change_; }
  [[nodiscard]] const CoordinationAlarm& alarm() const noexcept { return alarm_; }

 private:
  enum class Start : std::uint8_t { send, nothing_to_do, refused };
  Start start_spindle() noexcept;
  Start start_axis(const CouplingInputs& in) noexcept;
  Start start_polygon(const CouplingInputs& in) noexcept;
  Start start_cam(const CouplingInputs& in) noexcept;
  Start start_egb(const CouplingInputs& in) noexcept;
  [[nodiscard]] bool spindle_done(const CouplingInputs& in) const noexcept;
  bool axis_done(const CouplingInputs& in) noexcept;
  bool polygon_done(const CouplingInputs& in) noexcept;
  [[nodiscard]] bool cam_done(const CouplingInputs& in) const noexcept;
  bool egb_done(const CouplingInputs& in) noexcept;

  CouplingSetup setup_;
  CouplingKind kind_ = CouplingKind::spindle;
  SpindleSyncOut spindle_{};
  AxisSyncOut axis_sync_{};
  PolygonOut polygon_{};
  bool polygon_asked_ = false;  // the last G51.2 / G50.2 sent was a G51.2
  CamOut cam_{};
  bool cam_asked_ = false;  // the last G51.8 / G50.8 sent was a G51.8
  EgbOut egb_{};
  bool egb_asked_ = false;  // the last G81.4 / G80.4 sent was a G81.4
  std::uint64_t egb_sent_cycle_ = 0;
  // When a G51.2 / G81.4 was sent without waiting whose lock the next cutting block waits for.
  std::optional<std::uint64_t> polygon_lock_due_;
  std::optional<std::uint64_t> egb_lock_due_;
  std::uint32_t slave_ = 0;  // G51.4 / G50.4 Q: the slave's system number
  bool sent_ = false;
  std::uint64_t sent_cycle_ = 0;
  SlotChange change_{};
  CoordinationAlarm alarm_{};
};

}  // namespace mcnc::coordination
