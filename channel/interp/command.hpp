#pragma once
// The canonical commands of the interpreter: what one pull of Interpreter::next() yields. The
// JSON form (`mcnc interp`, docs/canonical-commands.md) prints these fields by op.
//
// Positions are machine coordinates of the channel's axes, in the channel's axis order: mm for
// linear axes (diameter axes already halved to the physical radius), degrees for rotary axes.
// Work offsets, G52/G50 shifts, the facing-turret mirror and the tool offset are applied.
#include "channel/interp/axis_vector.hpp"
#include "channel/interp/program_alarm.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mcnc::interp {

enum class Op : std::uint8_t {
  rapid,
  linear,
  arc,
  dwell,
  spindle,
  spindle_select,
  tool,
  aux,
  wait_input,
  stop,
  end,
  sync,
  axis_release,
  axis_acquire,
  axis_restore,
  axis_couple,
  axis_decouple,
  spindle_sync,
  spindle_unsync,
  polygon,      // G51.2: the channel's polygon axis follows its master spindle at sync_q/sync_p
  polygon_off,  // G50.2: it is released (`wait`: the block ends once it stands)
  cam,          // G51.8: the channel's cam slave follows a lift per master spindle angle
  cam_off,      // G50.8: the lift is taken off the cam slave
  egb,          // G81.4: the channel's EGB work axis follows its tool spindle (gear box)
  egb_off,      // G80.4: it stops where it reached (`wait`: the block ends once it stands)
  subcall,
  subcall_release,
  message,
  thread,
  spindle_mode,  // M18 / M17 (GSK M14 / M15): `spindle` to position or speed control
  wait_spindle,  // G04 PSn=: until spindle `spindle`'s actual speed is `rpm` (or `dwell_s`)
  // G81.1: axis `oscillating` strokes between `top` and `bottom` by itself.
  oscillate,
  // G80.1: it ends its stroke at a dead point, then goes to `to`.
  oscillate_end,
  // G10 L14 P9: the drives of `torque_data_axes` get `torque_data` from the next block on.
  torque_limit,
  // G10 L14 P0/P1: the loads of `torque_data_axes` watched against `torque_data`; P2-P5
  // (`load_timer` 2-5): a load timer started over them instead.
  load_watch,
  // G10 L14 P20-P51: the time load timer `load_timer` counted for each axis of
  // `torque_data_axes` compared with `torque_data` (s); the axes that meet it go to
  // #`timer_variable` as bits (the channel hands them back: CommandSource::load_timer_result).
  load_timer_check,
  // G10 L14 P10/P11/P12: the axes of `torque_data_axes` to torque mode at `torque_data` % (P10;
  // 0: back to position mode), their speed limit in it (P11, rpm), or back to position mode
  // with `torque_data` as their torque limit (P12; 0: none). `torque_mode_p` says which.
  torque_mode,
};

enum class FeedMode : std::uint8_t { per_min, per_rev };
enum class ArcDirection : std::uint8_t { cw, ccw };
enum class Plane : std::uint8_t { xy, zx, yz };  // G17, G18, G19
// keep: a speed for another channel's spindle whose direction this channel does not know.
enum class SpindleDirection : std::uint8_t { cw, ccw, stop, orient, keep };

// Spindle arguments of G114.1 and the G144 argument vector use these sizes.
inline constexpr int kSubcallArgs = 26;  // #1-#26
// The highest torque a program may name (G160 P, G10 L14): 1000 % of the motor's rated torque,
// what the drive's max torque 0x6072 (per mille) takes.
inline constexpr double kMaxTorquePercent = 1000.0;

// The modal state a block runs in, as a control's modal screen shows it: the G code of groups
// 01 (motion), 16 (plane), 03 (G90/G91: system B only), 05 (feed per minute or revolution), 02
// (G96/G97), 06 (inch/metric), 07 (nose radius compensation) and 14 (work coordinates), each
// as ten times its number (G54.1: 541; 0 in any group but 01: the group has no code), and the
// modal F (per minute or revolution, by group 05).
inline constexpr std::array<int, 8> kShownModalGroups{1, 16, 3, 5, 2, 6, 7, 14};
struct ModalState {
  std::array<std::uint16_t, kShownModalGroups.size()> g{};
  double feed = 0.0;
};

