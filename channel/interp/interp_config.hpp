#pragma once
// The parameters of one channel's interpreter: the dialect choices of docs/dialect.md, the
// channel's axes, reference points, initial offsets and the macro-call tables of spec dafeng
// §4.13. `mcnc interp --param FILE` reads them from YAML (tools/mcnc/interp_params.cpp).
#include "channel/interp/command.hpp"
#include "channel/interp/macro/variable_store.hpp"
#include "channel/interp/program/program_store.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mcnc::interp {

enum class GCodeSystem : std::uint8_t { a, b };  // param 2200.1
// Which manual decides where the dialects differ (docs/dialect.md): the Dafeng and GSK lathes,
// and the FANUC-style mill of seed 003 (gsk Part B). Named by config::kDialectNames, in order.
enum class Dialect : std::uint8_t { dafeng, gsk, fanuc_mill };
// Numbers without a decimal point: whole units (calculator type, spec D1) or least increments.
enum class DecimalPoint : std::uint8_t { calculator, increment };

// G31.8: the most signals one block stores (its Q; without Q, as many; decision 93).
inline constexpr int kMaxMultiSkipSignals = 100;
inline constexpr int kMaxToolOffsets = 64;                     // offset numbers 1-64 (spec L3626)
inline constexpr int kExtendedWorkSystems = 99;                // G54.1 P1-P99
inline constexpr int kWorkSystems = 6 + kExtendedWorkSystems;  // G54-G59, then P1-P99
inline constexpr int kReferencePoints = 4;                     // G28 (1), G30 P2-P4
inline constexpr int kSpindlesUnknown = -1;                    // InterpreterConfig::spindles

struct AxisConfig {
  char name = 'X';
  bool diameter = false;  // X programmed as a diameter (param 0001.1)
  bool rotary = false;    // degrees (param 0001.2)
  double start = 0.0;     // machine position when the program starts (physical)
  std::array<double, kReferencePoints> reference{};  // machine positions (physical)
  int exchange = 0;         // param 5660: the number of G140/G141 `αn` (0: not exchangeable)
  int id = 0;               // system axis number (G51.4 P and Q)
  bool may_follow = false;  // param 5600.1: G51.4 may make it a slave
  // A spindle under position control (C1 mode: Dafeng M18, GSK M14): that spindle's number in
  // the channel (1-9); it moves only while the spindle is under position control. 0: an axis.
  int spindle = 0;
  // G60 (the mill's single-direction positioning, FANUC param 5440): how far before its end
  // point the axis turns to come in; its sign is the direction of that last move (+: from
  // below). 0: G60 moves the axis as G00 does.
  double approach = 0.0;
  // The stored stroke check 2's limits that G22 without words takes (Dafeng params 0512 and
  // 0513, GSK №100 and №101): machine positions (physical); infinite: no limit.
  double stroke_minus = -std::numeric_limits<double>::infinity();
  double stroke_plus = std::numeric_limits<double>::infinity();
  // G31: the skip input its drive's touch probe is wired to (0: none).
  int probe_input = 0;
  // G160: its drive takes a torque limit and reports its torque (torque_skip).
  bool torque_skip = false;
  // Param 5511: the load ratio G31 P98/P99 skip at on this axis, percent of the rated torque,
  // where no G10 L14 P6 set one (0: none, the axis is not watched).
  double skip_load = 0.0;
  // Param 5521: the motor speed limit in torque mode (G10 L14 P10) where no P11 set one, rpm (0:
  // none; then P10 needs a P11 first).
  double torque_mode_speed = 0.0;
  // Its drive switches to torque mode (torque_mode of the machine file; the channel refuses G10
  // L14 P10-P12 naming an axis without it).
  bool torque_mode = false;
  // Param 5700.1: G81.1 may oscillate it.
  bool oscillation = false;
};

// Tool offset values as programmed: X as a diameter on a diameter axis.
struct ToolOffsetValues {
  double x = 0.0;
  double z = 0.0;
  double y = 0.0;
  double radius = 0.0;
  int tip = 0;
};

struct MacroCallTables {
  int t_program = 0;  // 9000.1 / 9010: T calls O<t_program> like M98, #149 = T value
  // Individual G-code macro calls (9020-9033): code x10 (G120 -> 1200), program.
  std::vector<std::pair<int, int>> g_macro;
  int g_range_count = 0, g_range_program = 0, g_range_first = 0;  // 9034-9036
  std::vector<std::pair<int, int>> m_subprogram;                  // 9040-9053 (like M98)
  int m_sub_range_count = 0, m_sub_range_program = 0, m_sub_range_first = 0;  // 9054-9056
  std::vector<std::pair<int, int>> m_macro;  // 9060-9073 (like G65)
  int m_macro_range_count = 0, m_macro_range_program = 0, m_macro_range_first = 0;  // 9074-9076
};

