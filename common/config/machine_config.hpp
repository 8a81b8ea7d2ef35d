#pragma once
// The machine file model. Loaded and validated once at start-up by load_machine_file(); every
// process of a machine reads the same file, so ids (1-based positions in the file) agree.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include "common/config/host_config.hpp"
#include "common/config/plc_config.hpp"

#include <string>
#include <vector>

namespace mcnc::config {

// Start-up error: names the YAML key path (e.g. "axes[1].node_id") and the reason.
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string key_path, const std::string& reason)
      : std::runtime_error(key_path + ": " + reason), key_path_(std::move(key_path)) {}
  [[nodiscard]] const std::string& key_path() const noexcept { return key_path_; }

 private:
  std::string key_path_;
};

// spindle: a drive in CSV that switches to CSP to position (docs/drives.md); in a channel's
// `spindles`, not its program axes.
enum class AxisType { linear, rotary, spindle };

// Parameters of the simulated drive behind an axis (mcnc-drivesim only).
// One entry of a simulated drive's object dictionary defaults (like an EDS DefaultValue).
struct DriveObjectDefault {
  int index = 0;  // 0x1000..0xFFFF
  int sub = 0;
  std::int64_t value = 0;  // numeric objects of up to 32 bits
};

struct DriveSimConfig {
  double time_constant_s = 0.004;    // position loop gain 1 / tau: following error ~ v * tau
  double max_velocity = 500.0;       // units/s, the drive's own limit
  double quick_stop_decel = 5000.0;  // units/s^2
  double units_per_rev = 10.0;       // load units per motor revolution (lead, 360 / ratio)
  double inertia = 0.0005;           // kg m^2 at the motor, load included
  double friction = 0.001;           // N m s/rad, viscous
  double torque_limit = 10.0;        // N m
  double rated_torque = 3.0;         // N m, the motor's (0x6076): 100 % load
  double velocity_bandwidth_hz = 200.0;
  // `probe`: the touch probe's input is on while the axis stands at or beyond `probe_at` on
  // the side probe_side (+1 above, -1 below), a part the stylus touches there; 0: no probe.
  int probe_side = 0;
  double probe_at = 0.0;
  // `probe.teeth: {pitch, width, count}` (G31.8): the input is on only within `count` windows
  // of `width`, the k-th from probe_at + k * pitch on that side; pitch 0: no teeth.
  double probe_pitch = 0.0;
  double probe_width = 0.0;
  int probe_count = 1;
  // `contact`: the load cannot pass `contact_at` going to the side contact_side (+1 above, -1
  // below), a part or a centre the axis presses against (G160); 0: none.
  int contact_side = 0;
  double contact_at = 0.0;
  std::vector<DriveObjectDefault> objects;  // at most 16
};