// The file name of blocks the operator typed (MDI), in their alarms and the trace.
inline constexpr std::string_view kMdiName = "MDI";

struct Command {
  // User-provided, so that value-initialisation (`emplace_back()`, `Command{}`) runs the member
  // initialisers only, without zeroing all of the object first: one is made per command.
  Command() noexcept {}  // NOLINT(modernize-use-equals-default)

  Op op = Op::rapid;
  std::uint64_t n = 0;                // 1-based sequence number of the command in this run
  int line = 0;                       // 1-based line of the block in its file
  const std::string* file = nullptr;  // the file of the block (owned by the interpreter)
  // The block's line as written, for the trace (not printed: a view into the interpreter's copy
  // of the file, valid as long as `file`).
  std::string_view block_text;
  // The interpreter evaluated nothing after this block and will not until it is pulled past:
  // the read-ahead barriers of spec dafeng §4.3 and the multi-channel words.
  bool barrier = false;
  ModalState modal;  // in force for this block

  // rapid, linear, arc: end point of every channel axis (unmoved axes keep their position).
  AxisVector to{};
  double feed = 0.0;  // linear, arc: mm/min or mm/rev (FeedMode)
  FeedMode feed_mode = FeedMode::per_min;
  bool exact_stop = false;  // linear, arc: stop exactly at the end (G09, G61)
  // arc: centre in the two plane axes (axis indices), direction, plane, extra full turns.
  Plane plane = Plane::zx;
  ArcDirection direction = ArcDirection::cw;
  std::array<int, 2> center_axes{};
  std::array<double, 2> center{};
  int turns = 0;

  // thread (G32, G34, G32.1, G32.2/G32.3 and the threading cycles): `to` as a linear move (an
  // arc thread also has the arc fields); lead along the long axis (the plane axis that travels
  // farther, physical), its change per revolution (G34), the spindle angle where the thread
  // starts (degrees). continuous: starts without waiting for the one-revolution signal (the
  // next block of a continuous thread, or NQ1). rpm > 0: interpolated thread (G32.1, G32.2 S):
  // the spindle is a position-controlled axis turning at rpm. The reference spindle is
  // `spindle`. left_hand: an interpolated thread whose spindle turns the negative way (GSK
  // G92.1 F < 0): the start angle counts that way too.
  double lead = 0.0;
  double lead_change = 0.0;
  double start_angle = 0.0;
  bool continuous = false;
  bool left_hand = false;
  bool thread_arc = false;

  // dwell: seconds, or spindle revolutions when in_revs.
  double seconds = 0.0;
  bool in_revs = false;

  // spindle / spindle_select: spindle number within `channel` (0 = this channel).
  int spindle = 1;
  int channel = 0;
  SpindleDirection spindle_direction = SpindleDirection::stop;
  double rpm = 0.0;
  bool css = false;  // constant surface speed: `surface` m/min, clamped at `max_rpm`
  double surface = 0.0;
  double max_rpm = 0.0;    // 0: no G50 S clamp programmed
  bool has_angle = false;  // M05 PA: stop at `angle` degrees
  double angle = 0.0;
  int divisions = 0;              // M05 PN: stop at the nearest multiple of 360/PN
  bool position_control = false;  // spindle_mode: true M18 (C1 mode), false M17

  // tool
  int tool = 0;
  int offset = 0;

  // aux, stop (0 = M00, 1 = M01), end (2 or 30)
  int code = 0;

