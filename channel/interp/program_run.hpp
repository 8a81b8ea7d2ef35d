#pragma once
// The state of one interpreter run and its execution, behind Interpreter (interpreter.hpp).
// The run's state that is a value of its own lives in channel/interp/state/: the modal state
// (ModalState), the coordinate systems (CoordinateSystems), the spindles (SpindleState), the
// tools and their offsets (ToolTable), the modal hole cycle (HoleMode) and the G70-G73 contour
// (ContourCapture); the rules over each (the offsets' sum, a tool offset on an axis, ...) are
// their members. ProgramRun holds one of each and the flow, the block and the transforms.
// The execution: program_run.cpp: programs, calls and macro statements; program_run_block.cpp:
// NC blocks; program_run_motion.cpp: coordinates and motion; program_run_corners.cpp: chamfers
// and corner rounds (,C ,R); program_run_thread.cpp: threading and the single cycles;
// program_run_cycles.cpp: the multiple repetitive cycles G71-G76 and the hole cycles' words;
// program_run_contour.cpp: the finishing contour of G70-G73; program_run_holes.cpp: the hole
// cycles (lathe G83-G89, mill G73-G89); program_run_positioning.cpp: the mill's G27/G29/G60;
// program_run_tool_length.cpp: the mill's T, H and D; program_run_frame.cpp: the G68.1 rotation
// and the G51.1 mirror; program_run_polar.cpp: G12.1 polar interpolation;
// program_run_cylinder.cpp: G07.1; program_run_inclined.cpp: inclined-axis control;
// program_run_chip_breaking.cpp: G98.1/G99.1; program_run_normal.cpp: G40.1-G42.1;
// program_run_oscillation.cpp: G81.1; program_run_skip.cpp: G31, G31.8 and G160;
// program_run_torque.cpp: G10 L14; program_run_stroke.cpp: G22/G23; system_variables.cpp: the
// system variables (#2000-#19999).
#include "channel/interp/block_lookahead.hpp"
#include "channel/interp/cycles/multiple_thread.hpp"
#include "channel/interp/gcode_table.hpp"
#include "channel/interp/interpreter.hpp"
#include "channel/interp/limits/stroke_zone.hpp"
#include "channel/interp/normal_direction.hpp"
#include "channel/interp/parse/parsed_program.hpp"
#include "channel/interp/path/plane_path.hpp"
#include "channel/interp/state/contour_capture.hpp"
#include "channel/interp/state/coordinate_systems.hpp"
#include "channel/interp/state/hole_mode.hpp"
#include "channel/interp/state/modal_state.hpp"
#include "channel/interp/state/spindle_state.hpp"
#include "channel/interp/state/tool_table.hpp"
#include "channel/interp/transform/axis_mirror.hpp"
#include "channel/interp/transform/cylindrical_interpolation.hpp"
#include "channel/interp/transform/plane_rotation.hpp"
#include "channel/interp/transform/polar_interpolation.hpp"
#include "channel/interp/transform/transform_chain.hpp"

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mcnc::interp {

// One evaluated word of the block being executed.
struct BlockWord {
  parse::Address address;
  int index = -1;
  double value = 0.0;
  bool has_point = false;
  bool literal = true;
  int column = 0;
  bool used = false;
};

// Thrown nowhere: every failing step returns false after recording the alarm in `alarm_`.
class ProgramRun final : public macro::VariableProvider {
 public:
  ProgramRun(const InterpreterConfig& config, const InterpreterEnvironment* environment);

  std::optional<ProgramAlarm> start_text(std::string text, const std::string& file_name);
  // The same, read from the file at `path` as it runs (file_name: its name in alarms).
  std::optional<ProgramAlarm> start_file(const std::string& path, const std::string& file_name);
  std::optional<ProgramAlarm> start_number(int number);
  // Starts O<number> as a program called from another channel (G144): its locals #1-#26 are
  // the call's arguments, and M99 at its top level ends it instead of looping.
  std::optional<ProgramAlarm> start_called(int number,
                                           std::span<const std::pair<int, double>> args);
  // Starts blocks the operator typed (MDI): the end of the text ends them (end code 0), as do
  // M30, M02 and an M99 at their top level.
  std::optional<ProgramAlarm> start_mdi(std::string text);
  std::optional<InterpResult> next();
  std::vector<ProgramAlarm> take_warnings();

  macro::VariableStore& variables() { return vars_; }
  // The machine position (machine_ turned and mirrored by the frame).
  AxisVector machine() const;
  void set_machine(const AxisVector& at);
  // The last G31: skipped at `skip_at` (machine), or not; the axes stand at `stop_at`.
  void set_skip_result(bool skipped, const AxisVector& skip_at, const AxisVector& stop_at);
  void set_multi_skip_result(std::span<const double> latched, const AxisVector& stop_at);
  // The last G10 L14 P20-P51: the axes (bit i: channel axis i) that met its condition, written
  // to its R variable when any did.
  void set_load_timer_result(std::uint32_t axes);
  // The G10 L14 P7/P8-watched in-feed just pulled (Interpreter::overload_result).
  void set_overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                           const AxisVector& stop_at);
  double program_position(int axis) const;
  std::optional<ProgramAlarm> save_retained();
  std::size_t main_block_count() const;

  macro::VariableRead read(std::int64_t number) const override;
  macro::MacroAlarm write(std::int64_t number, macro::MacroValue value) override;

 private:
  enum class CallKind : std::uint8_t { main, subprogram, macro };
  struct Frame {
    const parse::ParsedProgram* program = nullptr;
    int pc = 0;        // next line to execute
    int start_pc = 0;  // where a repetition starts
    int repeats_left = 0;
    CallKind kind = CallKind::main;
    bool modal_call = false;  // a G66 call: its own motion does not call again
    bool t_call = false;      // the T-code program: its T words are real T commands
  };
  struct ModalCall {
    bool active = false;
    int program = 0;
    int repeat = 1;
    std::array<macro::MacroValue, 33> args{};
    std::size_t frame_depth = 0;  // frames when G66 was given
  };

  // ---- programs and flow (program_run.cpp)
  parse::StructureLimits structure_limits() const;
  program::ProgramStore& store();
  std::optional<ProgramAlarm> start_programs(program::SplitResult split,
                                             const std::string& file_name);
  const parse::ParsedProgram* find_program(int number, int column);
  bool step();
  bool execute(const parse::Line& line, int index, const parse::Statement& s);
  bool evaluate(const parse::Statement& s, int expression, macro::MacroValue& out);
  bool condition(const parse::Statement& s, int expression, bool& out);
  bool assign(const parse::Line& line, const parse::Statement& s);
  const std::string& message_of(const parse::Line& line) const;
  bool jump_to_sequence(std::int64_t n, parse::GotoDirection direction, int column);
  int find_sequence(const parse::ParsedProgram& p, std::int64_t n, int from,
                    parse::GotoDirection direction, int column);
  bool call_subprogram(int program, int start_sequence, int repeat, int column, bool t_call);
  bool call_macro(int program, int repeat, const std::array<macro::MacroValue, 33>& args,
                  int column, bool modal);
  bool return_from_subprogram(std::int64_t return_sequence, int column);
  void end_program(int code);

  // ---- NC blocks (program_run_block.cpp)
  bool execute_block(const parse::Line& line, const parse::Statement& s);
  bool evaluate_words(const parse::Statement& s);
  bool repeat_word(std::int64_t& repeat);
  bool program_word(const char* code, int column, std::int64_t& program);
  // A macro-type call (G65, G/M macro codes): L repeats, the other words are arguments.
  bool call_with_arguments(int program, int column, bool p_is_program);
  bool collect_macro_args(std::array<macro::MacroValue, 33>& args, bool type_one_only,
                          bool reserve_p);
  bool apply_modal(GFunction f, int code10, int column);
  bool run_spindle_words(bool has_m_spindle);
  // A spindle of this channel named by its number (`what`: the words that name it) must be one
  // the channel has.
  bool own_spindle(int spindle, const std::string& what, int column);
  // C1 mode codes: 1 for position control (Dafeng M18 + 100(n-1), GSK M14), 0 for speed
  // control (M17 + 100(n-1), GSK M15), -1 for any other M code; `spindle` is set to the one
  // addressed. position_code() names the code of the dialect, for messages.
  [[nodiscard]] int control_code(std::int64_t m, int& spindle) const;
  [[nodiscard]] std::string position_code(int spindle, bool position) const;
  bool run_tool_word();
  // The mill's T (a tool number), H (length offset) and D (radius offset) words
  // (program_run_tool_length.cpp).
  bool run_mill_tool_words();
  bool run_length_compensation(GFunction f, double value);  // G43 / G44 / G49
  // The offset number whose radius G41/G42 use: the mill's D, the lathe's T offset.
  int radius_offset() const;
  bool run_m_codes(bool after_motion);
  bool run_one_shot(GFunction f, int code10, int column);
  bool run_dwell(int column);
  bool run_channel_sync(int column);
  bool run_data_input(int column);
  bool run_channel_call(int column);
  bool run_axis_exchange(GFunction f, int column);
  bool run_spindle_sync(GFunction f);
  bool run_polygon(GFunction f, int column);
  bool run_coupling_off(Op op, const char* code, const char* axis);  // G50.2 P, G80.4 P
  bool run_cam(GFunction f, int column);
  bool run_cam_table(Command& c, int column);
  bool run_gear_box(GFunction f);  // G81.4 / G80.4
  bool run_axis_sync(GFunction f, int column);
  bool check_unused_words();

  // ---- coordinates and motion (program_run_motion.cpp)
  struct AxisWords {
    BlockWord* word = nullptr;  // the axis's word in this block, if any
    bool incremental = false;
    bool error = false;  // an alarm was raised (absolute and incremental together)
  };
  AxisWords axis_words(int axis);
  // Calls f(axis, word, incremental) for every channel axis the block programs, marking its word
  // used; stops and returns false when f does or an alarm is raised.
  template <typename F>
  bool for_each_axis_word(F&& f) {
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      const AxisWords aw = axis_words(static_cast<int>(i));
      if (aw.error) {
        return false;
      }
      if (aw.word == nullptr) {
        continue;
      }
      aw.word->used = true;
      if (!f(static_cast<int>(i), *aw.word, aw.incremental)) {
        return false;
      }
    }
    return true;
  }
  bool read_axis_targets(AxisVector& target, std::array<bool, kMaxChannelAxes>& given,
                         bool machine_coordinates);
  bool run_motion(GFunction motion, bool machine_coordinates, int column);
  bool run_arc(GFunction motion, const AxisVector& target, int column);
  // The arc of a G02/G03/G05 block to `target` in the plane of `axes`, after its feed check.
  bool emit_arc(const AxisVector& target, const std::array<int, 2>& axes, ArcDirection dir,
                const std::array<double, 2>& center, int turns, int column);
  // G05 / G05.1: the arc through the middle point of I/K (`any`: the block has axis words).
  bool run_three_point_arc(GFunction motion, const AxisVector& target, bool any, int column);
  // ,C ,R and E (Dafeng) or L D (GSK) of a G01/G02/G03 block: the corner after its move.
  bool take_corner_request();
  void mark_corner(Command& c) const;
  // ,A (Dafeng) or Q (GSK) of a G01/G00 block: completes `target`; false after an alarm. Sets
  // `deferred` when the block gives the angle only and its end comes with the next block.
  bool apply_line_angle(AxisVector& target, std::array<bool, kMaxChannelAxes>& given,
                        bool& deferred, int column);
  bool run_reference_return(GFunction f, int column);
  // The mill's G27, G29 and G60 (program_run_positioning.cpp).
  bool run_reference_check(int column);
  bool run_return_from_reference(int column);
  bool run_single_direction(int column);
  bool run_coordinate_set(int column);
  bool run_local_system(int column);
  bool run_restore_origin(int column);
  double offset_sum(int axis) const;   // EXT + work + G50 shift + G52 (physical)
  double tool_offset(int axis) const;  // physical
  double to_physical(int axis, double programmed, bool mirror = true) const;
  double to_programmed(int axis, double physical, bool mirror = true) const;
  // A value of the axis's data (G53's positions, G10 L2 and #5201.. work offsets): as its
  // parameter makes it a diameter or a radius, whatever G10.9 switched.
  double data_to_physical(int axis, double value) const;
  double physical_to_data(int axis, double physical) const;
  bool run_radius_switch(int column);  // G10.9

  // ---- G98.1 / G99.1 chip breaking (program_run_chip_breaking.cpp)
  bool run_chip_breaking(GFunction f, int column);
  // The block's cutting moves get the chip breaking in force (false after an alarm) ...
  bool mark_chip_breaking();
  // ... and leave split at the breaks: ready_[from..] from released_at_.
  void split_chip_breaking(std::size_t from);

  // ---- G40.1 / G41.1 / G42.1 normal direction control (program_run_normal.cpp)
  bool run_normal_direction(GFunction f, int column);
  // ---- G81.1 / G80.1 oscillation (program_run_oscillation.cpp)
  bool run_oscillation(GFunction f, int column);
  // No released move may take an oscillating axis away from where G81.1 left it.
  void check_oscillation(std::size_t from);
  // False after alarm 1161 when an axis still oscillates at the program's end.
  bool oscillation_ended();
  bool run_skip(int column);
  bool run_multi_skip(int column);        // G31.8
  bool run_torque_skip(int column);       // G160
  bool run_torque_data(int column);       // G10 L14 (program_run_torque.cpp)
  bool run_load_ratio(int column);        // G10 L14 P6
  bool run_torque_limit(int column);      // G10 L14 P9
  bool run_load_watch(int column);        // G10 L14 P0/P1, P2-P5 (the load timers)
  bool run_load_timer_check(int column);  // G10 L14 P20-P51
  bool run_torque_mode(int column);       // G10 L14 P10-P12
  bool run_overload_watch(int column);    // G10 L14 P7/P8 (program_run_overload.cpp)
  // A hole cycle's in-feed `c` (a drilling feed, or a tap step with `tapping`, into the hole,
  // ending `depth` mm past R): watched for overload when G10 L14 P7 (drilling) or P8 (rigid
  // tapping) is on.
  void watch_overload(Command& c, bool tapping, double depth);
  // G10 L14's per-axis values (`what` in an alarm), absolute addresses only, 0-`max` in
  // `unit`: into `values`, bit i of `given` for each axis named.
  bool read_axis_values(const char* what, const char* unit, double max, AxisVector& values,
                        std::uint32_t& given);
  bool read_axis_percents(const char* what, AxisVector& values, std::uint32_t& given);
  // G31 P98/P99: the load ratio of each axis the move from `from` moves; an alarm when none
  // has one.
  bool set_load_ratios(Command& c, const AxisVector& from, const char* code, int column);
  // What G31, G31.8 and G160 share (`code` names the block's code in an alarm): not in polar or
  // cylindrical interpolation nor under G41/G42; the input of L, K, I or param 5510; the
  // variable a word names (0 without the word); the feed move (`one_axis`: exactly one axis
  // named), a read-ahead barrier with exact stop (nullptr after an alarm).
  bool skip_move_allowed(const char* code, int column);
  bool read_skip_input(const char* code, int column, int& input, bool& on);
  bool read_result_variable(char letter, const char* code, const char* what,
                            std::int64_t& variable);
  Command* emit_skip_move(const char* code, bool one_axis, int column);
  // #5061.. from `skip_at` (machine) and the R variable of the last G31.
  void record_skip(bool skipped, const AxisVector& skip_at);
  // G31.8: the machine positions of its axis at each signal into #P.., their count into #R.
  bool record_multi_skip(std::span<const double> at, int column);
  // An axis's machine position in programmed units, as #5021 reads it (X as a diameter).
  double machine_reading(std::size_t axis, double physical) const;
  // The block's moves (out_) tagged for normal direction control (Command::normal): turned by
  // the side in force, or held where the control leaves the axis after G40.1 (false after an
  // alarm: the block programs the axis the control turns).
  bool tag_normal_direction();
  // The released commands ready_[from..] turned (NormalDirection); the program learns the axis's
  // angle once the look-ahead holds no move of the control.
  void turn_normal_direction(std::size_t from);

  // ---- G22 / G23 stored stroke check 2 (program_run_stroke.cpp)
  bool run_stroke_check(GFunction f, int column);
  // The moves ready_[from..] against the forbidden area: alarm 1156 at the line of the first
  // that would enter it, before it leaves.
  void check_stroke(std::size_t from);
  std::string stroke_limits_text() const;  // "X 10.000..50.000, Z ..." in the data's unit
  bool check_feed(int column);
  void apply_tool_offset(int offset);
  // The channel axes of the current plane's first and second axis (-1 when missing).
  std::array<int, 2> plane_axis_indices() const;
  bool require_plane_axes(std::array<int, 2>& axes, int column);
  // Centre of an arc from `from` to `target` in the current plane from R or I/J/K (the words of
  // the block); with R the direction picks the side. Marks the words used.
  bool arc_center(bool ccw, const std::array<int, 2>& axes, const AxisVector& target,
                  std::array<double, 2>& center, int column);

  // ---- the G68.1 rotation and the G51.1 mirror (program_run_frame.cpp)
  bool run_rotation(GFunction f, int column);  // G68.1 / G69.1
  bool run_mirror(GFunction f, int column);    // G51.1 / G50.1
  bool frame_active() const { return rotated_ || program_mirror_.active(); }
  // The rotary axis that polar interpolation makes a virtual linear axis (a length, not degrees).
  bool polar_virtual(int axis) const { return polar_ && axis == polar_axes_[1]; }
  bool cylinder_axis(int axis) const { return cylindrical_ && axis == cylinder_axis_; }
  // False after alarm 1153 when `f` may not run while the frame is turned or mirrored.
  bool frame_allows(GFunction f, int code10, int column);
  // Builds frame_ from the rotation, the mirror and the offsets in force, the machine staying
  // where it is; the commands made so far go out under the frame they were made in.
  void rebuild_frame();
  // The block's commands not yet mapped: positions and centres from the frame to the machine.
  void map_to_machine();

  // ---- G12.1 / G13.1 polar interpolation (program_run_polar.cpp)
  bool run_polar(GFunction f, int column);
  // G13.1 and the program end: the machine's position back on the linear and rotary axes.
  void end_polar();
  // G16 in G12.1: the polar plane's target of the block's radius and angle words (given the
  // linear and rotary axis); false after an alarm.
  bool polar_coordinate_target(AxisVector& target, std::array<bool, kMaxChannelAxes>& given);
  // False after alarm 1154 (or 1122) when the code may not run in polar interpolation.
  bool polar_allows(GFunction f, int code10, int column);
  // The commands list[from..] from the mode's plane to the machine, after the look-ahead (the
  // corners and the compensation work in the mode's plane): every line and arc becomes the
  // machine lines that keep the tool tip on it.
  void expand_modes(std::vector<Command>& list, std::size_t from);
  void expand_polar(std::vector<Command>& list, std::size_t from);

  // ---- G07.1 cylindrical interpolation (program_run_cylinder.cpp)
  bool run_cylindrical(int column);
  void end_cylindrical();  // G07.1 C0 and the program end: the rotary axis in degrees again
  void expand_cylindrical(std::vector<Command>& list, std::size_t from);
  // Polar or cylindrical interpolation: the program's plane is not the machine's.
  bool interpolation_mode() const { return polar_ || cylindrical_; }
  // Shared by both: the machine lines of programmed move `c` from `from` (as machine_) and the
  // machine position `start`; each step gives the machine values of `axes` and the length of
  // contour it covers. The other axes move in proportion; F is scaled to the contour.
  struct ModeStep {
    double first = 0.0;
    double second = 0.0;
    double length = 0.0;
  };
  void emit_mode_steps(std::vector<Command>& into, const Command& c, const AxisVector& from,
                       const AxisVector& start, const std::array<int, 2>& axes,
                       const std::vector<ModeStep>& steps, double total);
  // Shared by both: programmed line or arc `c` from `from` as a piece of the mode's plane on
  // `axes`, every coordinate less `shift` (polar interpolation's offsets; none on the cylinder).
  static transform::PlanePiece plane_piece(const Command& c, const AxisVector& from,
                                           const std::array<int, 2>& axes,
                                           const std::array<double, 2>& shift);

  // ---- inclined-axis control (program_run_inclined.cpp)
  bool inclined_on() const { return !inclined_.identity(); }
  // The machine's inclined coordinates of a Cartesian machine position and back; the identity
  // without inclined-axis control.
  AxisVector to_inclined(const AxisVector& cartesian) const;
  AxisVector from_inclined(const AxisVector& inclined) const;
  // False after alarm 1159 when `axis` (a channel axis) is the inclined or the orthogonal axis,
  // which `what` may not take (spec L4653-4767: no exchange, no G51.4 slave).
  bool inclined_allows(int axis, const std::string& what, int column);
  // The commands list[from..] from the Cartesian machine (after the look-ahead and the polar or
  // cylindrical expansion) to the inclined one: end points mapped, every arc as chords within
  // polar_tolerance of it, F and the thread lead scaled so that each move takes as long (or as
  // many revolutions) as the programmed one.
  void expand_inclined(std::vector<Command>& list, std::size_t from);

  // ---- threading and single cycles (program_run_thread.cpp)
  bool run_thread(GFunction f, int column);
  bool run_flexible_tap(int column);  // G33 (GSK)
  // The lead from F or I (or the last one). GSK G92.1 and G32.1 take a signed F (gsk A.6.29,
  // A.6.39): < 0 is a left-hand thread, which sets left_hand_thread_ (modal with the lead).
  bool thread_lead(double& lead, int column);
  bool signed_lead() const;
  bool thread_start_angle(double& angle);
  // GSK G92/G92.1 P (gsk A.6.41): whether this block and the modal blocks after it repair a
  // thread, into cycle_repair_ (false after an alarm).
  bool thread_repair_word(const std::string& code, bool cycle_code_in_block, int column);
  // The start angle that puts the groove of the thread from `start` to `end` (machine points
  // on `axes`) through the recorded position: false after alarm 1160 (its Z not on the thread,
  // or the thread longer along X).
  bool thread_repair_angle(const std::array<double, 2>& start, const std::array<double, 2>& end,
                           const std::array<int, 2>& axes, double lead, double& angle, int column);
  bool run_single_cycle(GFunction f, bool cycle_code_in_block, int column);
  // Emits the moves of a plane path from the current position; the other axes stay. Its
  // threads are interpolated at `thread_rpm` when > 0 (G92.1), turning the spindle the
  // negative way with left_hand_thread_.
  void emit_plane_path(const path::PlanePath& moves, const std::array<int, 2>& axes, double feed,
                       double thread_rpm = 0.0);
  // A cycle's alarm; an error of a contour element names the contour block's line.
  bool fail_path(const path::PathError& e, int column);

  // ---- the P..Q contour of G70-G73 (program_run_contour.cpp)
  using ContourMode = state::ContourMode;
  struct BlockContext {  // the executing block's state, kept while the contour's blocks run
    const parse::Line* line = nullptr;
    const std::string* file = nullptr;
    std::vector<BlockWord> words;
    std::size_t out_start = 0;
    bool barrier = false;
    bool moved = false;
    bool exact_stop = false;
    bool motion_code = false;
  };
  BlockContext save_block() const;
  void restore_block(BlockContext&& b);
  // P and Q of the cycle block: the line indices of N(P) and N(Q) in the running program.
  bool find_contour(const char* code, int& first, int& last, int column);
  bool run_contour(int first, int last, ContourMode mode, int column);
  bool run_finishing_cycle(int column);
  // The contour's moves in the plane from the current position, which is kept; type2 when its
  // first block gives both plane axes (gsk A.6.30 "type selection").
  bool capture_contour(const char* code, const std::array<int, 2>& axes, path::PlanePath& contour,
                       bool& type2, int column);
  bool contour_forbids(const char* what, int column);

  // ---- canned cycles G71-G76 and the hole cycles (program_run_cycles.cpp)
  bool require_turning_plane(const char* code, std::array<int, 2>& axes, int column);
  // G74-G76: the plane axes and the block's end point; second_block when it gives one.
  bool cycle_end_point(const char* code, std::array<int, 2>& axes, AxisVector& target,
                       bool& second_block, int column);
  // A cycle amount: mm with a decimal point, least increments without one (FANUC/GSK rule for
  // the P/Q/R amounts of G71-G76, gsk A.6.31-A.6.32).
  double cycle_amount(const BlockWord& w) const;
  bool run_rough_cycle(GFunction f, int column);   // G71, G72
  bool run_pattern_cycle(int column);              // G73
  bool run_groove_cycle(GFunction f, int column);  // G74, G75
  bool run_multiple_thread(int column);            // G76
  bool run_extended_thread(int column);            // GSK G78
  // G76/G78 P mmrraa of the first block: its three fields (false after an alarm).
  bool packed_thread_word(const char* code, BlockWord& p, std::array<int, 3>& fields);
  // G76/G78's second block: R(i) the taper, P(k) the height, Q(d) the first depth, F/I the lead.
  bool thread_second_block(cycles::MultipleThread& t, int column);
  bool emit_multiple_thread(const cycles::MultipleThread& t, const std::array<int, 2>& axes,
                            int column);
  // Emits a contour cycle's moves; execution goes on after N(Q) when the contour follows.
  bool run_contour_cycle(const path::PlanePath& moves, const std::array<int, 2>& axes, int first,
                         int last);
  // Hole cycles: whether this block drills (a group 10 code, or the modal cycle and positioning
  // words), the words of such a block, and the holes.
  bool hole_cycle_block(bool group10_in_block, bool motion_code_in_block) const;
  bool take_hole_words(int column);
  // The plane's axes and the drilling axis: the lathe's Z (X for the side cycles), the mill's
  // axis normal to the plane.
  bool hole_axes(std::array<int, 2>& plane, int& drill, int column);
  bool run_hole_cycle(int column);

  // ---- output and alarms
  Command& emit(Op op);
  // Moves the executed block's commands through the look-ahead (corners, nose compensation)
  // and the polar or cylindrical interpolation.
  void release_block();
  void release_through_lookahead();
  bool fail(int number, std::string text, int column);
  void warn(std::string text, int column);  // the block goes on; Interpreter::take_warnings
  bool fail_macro(const macro::MacroAlarm& a);
  BlockWord* word(char letter);
  BlockWord* word(char a, char b);
  BlockWord* comma_word(char letter);  // ,C ,R ,A
  void index_word(std::size_t k);      // words_[k] was added
  void index_words();                  // words_ was replaced
  int count_words(char letter) const;
  // A word's value in the program's unit, a literal without a point counted in increments
  // (`decimal_point: increment`) and a variable's value cut to the increment; `length`: the
  // length increment of G20/G21, else the angle and time increment.
  double scaled(const BlockWord& w, bool length) const;
  double length_increment() const;                              // in the program's unit (mm, inch)
  double scaled_axis_word(int axis, const BlockWord& w) const;  // length or degrees by the axis
  double length_of(const BlockWord& w) const;  // a length word in mm (inch converted)

  InterpreterConfig config_;
  const InterpreterEnvironment* environment_;
  InterpreterEnvironment default_environment_;
  macro::VariableStore vars_;
  macro::MathConstantsProvider constants_;

  // Programs: those of the started file, then the directory (loaded once per run).
  std::vector<std::unique_ptr<parse::ParsedProgram>> file_programs_;
  std::map<int, std::unique_ptr<parse::ParsedProgram>> directory_programs_;
  std::shared_ptr<program::ProgramStore> store_;  // config_'s, or made when first asked for
  std::vector<Frame> frames_;
  int macro_depth_ = 0;
  int main_number_ = 0;

  // Output
  std::vector<Command> out_;    // commands of the block being executed
  std::vector<Command> ready_;  // commands the look-ahead released; ready_head_ is the next
  std::size_t ready_head_ = 0;
  BlockLookahead lookahead_;
  std::uint64_t sequence_ = 0;
  bool started_ = false;
  bool called_ = false;  // started by G144: M99 in the main program ends it
  bool mdi_ = false;     // MDI blocks: their end and M99 end them
  bool ended_ = false;
  std::optional<ProgramAlarm> alarm_;
  std::vector<ProgramAlarm> warnings_;
  std::size_t warning_count_ = 0;  // of the run: the first kMaxWarnings are kept
  bool alarm_reported_ = false;

  // The block being executed.
  const parse::Line* line_ = nullptr;
  const std::string* file_ = nullptr;
  std::vector<BlockWord> words_;
  // Where in words_ the first one-letter word of each letter A-Z is, and the first comma word
  // (,A ,C ,R), as index + 1 (0: none): word() and comma_word() look there rather than scan the
  // block, which they do several times per block. Kept by index_word() and index_words().
  std::array<std::uint32_t, 26> first_letter_word_{};
  std::array<std::uint32_t, 26> first_comma_word_{};
  std::uint32_t two_letter_words_ = 0;  // UX, PS, SP ...: word(a, b) scans only when some are
  std::size_t block_out_start_ = 0;
  bool block_barrier_ = false;
  bool block_moved_ = false;
  bool block_exact_stop_ = false;
  bool block_motion_code_ = false;  // the block has a group 01 code

  // Modal state
  state::ModalState modal_;
  ModalCall modal_call_;
  state::ContourCapture contour_;  // the P..Q contour of G70-G73
  // The modal amounts of the cycles' first blocks (G71 U R, G73 U W R, G74 R, G76 P Q R).
  CycleDefaults cycle_memory_;
  // GSK G78's first block (gsk A.6.33), kept for the blocks that follow: m (constant-distance
  // infeed), r (entry: 0 centre, 1 left, 2 right, 3 alternating), a, Q, R, D, L and J/K (the
  // run-out; < 0: param №19).
  struct ExtendedThread {
    bool constant_depth = false;
    int entry = 0;
    int angle = 60;
    double min_depth = 0.1;
    double allowance = 0.0;
    int finish_passes = 1;
    int starts = 1;
    double runout_rise = -1.0;
    double runout_length = -1.0;
    double screw_in = 0.0;  // E, radius
  };
  ExtendedThread extended_thread_;
  // The modal hole cycle (group 10): its code and the amounts later blocks keep.
  state::HoleMode hole_;
  Command::Compensation compensation_ = Command::Compensation::off;  // G40/G41/G42
  int idle_blocks_ = 0;  // blocks without a move in a row under compensation
  // The moves of a cycle are not compensated again: G71-G73 rough the compensated contour,
  // G74-G76 and the hole cycles suspend the compensation (gsk A.6.22 rule 5).
  bool cycle_output_ = false;
  Op last_op_ = Op::end;
  // The corner the current block asks for after its move, and the modal corner feed E.
  Command::Corner corner_kind_ = Command::Corner::none;
  double corner_size_ = 0.0;
  double corner_feed_ = 0.0;
  // An angle-only G01 (`G01 ,A135`): its start and angle wait for the next block's end point.
  struct AngleStart {
    bool active = false;
    AxisVector from{};
    double degrees = 0.0;
    int line = 0;
    double feed = 0.0;
    int idle_blocks = 0;
  };
  AngleStart angle_start_;         // the last command emitted: a thread after a thread continues it
  double thread_lead_ = 0.0;       // the last thread lead (mm/rev): G32 blocks may omit F
  bool left_hand_thread_ = false;  // the last lead was a negative F of G92.1/G32.1 (GSK)
  // The modal single cycle (G90/G92/G94): its end point (machine), taper and lead, which the
  // blocks that follow without the G code keep unless they give new ones.
  AxisVector cycle_end_{};
  double cycle_taper_ = 0.0;
  bool cycle_repair_ = false;  // GSK G92/G92.1 P1: the modal thread cycle repairs (gsk A.6.41)

  // Spindles of this channel (1-9), the reference spindle (SP) and G96 data.
  state::SpindleState spindles_;

  // The axes programmed as a diameter now: param 0001.1 (AxisConfig::diameter) until G10.9
  // switches one, again at the program's end (spec L3959-4023).
  std::array<bool, kMaxChannelAxes> diameter_{};

  // G22: the limits stored (the last G22's, kept by G23) and whether the check is on.
  limits::StrokeZone stroke_zone_;
  bool stroke_on_ = false;
  // The machine position after the last move released (ready_), where the next one starts.
  AxisVector released_at_{};
  // G98.1 / G99.1: Q (revolutions of feed between breaks) and P (the break) while on, and the
  // revolutions of feed since the last break.
  struct ChipBreaking {
    bool active = false;
    double every = 0.0;
    double brk = 0.0;
  };
  ChipBreaking chip_;
  double chip_revs_ = 0.0;
  // G41.1 (+1) / G42.1 (-1) / G40.1 (0), and the channel axis it turns (-1: none configured).
  int normal_side_ = 0;
  int normal_axis_ = -1;
  // The turning of the released path, and whether G40.1 came while the look-ahead held moves of
  // the control: until they leave, machine_ does not hold the axis's angle.
  NormalDirection normal_;
  bool normal_pending_ = false;
  // G81.1: the axes that oscillate as the blocks run, and as the released commands leave
  // (the look-ahead may still hold moves from before G81.1), each held at its machine position
  // of then.
  std::array<bool, kMaxChannelAxes> oscillating_{};
  std::array<bool, kMaxChannelAxes> released_oscillating_{};
  AxisVector oscillation_hold_{};
  AxisVector block_start_{};  // machine_ when the executing block began (its moves start there)

  // The tool and offset numbers selected, and the offset table.
  state::ToolTable tools_;

  // Coordinates (physical, per channel axis). machine_ is the position in the frame: the
  // programmed point plus the offsets, before the G68.1 rotation and the G51.1 mirror, which
  // frame_ applies to every command on its way out (identity when neither is active).
  AxisVector machine_{};
  // G31: the skip position as #5061.. read it (workpiece, programmed units), and the variable
  // of the last G31's R (0: none), told whether the signal came.
  AxisVector skip_position_{};
  bool skip_known_ = false;
  std::int64_t skip_flag_variable_ = 0;
  // G31.8: the first variable of the positions (P), that of the count (R, 0: none) and the axis
  // whose positions they are.
  std::int64_t multi_skip_first_ = 0;
  std::int64_t multi_skip_count_variable_ = 0;
  int multi_skip_axis_ = 0;
  // What #P.. held before the dry run's positions went in (multi_skip_dry_ of them): the channel's
  // result gives back those it did not latch.
  std::array<macro::MacroValue, kMaxMultiSkipSignals> multi_skip_before_{};
  std::size_t multi_skip_dry_ = 0;
  int multi_skip_column_ = 0;
  // G10 L14 P6: per channel axis, the load ratio G31 P98/P99 skip at (percent of the rated
  // torque; 0: param 5511's).
  AxisVector load_ratio_{};
  // G10 L14 P2-P5: the axes each load timer (2-5) counts for (bit i: channel axis i), which
  // format ② (P20-P51) may read.
  std::array<std::uint32_t, 4> load_timer_axes_{};
  std::int64_t load_timer_variable_ = 0;  // the R of the last G10 L14 P20-P51
  // G10 L14 P11: per channel axis, the motor speed limit of torque mode, rpm (0: param 5521's).
  AxisVector torque_mode_speed_{};
  // G10 L14 P7 ([0], drilling) and P8 ([1], tapping): the loads watched in the cycles'
  // in-feeds (bit i of axes: channel axis i at loads[i] %), J and the counting variable R.
  struct OverloadWatch {
    std::uint32_t axes = 0;
    AxisVector loads{};
    double filter_s = 0.0;
    std::int64_t variable = 0;
  };
  std::array<OverloadWatch, 2> overload_watch_{};
  std::uint64_t overload_blocks_ = 0;   // hole blocks watched so far (Command::overload_block)
  std::uint64_t overload_block_ = 0;    // the hole block executing now, when watched
  std::int64_t overload_variable_ = 0;  // the R of the in-feeds released last
  bool rotated_ = false;
  transform::PlaneRotation rotation_;     // physical program coordinates
  transform::AxisMirror program_mirror_;  // physical work coordinates
  transform::TransformChain frame_;
  std::size_t framed_commands_ = 0;  // out_ commands frame_ has mapped already
  // G12.1: machine_ holds the polar plane's point (plus the offsets) on the linear and rotary
  // axes; the commands leave through expand_polar() after the look-ahead.
  bool polar_ = false;
  std::array<int, 2> polar_axes_{-1, -1};  // linear, rotary
  double polar_zero_ = 0.0;                // the rotary axis's angle where the virtual axis is 0
  transform::PolarPoint polar_at_;         // the machine's radius and angle now
  AxisVector polar_from_{};                // where the next expanded move starts (as machine_)
  // G16 (format 2): the polar plane's point is programmed as radius and angle; the last one
  // programmed so (a negative radius and the turns stay as written), none after other moves.
  bool polar_coords_ = false;
  std::optional<std::array<double, 2>> polar_command_;
  // G07.1: machine_ holds the rotary axis as the length around the cylinder.
  bool cylindrical_ = false;
  int cylinder_axis_ = -1;
  double cylinder_radius_ = 0.0;
  AxisVector cylinder_from_{};  // where the next expanded move starts (as machine_)
  // Inclined-axis control (params 5680.1, 5690-5692): the last link from the Cartesian machine
  // (machine_ through frame_, which everything else works in) to the inclined machine axes;
  // the identity when off. released_at_ and what the channel sees (machine(), set_machine())
  // are inclined.
  transform::TransformChain inclined_;
  std::array<int, 2> inclined_axes_{-1, -1};  // inclined, orthogonal (channel axes)
  state::CoordinateSystems coordinates_;      // work offsets, G52, G50 shift, the system selected
  std::array<bool, kMaxChannelAxes> released_{};  // G140 without G142/G141 since
  // The intermediate point of the last G28/G30 (machine), per axis it named: G29 goes back
  // through it.
  AxisVector reference_via_{};
  std::array<bool, kMaxChannelAxes> reference_via_given_{};
  // M92 loops: passes left per (call depth, M92 line); -1 = endless.
  std::map<std::pair<std::size_t, const parse::Line*>, std::int64_t> loop_counters_;

  double timer_ms_base_ = 0.0;
  double timer_hours_base_ = 0.0;
  double parts_done_ = 0.0;      // #3901
  double parts_required_ = 0.0;  // #3902
};

}  // namespace mcnc::interp