struct AxisConfig {
  std::string name;        // unique machine-wide, e.g. "X1"
  std::string middleware;  // its axis node's DDS implementation; empty: the machine's
  int id = 0;              // 1-based position in `axes`
  char address = 'X';      // program address in its channel: X, Z, Y, C, A, B
  AxisType type = AxisType::linear;
  bool diameter = false;  // programmed in diameter (X on a lathe); physical is radius
  std::string channel;    // home channel (owner at start)
  // Param 5660: the number G140/G141 name the axis by (`A14`), 0: not exchangeable.
  int exchange = 0;
  // G51.4 (params 5600, 5610): the axis may follow another axis's increments; its default
  // master (axis id, 0: none: G51.4 names it with P); and whether it follows that master from
  // power-on (5600.3 = 0: a gantry's second drive).
  bool sync_slave = false;
  int sync_master = 0;
  bool sync_at_power_on = false;
  // Param 5700.1: G81.1 may oscillate the axis.
  bool oscillation = false;
  std::string bus;                   // bus name
  int node_id = 0;                   // CANopen node id 1..127
  double counts_per_unit = 10000.0;  // drive increments per mm or degree
  double rapid_rate = 12000.0;       // units/min (G00)
  double max_feed = 6000.0;          // units/min (feed clamp)
  double acceleration = 1000.0;      // units/s^2
  double jerk = 0.0;                 // units/s^3; 0 (absent): 50 x acceleration
  double in_position = 0.0005;       // units; in-position width for exact stop
  bool has_soft_limits = false;      // soft_limits given
  double soft_limit_min = 0.0;       // units (physical: radius on a diameter axis)
  double soft_limit_max = 0.0;
  double following_error_limit = 2.0;  // units; more between command and actual: alarm
  // CANopen settings the master writes at start-up: the drive's heartbeat producer time
  // (0x1017, ms; 0: none, nothing watched), its quick stop deceleration (0x6085, units/s^2; 0:
  // the drive keeps its own), and what TPDO2 carries besides TPDO1 (0x606C, 0x60F4).
  int heartbeat_ms = 100;
  double quick_stop_deceleration = 0.0;
  bool tpdo2_velocity = false;
  bool tpdo2_following_error = false;
  bool tpdo2_torque = false;  // 0x6077, after the others
  // `touch_probe`: the drive's touch probe 1 is wired to skip input `probe_input` (G31 L/K/I,
  // param 5510; 0: none). Its objects take TPDO2 (0x60BA/0x60BB) and a word of RPDO1 and TPDO1.
  int probe_input = 0;
  // `torque_skip: true`: the drive's max torque 0x6072 is in RPDO2 and its torque 0x6077 in
  // TPDO2 (canopen::add_torque_limit), so that G160 can limit the torque and skip on it.
  bool torque_skip = false;
  // `torque_mode: true` (G10 L14 P10-P12; needs torque_skip): the drive switches to cyclic
  // synchronous torque (CST) as the owner asks, the mode and its display in RPDO1/TPDO1, the
  // target torque 0x6071 and the max motor speed 0x6080 in RPDO2 (canopen::add_torque_mode).
  bool torque_mode = false;
  // `torque_mode_speed` (param 5521): the motor speed in torque mode where no G10 L14 P11 set
  // one, rpm (0: none).
  double torque_mode_speed = 0.0;
  // `torque_scale` (param 5522): what the drive's torque objects (0x6071, 0x6072, 0x6077) count
  // as 1000 per mille, in % of the motor's rated torque: 100 for a drive that counts them of
  // its rated torque as CiA 402 says, its maximum torque's % for one that counts of that.
  double torque_scale = 100.0;
  // `skip_load` (param 5511): the load ratio G31 P98/P99 skip at where no G10 L14 P6 set one,
  // percent of the rated torque (0: none).
  double skip_load = 0.0;
  // Reference return at start-up by the drive's homing mode (CiA 402 method, home offset).
  bool has_homing = false;
  int homing_method = 0;
  double home_offset = 0.0;  // units: the position the home becomes
  DriveSimConfig drive;
  // C1 mode (Dafeng M18, GSK M14). On a spindle: the name of its C axis (empty: none). On that
  // C axis (in MachineConfig::c_axes): the spindle it drives under position control; it has no
  // node of its own and shares the spindle's id, bus and node.
  std::string c_axis;
  std::string spindle;
};

struct BusConfig {
  std::string name;           // e.g. "can0"
  std::string uri;            // "udp:239.255.42.1:42000" or "socketcan:can0"
  int bitrate = 1000000;      // bit/s
  std::string sync_producer;  // axis name whose node produces SYNC on this bus
  // Realtime: SYNC goes out this long after each cycle's start, so that every node's RPDO of
  // the cycle is on the bus before it. Absent: half the cycle.
  int sync_offset_us = -1;
};

// The look-ahead planner of a channel (docs/motion.md).
struct ChannelMotionConfig {
  int lookahead_blocks = 200;
  double path_tolerance = 0.01;    // G64: how far a blended corner leaves the corner point
  bool jerk_limited = true;        // profile: s_curve (true) or trapezoid
  bool rapid_interpolated = true;  // rapid: interpolated (straight line) or axis (each its own)
};

// A channel programs at most this many axes: its own, its exchange axes and its spindle's C.
inline constexpr std::size_t kMaxProgramAxes = 8;