  // linear with skip (G31): the move ends where skip input `input` goes on (input_on) or off;
  // the channel then hands the skip position back (CommandSource::skip_result).
  bool skip = false;
  // G31 P1-P8: the skip signal is the PLC's G0014.(skip_signal - 1) going on, not a probe
  // input (`input` is then 0); 0: a touch probe's input.
  int skip_signal = 0;
  // G31.8 (multi_skip): the move goes on past each signal, up to max_signals of them.
  bool multi_skip = false;
  int max_signals = 0;
  // G160 (torque_skip): the axis's torque limited to torque_limit percent of the motor's rated
  // torque (-1: the limit cancelled, no skip); it skips when the torque reaches it and the
  // following error exceeds `deviation` (mm, physical).
  bool torque_skip = false;
  double torque_limit = 0.0;
  double deviation = 0.0;
  std::size_t skip_axis = 0;  // G160: the channel axis it moves (index into the channel's axes)
  // G31 P98/P99 (load_skip): per channel axis that the move moves, the load ratio it skips at,
  // percent of the rated torque (G10 L14 P6, else param 5511; 0: not watched). The axis's
  // torque is limited to it and the move skips where the axis is held back at it, as G160's
  // with deviation 0; P99 (`skip` as well) also on the block's input.
  bool load_skip = false;
  std::array<double, kMaxChannelAxes> load_ratio{};
  // G10 L14's values per axis, percent of the motor's rated torque, for each channel axis i with
  // bit i of torque_data_axes: torque_limit (P9) the drive's limit (0: cancelled), load_watch
  // (P0/P1) the reference load above which the axis overloads (no axes: every check
  // cancelled); `every_move` P0 (all moves of the axis) or P1 (its G01 moves), `filter_s` J,
  // how long the load must stay above (s).
  std::uint32_t torque_data_axes = 0;
  std::array<double, kMaxChannelAxes> torque_data{};
  bool every_move = false;
  double filter_s = 0.0;
  // load_watch: 0 for P0/P1, else the load timer P2-P5 starts (2-5; no alarm, it counts the
  // seconds above the reference). load_timer_check: the timer read (P20/P21: 2 ... P50/P51: 5),
  // `timer_longer` P21/P31/P41/P51 (more than the seconds) or P20/.../P50 (less), and the
  // variable R (0: none, the condition met is an alarm).
  int load_timer = 0;
  bool timer_longer = false;
  std::int64_t timer_variable = 0;
  int torque_mode_p = 0;  // torque_mode: 10, 11 or 12
  // G10 L14 P7/P8 (decision 162): a hole cycle's in-feed whose load is watched (bit i of
  // overload_axes: channel axis i at overload_loads[i] % of the rated torque, for
  // overload_filter_s seconds in a row; 0: not watched). On an overload the move stops, the
  // tool goes back along it to the hole's R point, overload_retract (mm) short of `to`, then
  // the cycle alarms, goes on with the next block or retries the in-feed (overload_outcome);
  // overload_variable (0: none) counts the overloads. overload_p is 7 (drilling) or 8
  // (tapping); overload_block names the block whose commands a `go_on` drops.
  enum class Overload : std::uint8_t { stop, alarm, go_on, retry };
  std::uint32_t overload_axes = 0;
  std::array<double, kMaxChannelAxes> overload_loads{};
  double overload_filter_s = 0.0;
  double overload_retract = 0.0;
  Overload overload_outcome = Overload::stop;
  std::int64_t overload_variable = 0;
  int overload_p = 7;
  std::uint64_t overload_block = 0;
  // wait_input (G04 I): input number, wanted state, optional timeout/width/dwell (< 0: none).
  // wait_spindle (G04 PS) takes `spindle`, `rpm` and `dwell_s`.
  int input = 0;
  bool input_on = true;
  double timeout_s = -1.0;
  double width_s = -1.0;
  double dwell_s = -1.0;

  // sync (G04.1): no P = read-ahead barrier only; `all_channels` for Q-1 or P without Q.
  bool has_p = false;
  int p = 0;
  bool all_channels = false;
  std::array<std::uint64_t, 4> channels{};  // bit c set: channel c takes part (1-255)

  // axis_release / axis_acquire: axis letter and exchange number; force for G141 P1.
  char axis = 0;
  int exchange = 0;
  bool force = false;
  // axis_couple / axis_decouple (system axis numbers); master 0 = from the machine's parameters.
  int master = 0;
  int slave = 0;

  // spindle_sync (G114.1): P, Q, K, R; polygon (G51.2): P, Q, R.
  int sync_p = 1;
  int sync_q = 1;
  int sync_k = 1;
  double sync_r = 0.0;

  // cam (G51.8, R in sync_r): the shape (CamShape: 0 a table, 1 the ellipse of H1, 2 the
  // eccentric circle of H2); the table's first variable (P) and its lift values as they stood
  // when the block ran; the ellipse's semi-axes A and B, or the circle's diameter D and
  // eccentricity P, in cam_a and cam_b.
  int cam_shape = 0;
  int cam_first = 0;
  std::vector<double> cam_lift;
  double cam_a = 0.0;
  double cam_b = 0.0;