// The parameters the canned cycles take when their first block is not programmed (spec dafeng
// §2.5: params 5030-5036, 5110-5111, 5130-5136, 5200-5211). Lengths physical mm (radius).
// What a drilling (G10 L14 P7) or tapping (P8) overload does (decision 162): params
// 5100.2/5200.4 retract (else the cycle stops where it stands, with an alarm), 5100.3/5200.5
// retry the in-feed after the retract, 5100.4/5200.6 alarm after it (else the block ends
// there and the program goes on); 5113/5251 the variable that counts the overloads when the
// G10 gives no R (0: none).
struct OverloadParams {
  bool retract = false;
  bool retry = false;
  bool alarm = false;
  int variable = 0;
};

struct CycleDefaults {
  double rough_depth = 1.0;                  // G71 U(d) / G72 W(d), param 5130
  double rough_retract = 0.5;                // R(e), param 5131
  bool rough_retract_along_contour = false;  // J1, param 5120.3
  double pattern_relief_x = 0.0;             // G73 U(i) (radius), W(k)
  double pattern_relief_z = 0.0;
  int pattern_passes = 1;           // G73 R(d)
  double groove_retract = 0.5;      // G74/G75 R(e), param 5136
  int thread_finish_passes = 1;     // G76 m, param 5032
  int thread_chamfer = 10;          // G76 r in 0.1 leads, param 5033
  int thread_angle = 60;            // G76 a, degrees, param 5034
  double thread_min_depth = 0.1;    // G76 Q(dmin), param 5030
  double thread_allowance = 0.0;    // G76 R(d), param 5031
  bool thread_alternating = false;  // param 5035 = 1: alternating flanks
  double thread_chip_break = 0.0;   // Dafeng G76 PQ, mm of thread between breaks (0: none)
  bool drill_high_speed = true;     // param 5100.1: G83 = G83.5 (true) or G83.6
  double drill_retract = 0.5;       // high-speed back-off r, param 5110
  double drill_clearance = 0.5;     // deep-hole clearance c, param 5111
  double drill_full_retract = 0.0;  // G83.7: depth between full retracts (0: every peck)
  bool tap_high_speed = true;       // param 5200.1: G84 Q = G84.5 (true) or G84.6
  double tap_retract = 0.5;         // param 5211
  // The mill's G76/G87 shift off the wall (FANUC param 5101 RD1/RD2): 0 along the plane's
  // first axis (G17: +X), 1 its negative, 2 along the second axis (+Y), 3 its negative.
  int bore_shift_direction = 0;
  OverloadParams drill_overload;  // params 5100.2-5100.4, 5113
  OverloadParams tap_overload;    // params 5200.4-5200.6, 5251
};