struct ChannelConfig {
  std::string name;                   // "CH1"
  std::string middleware;             // its DDS implementation; empty: the machine's
  int id = 0;                         // 1-based position in `channels`
  std::vector<std::string> axes;      // axis names, in program order
  std::vector<std::string> spindles;  // spindle axis names: S1, S2, ... of the channel
  // Exchangeable axes of other channels this channel may take with G141 (the spec's virtual
  // axes): each is a slot after `axes`, programmed by the axis's address, that moves nothing
  // until the channel owns the axis.
  std::vector<std::string> exchange_axes;
  // The C axis of the channel's first spindle (c_axis), programmed while that spindle is under
  // position control: a slot after the exchange axes.
  std::vector<std::string> c_axes;
  ChannelMotionConfig motion;
  // Param 2201.3 (`feed_mode`): the channel powers on in G99, feed per revolution of its first
  // spindle; false: G98, feed per minute.
  bool feed_per_rev = false;
  // `dialect`: the interpreter's dialect by its name (config::kDialectNames), e.g. "fanuc-mill"
  // for a milling channel; the default is the Dafeng lathe.
  std::string dialect = "dafeng";
  // Polar interpolation G12.1 (params 5530/5531, `polar`): the addresses of the linear axis and
  // of the rotary axis that becomes its virtual second axis (0: none, G12.1 is an alarm), and
  // how far the tool tip may leave the programmed contour, mm.
  char polar_linear = 0;
  char polar_rotary = 0;
  double polar_tolerance = 0.001;
  // Cylindrical interpolation G07.1 (param 0016, `cylindrical_parallel`): the linear axis whose
  // place the rotary axis takes in the plane.
  char cylindrical_parallel = 'Y';
  // Normal direction control G41.1/G42.1 (params 5550/5551, `normal`): the address of the
  // rotary axis kept normal to the path (0: none, G41.1 is an alarm) and its speed between
  // blocks, degrees per minute.
  char normal_axis = 0;
  double normal_feed = 3600.0;
  // Inclined-axis control (params 5680.1, 5690-5692, `inclined`): the addresses of the inclined
  // axis and of the orthogonal axis it is compensated on (0: off), and the angle in degrees.
  char inclined_axis = 0;
  char inclined_orthogonal = 0;
  double inclined_degrees = 0.0;
  // Polygon turning G51.2 (params 5310-5312, `polygon`): the master spindle and the polygon
  // axis that follows it (axis ids: a spindle of this channel, and another spindle or one of
  // its own rotary axes; 0: none, G51.2 is an alarm), and the fastest the polygon axis may
  // turn, rpm (G51.2 that would need more is an alarm).
  int polygon_master = 0;
  int polygon_slave = 0;
  double polygon_max_rpm = 0.0;
  // Param 5300.5: G51.2 ends without waiting for the polygon axis to lock; the next cutting
  // block waits for it instead.
  bool polygon_no_wait = false;
  // Electronic cam G51.8 (params 5350/5351, `cam`): the master spindle (a spindle of this
  // channel) and the slave, one of its own axes (axis ids; 0: none, G51.8 is an alarm).
  int cam_master = 0;
  int cam_slave = 0;
  // Electronic gear box G81.4 (params 5330-5337, `egb`): the tool spindle (a spindle of this
  // channel), the work axis (one of its own rotary axes) and the axial feed axis of helical
  // gears (one of its linear axes; 0: none) (axis ids; tool 0: none, G81.4 is an alarm); the
  // time G80.4 stops the work axis in (5333), and the speed deviation (rpm of the work axis;
  // 0: not watched) that lasting longer than deviation_time is an alarm (5336/5337).
  int egb_tool = 0;
  int egb_work = 0;
  int egb_axial = 0;
  double egb_stop_time_s = 0.5;
  double egb_deviation_rpm = 0.0;
  double egb_deviation_time_s = 0.1;
  // Param 5320's bits: the work axis follows the tool spindle's commanded angle (.1 = 1,
  // synchronous) rather than its feedback (0, follow: the deviation is watched); G81.4 ends
  // without waiting for the work axis to lock, the next cutting block waiting instead (.5); a reset
  // or an emergency stop lets go of the work axis at once, stopping it within stop_time (.4 = 1),
  // rather than once the tool spindle stands (0); the work axis (.2) and the helical term (.3) turn
  // the other way.
  bool egb_synchronous = false;
  bool egb_no_wait = false;
  bool egb_reset_at_once = false;
  bool egb_reverse = false;
  bool egb_helix_reverse = false;
  // G31 without L, K or I skips on this input (param 5510; 0: such a G31 is an alarm).
  int skip_input = 0;
  // Param 5520.1: a reset puts the channel's axes in torque mode (G10 L14 P10) back in position
  // mode where they stand; false (0): they keep their torque.
  bool reset_leaves_torque_mode = false;
  // G160 without P limits the torque to this, % of the rated torque (param 5515; 0: such a
  // G160 is an alarm), and without Q skips beyond this following error (param 5516).
  double torque_skip_limit = 0.0;
  double torque_skip_deviation = 0.0;
  // G04 PS: the actual speed is reached within this many rpm (param 1057), and not reaching it
  // within this many seconds is an alarm (param 1059).
  double speed_arrival_rpm = 10.0;
  double speed_arrival_timeout_s = 10.0;
  // G10 L14 P7 (drilling) and P8 (tapping) on an overload (`overload: {drilling, tapping}`):
  // retract to R (params 5100.2 / 5200.4; else the alarm where the tool stopped), then retry
  // the in-feed (5100.3 / 5200.5) or alarm (5100.4 / 5200.6), else go on with the next block;
  // the variable that counts the overloads when the G10 gives no R (5113 / 5251; 0: none).
  struct Overload {
    bool retract = false;
    bool retry = false;
    bool alarm = false;
    int variable = 0;
  };
  Overload drill_overload;
  Overload tap_overload;