  // egb (G81.4): T the work's teeth and L the hob's threads (the work axis turns L/T times the
  // tool spindle, L's sign its direction); P the helix angle (degrees, 0: a spur gear) and Q
  // the module (mm, its sign the helical term's direction); R the work axis's phase (sync_r)
  // when egb_phase, else no phase matching. egb_off (G80.4) takes `wait`.
  int egb_teeth = 1;
  int egb_threads = 1;
  double egb_helix = 0.0;
  double egb_module = 0.0;
  bool egb_phase = false;

  // subcall (G144)
  int program = 0;
  bool wait = true;
  int repeat = 1;
  std::vector<std::pair<int, double>> args;  // (#number, value) of the given arguments

  // message (#3006)
  std::string text;

  // oscillate (G81.1): channel axis `oscillating` moves from where it stands to its top dead
  // point, then between `top` and `bottom` (machine, physical), each stroke half a sine whose
  // top speed is `feed` (units/min, whatever the feed mode and override), while the blocks after
  // it run. oscillate_end (G80.1): the stroke under way ends at its dead point, then one stroke
  // to `to` (every other axis keeps its position); the block ends there.
  int oscillating = 0;
  double top = 0.0;
  double bottom = 0.0;

  // What the block asks of the look-ahead that follows the interpreter's blocks (not printed:
  // the look-ahead consumes them): the corner to insert after this move (,C ,R / L D) and the
  // tool-nose compensation in effect for the move.
  enum class Corner : std::uint8_t { none, chamfer_setback, chamfer_length, round };
  Corner corner = Corner::none;
  double corner_size = 0.0;
  double corner_feed = 0.0;  // the corner's feed (E); 0: the move's feed
  enum class Compensation : std::uint8_t { off, left, right };
  Compensation compensation = Compensation::off;
  double nose_radius = 0.0;
  int nose_tip = 0;
  // Normal direction control for this move (G41.1/G42.1; not printed: the interpreter turns the
  // axis on the path the look-ahead releases, channel/interp/normal_direction.hpp): left or
  // right of travel in the plane of `normal_plane` (channel axes), or `hold`: the axis stays
  // where the control's last move leaves it (a move after G40.1 made before that was known).
  enum class Normal : std::uint8_t { off, left, right, hold };
  Normal normal = Normal::off;
  std::array<int, 2> normal_plane{};
  // The channel axis whose travel the feed does not count, -1: none (not printed). The normal
  // direction axis turning with an arc: F is the tool's feed along the path in the plane, and
  // the axis turns in the time that takes, as fast as its own limits allow (decision 139).
  int feed_without_axis = -1;
  // Chip breaking in force for this cutting move (G98.1/G99.1; not printed: the interpreter
  // splits the move before it leaves): the path length of one spindle revolution (0: none),
  // the revolutions of feed between breaks (Q) and the break (P: > 0 a dwell of P
  // revolutions, < 0 back along the path for -P revolutions and forward again).
  double chip_rev_length = 0.0;
  double chip_every = 0.0;
  double chip_break = 0.0;
  // G98.1 under G96: the spindle's speed follows the radius, and so do the revolutions a mm of
  // path takes. The surface speed (m/min; 0: a constant speed, chip_rev_length holds), the G50 S
  // limit (rpm), the axis whose distance from chip_centre (machine, physical) is the radius,
  // and `feed` (mm/min) make the speed at each point; chip_rev_length is then the shortest.
  double chip_surface = 0.0;
  double chip_max_rpm = 0.0;
  int chip_radius_axis = 0;
  double chip_centre = 0.0;

  // rapid, linear, arc or thread: the command moves the axes to `to`.
  bool moves() const {
    return op == Op::rapid || op == Op::linear || op == Op::arc || op == Op::thread;
  }
  void set_channel(int c) { channels[static_cast<std::size_t>(c) / 64] |= 1ULL << (c % 64); }
  bool has_channel(int c) const {
    return (channels[static_cast<std::size_t>(c) / 64] >> (c % 64)) & 1ULL;
  }
};

}  // namespace mcnc::interp