struct InterpreterConfig {
  GCodeSystem system = GCodeSystem::a;
  Dialect dialect = Dialect::dafeng;
  int channel = 1;
  // Spindles the channel drives (S1 first); their commands run, not alarm. A higher spindle
  // number of this channel (S_ P, Sn=, M1xx..., SP) is an alarm. kSpindlesUnknown (`mcnc interp`
  // without `spindles`): every spindle 1-9 is taken.
  int spindles = kSpindlesUnknown;
  int channel_count = 0;  // channels of the machine (G04.1 Q must name them); 0: not checked
  bool plc = false;       // a PLC node runs M codes and T codes (else they are not executable)
  // G04 I: the input ports of the PLC's inputs (`port` in plc.signals); others are an alarm.
  std::vector<int> input_ports{};
  // G31 P1-P8: the PLC has an input for skip signal P (G0014.(P-1), `skip` in plc.signals);
  // others are an alarm.
  std::array<bool, 8> skip_signals{};
  std::vector<AxisConfig> axes{AxisConfig{'X', true}, AxisConfig{'Z', false}};
  DecimalPoint decimal_point = DecimalPoint::calculator;
  double least_increment = 0.001;                   // mm (param 0013)
  FeedMode power_on_feed_mode = FeedMode::per_min;  // param 2201.3
  bool arc_check = true;                            // param 2203.1
  double arc_tolerance = 0.01;                      // mm, param 2210
  bool dwell_in_revs_with_g99 = false;
  // GSK thread repair, G92 P1 / G92.1 P1 (gsk A.6.41): status param №174.4 switches it on
  // (off: P1 is ignored). What the "record thread repair position" soft key of the position
  // page recorded, with the tool tip in the groove: Z in the work coordinates as the absolute
  // page shows it (mm) and the spindle's angle then (degrees); not recorded: P1 is an alarm.
  bool thread_repair = false;
  bool thread_repair_recorded = false;
  double thread_repair_z = 0.0;
  double thread_repair_degrees = 0.0;
  // G92 chamfer-out without J/K, in leads along Z and X at 45 degrees (Dafeng param 5012,
  // GSK №19); 0: the thread runs to the end point and the tool leaves at rapid.
  double thread_chamfer_leads = 0.0;
  CycleDefaults cycles;
  // GSK L (chamfer): the chamfer's own length (type I, status param 181.0 = 1) instead of the
  // distance from the corner (type II, as Dafeng ,C).
  bool chamfer_is_length = false;
  // G22: the inside of its limits is forbidden (FANUC's default, GSK №172.2 = 0), or the
  // outside (the limits as travel limits).
  bool stroke_inside_forbidden = true;
  // Blocks in a row without a move that G41/G42 tolerates (0: the dialect's, Dafeng 4, GSK 7).
  int compensation_idle_blocks = 0;
  // Polar interpolation G12.1 (params 5530/5531): the linear axis (the polar plane's first) and
  // the rotary axis that becomes its virtual second axis, by name (0: none); the largest
  // distance of the tool tip from the programmed contour, mm.
  char polar_linear = 0;
  char polar_rotary = 0;
  double polar_tolerance = 0.001;
  // Cylindrical interpolation G07.1 (param 0016): the linear axis the rotary axis is parallel
  // to, whose place it takes in the plane (the spec's example: A parallel to Y, G19 = A-Z). Its
  // arcs become chords within polar_tolerance.
  char cylindrical_parallel = 'Y';
  // G41.1/G42.1 normal direction control: the rotary axis kept normal to the path (param 5550;
  // 0: none, the codes are an alarm) and the speed it turns at between blocks (param 5551,
  // degrees per minute).
  char normal_axis = 0;
  double normal_feed = 3600.0;
  // G31 without L, K or I skips on this input going on (param 5510; 0: such a G31 is alarm
  // 1157).
  int skip_input = 0;
  // G160 without P / Q: the torque limit in percent of the rated torque (param 5515; 0: such a
  // G160 is alarm 1152) and the following error it skips beyond, mm (param 5516).
  double torque_skip_percent = 0.0;
  double torque_skip_deviation = 0.0;
  // Inclined-axis control (spec dafeng §2.9, L4653-4767): param 5680.1 on when both axes are
  // named; 5691 the inclined axis, 5692 the orthogonal axis it is compensated on, 5690 the angle
  // in degrees (|angle| < 90). The program works in the Cartesian coordinates; every move leaves
  // in the machine's inclined ones.
  char inclined_axis = 0;
  char inclined_orthogonal = 0;
  double inclined_degrees = 0.0;
  std::array<bool, 10> block_skip{};  // switch of `/` (level 1) .. `/9`
  int max_tool = 99;                  // param 1511
  int max_subprogram_nesting = 16;    // M98 (spec L6335)
  int max_macro_nesting = 5;          // G65/G66 and macro-type calls (spec L7387)
  // Macro statements one pull may evaluate without yielding a command: an endless loop
  // without motion becomes an alarm instead of a hang.
  std::uint64_t statement_limit = 100'000'000;
  MacroCallTables calls;
  macro::MacroDialect macro;  // locals, commons, vacant ordering; `channel` is set from above
  std::string retained_file;  // #500-#999 are loaded from and saved to it ("" = not kept)
  // The machine-wide #500-#999 and #20000-#20999 this channel shares with the others, and
  // where its writes to them go (VariableStore::share); not owned, null: the interpreter's own.
  macro::VariableStore* shared_variables = nullptr;
  macro::SharedWriteSink* shared_sink = nullptr;
  std::filesystem::path program_dir;  // searched by O number after the programs of the file
  // The index of program_dir, kept across the interpreters of one thread (the channel's runs,
  // or its program checks: each has its own); null: each interpreter keeps one of its own.
  std::shared_ptr<program::ProgramStore> program_store;

  // Initial tables (what G10 writes).
  std::array<ToolOffsetValues, kMaxToolOffsets + 1> tool_geometry{};  // [0] unused
  std::array<ToolOffsetValues, kMaxToolOffsets + 1> tool_wear{};
  std::vector<std::array<double, kMaxChannelAxes>> work_offsets =
      std::vector<std::array<double, kMaxChannelAxes>>(kWorkSystems + 1);  // [0] = EXT
};

}  // namespace mcnc::interp