  // Every axis the channel programs, in slot order: its own axes, its exchange axes, then the
  // C axis of its spindle.
  [[nodiscard]] std::vector<std::string> program_axes() const;
};

// Param 1420: a G114.1 synchronisation group K, its master and slave spindles (axis ids). The
// channel that commands it is the master's (its G114.1 K and G113).
struct SpindleSyncGroup {
  int group = 1;  // K, 1..3
  int master = 0;
  int slave = 0;
  int channel = 0;  // the master's channel id
};

// The operator station (mcnc-hmi, docs/hmi.md); its command line overrides each.
struct HmiConfig {
  std::string listen = "127.0.0.1:8080";  // HOST:PORT
  std::string operator_token;             // empty: generated at start and printed once
  std::string viewer_token;               // empty: viewing needs no token
  std::string middleware;                 // mcnc-hmi's DDS implementation; empty: the machine's
};

struct MachineConfig {
  std::string name;
  int cycle_us = 1000;
  int deadline_cycles = 5;
  // G144 (spec dafeng §3.4 decide 1): how long a caller waits for a target still finishing its
  // earlier call (or still starting) to become free; 0: as long as it takes.
  int call_wait_timeout_ms = 10000;
  int domain = 0;  // DDS domain; MCNC_DOMAIN overrides (applied by the caller)
  // The DDS implementation of every process ("fastdds" or "cyclonedds"), unless its own entry
  // names one; empty: MCNC_MIDDLEWARE, else the built-in default (docs/decisions.md 32).
  std::string middleware;
  // A Cyclone DDS process needs the host's RouDi. false: mcnc-launch starts one when none
  // answers (and stops it at the end); true (`roudi: running`): one must already run.
  bool roudi_running = false;
  // Where M98, G65, G144 find programs by number (O<number>.nc, or any .nc file that holds
  // O<number>); relative to the machine file's directory. Empty: none.
  std::string program_dir;
  // Where the machine keeps #500-#999 between runs (relative to the machine file; created at
  // the first run's end). Empty: they start null.
  std::string retained_file;
  // The machine's DDS Security files, made by `mcnc certs` (relative to the machine file;
  // resolved by load_machine_file). Empty: the machine runs unsecured, and its launcher says so.
  std::string security_dir;
  std::vector<BusConfig> buses;
  std::vector<ChannelConfig> channels;
  std::vector<AxisConfig> axes;
  // The spindles' C axes (c_axis): not in `axes`, since no node of their own runs for them.
  std::vector<AxisConfig> c_axes;
  PlcConfig plc;  // plc.present: the machine has a PLC node
  std::vector<SpindleSyncGroup> spindle_sync;
  HmiConfig hmi;
  // The hosts the machine spans; empty: one host runs everything.
  std::vector<HostConfig> hosts;
  // The shortest cycle the hosts' link carries (machine.link_cycle_us).
  int link_cycle_us = kDefaultLinkCycleUs;

  [[nodiscard]] const AxisConfig* find_axis(const std::string& name) const noexcept;
  [[nodiscard]] const ChannelConfig* find_channel(const std::string& name) const noexcept;
  [[nodiscard]] const BusConfig* find_bus(const std::string& name) const noexcept;
  // By the ids the wire carries (1-based positions in the file, decision 1); nullptr when out
  // of range.
  [[nodiscard]] const ChannelConfig* channel_by_id(std::uint64_t id) const noexcept {
    return id >= 1 && id <= channels.size() ? &channels[id - 1] : nullptr;
  }
  [[nodiscard]] const AxisConfig* axis_by_id(std::uint64_t id) const noexcept {
    return id >= 1 && id <= axes.size() ? &axes[id - 1] : nullptr;
  }
  // The DDS implementation the machine file names for a process (a channel, an axis node, PLC,
  // HMI; anything else, the launcher and `mcnc status` among them, gets the machine's); empty
  // when it names none.
  [[nodiscard]] std::string middleware_of(const std::string& process) const;
  [[nodiscard]] double cycle_s() const noexcept { return cycle_us * 1e-6; }
  // The host that runs a process (a channel, an axis, a bus, "plc" or "hmi"); nullptr on a
  // machine of one host (no `hosts:`), and for a name no host runs.
  [[nodiscard]] const HostConfig* host_of(const std::string& process) const noexcept;
  // Cycles that take at least `ms` milliseconds (a time from the machine file as a count).
  [[nodiscard]] std::uint64_t cycles_of(int ms) const noexcept;
};

// Parse and validate. Throws ConfigError (key path + reason) on any problem: unknown key,
// missing key, wrong type, inconsistent value.
MachineConfig parse_machine_yaml(const std::string& yaml_text);
MachineConfig load_machine_file(const std::string& path);

// CAN bus load check (docs/configuration.md, "Bus load"). Worst-case bits on the wire of one
// classic CAN frame with an 11-bit identifier and `data_bytes` data bytes, bit stuffing included.
[[nodiscard]] int can_frame_bits(int data_bytes) noexcept;
// Bits per cycle on one bus: one SYNC (1 data byte), one RPDO and one TPDO (6 data bytes each)
// per axis on it, and per spindle an RPDO and a TPDO of 7 bytes and an RPDO of 4.
[[nodiscard]] int bus_bits_per_cycle(int axis_count, int spindle_count = 0) noexcept;
// One axis's PDO bits per cycle: 2 x bits(6); a homing axis's PDOs carry the mode (2 x bits(7));
// a spindle's besides its target velocity (2 x bits(7) + bits(4)).
[[nodiscard]] int axis_bits_per_cycle(const AxisConfig& axis) noexcept;
// The bytes the axis's TPDO2 carries (0: not mapped).
[[nodiscard]] int tpdo2_bytes(const AxisConfig& axis) noexcept;
// Share of the bit rate that traffic takes at the given cycle; the loader rejects a bus above
// kMaxBusLoad so that SDO, EMCY and heartbeat frames still fit.
[[nodiscard]] double bus_load(int axis_count, int bitrate, int cycle_us,
                              int spindle_count = 0) noexcept;
inline constexpr double kMaxBusLoad = 0.70;
// Channels of one machine: G04.1 participant sets travel as 64-bit masks.
inline constexpr std::size_t kMaxChannels = 64;

// Cycles of `cycle_us` that take at least `ms` milliseconds (rounded up: a time shorter than a
// cycle is one cycle, never none).
[[nodiscard]] std::uint64_t cycles_of(int ms, int cycle_us) noexcept;

}  // namespace mcnc::config
