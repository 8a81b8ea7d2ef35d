#include "common/config/machine_config.hpp"

#include "common/config/dialect_names.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

#include "common/config/yaml_reader.hpp"

namespace mcnc::config {

namespace {

using detail::YamlMap;
using detail::YamlValue;

// Names travel in logs, the trace and on the command line ("--program CH1=FILE"), so they stay
// short and free of separators.
constexpr std::size_t kMaxNameLength = 31;
// Linux IFNAMSIZ is 16 including the terminating NUL.
constexpr std::size_t kMaxIfnameLength = 15;
// kMaxBusLoad as a whole percentage, for an exact integer comparison.
constexpr long long kMaxBusLoadPercent = 70;
static_assert(kMaxBusLoad == kMaxBusLoadPercent / 100.0);

std::string read_name(const YamlValue& value) {
  std::string name = value.string();
  if (name.empty() || name.size() > kMaxNameLength) {
    value.fail("a name must have 1 to " + std::to_string(kMaxNameLength) + " characters");
  }
  for (char c : name) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) {
      value.fail("name '" + name + "' may only hold letters, digits, '_' and '-'");
    }
  }
  return name;
}

int read_int(const YamlValue& value, int min, int max) {
  return static_cast<int>(value.integer(min, max));
}

void read_optional_int(const YamlMap& map, std::string_view key, int min, int max, int& out) {
  if (auto value = map.optional(key)) {
    out = read_int(*value, min, max);
  }
}

void read_optional_positive(const YamlMap& map, std::string_view key, double& out) {
  if (auto value = map.optional(key)) {
    out = value->positive_number();
  }
}

// Strict dotted quad: four decimal octets 0..255.
bool parse_ipv4(std::string_view text, unsigned (&octets)[4]) {
  for (int i = 0; i < 4; ++i) {
    const auto dot = text.find('.');
    const std::string_view part = i < 3 ? text.substr(0, dot) : text;
    if ((i < 3 && dot == std::string_view::npos) || part.empty() || part.size() > 3) {
      return false;
    }
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (ec != std::errc() || end != part.data() + part.size() || value > 255) {
      return false;
    }
    octets[i] = value;
    if (i < 3) {
      text.remove_prefix(dot + 1);
    }
  }
  return true;
}

void check_uri(const YamlValue& value, const std::string& uri) {
  constexpr std::string_view kUdp = "udp:";
  constexpr std::string_view kSocketcan = "socketcan:";
  const std::string_view text = uri;
  if (text.starts_with(kUdp)) {
    const std::string_view rest = text.substr(kUdp.size());
    const auto colon = rest.rfind(':');
    if (colon == std::string_view::npos) {
      value.fail("a udp bus is written udp:GROUP:PORT, got '" + uri + "'");
    }
    unsigned octets[4] = {};
    if (!parse_ipv4(rest.substr(0, colon), octets)) {
      value.fail("'" + std::string(rest.substr(0, colon)) + "' is not an IPv4 address");
    }
    // 224.0.0.0/4: every process of the bus joins the group, so it must be multicast.
    if (octets[0] < 224 || octets[0] > 239) {
      value.fail("group " + std::string(rest.substr(0, colon)) +
                 " is not an IPv4 multicast address (224.0.0.0 to 239.255.255.255)");
    }
    const std::string_view port_text = rest.substr(colon + 1);
    unsigned port = 0;
    const auto [end, ec] =
        std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
    if (port_text.empty() || ec != std::errc() || end != port_text.data() + port_text.size() ||
        port < 1 || port > 65535) {
      value.fail("port '" + std::string(port_text) + "' is not in 1..65535");
    }
    return;
  }
  if (text.starts_with(kSocketcan)) {
    const std::string_view ifname = text.substr(kSocketcan.size());
    if (ifname.empty() || ifname.size() > kMaxIfnameLength) {
      value.fail("a socketcan interface name has 1 to " + std::to_string(kMaxIfnameLength) +
                 " characters");
    }
    for (char c : ifname) {
      if (c == '/' || c == ':' || static_cast<unsigned char>(c) <= ' ') {
        value.fail("'" + std::string(ifname) + "' is not a valid interface name");
      }
    }
    return;
  }
  value.fail("a bus uri starts with udp: or socketcan:, got '" + uri + "'");
}

// `middleware`: the DDS implementation of a process (idl/dds_participant.hpp).
void read_optional_middleware(const YamlMap& map, std::string& out) {
  if (auto value = map.optional("middleware")) {
    out = value->string();
    if (out != "fastdds" && out != "cyclonedds") {
      value->fail("middleware must be fastdds or cyclonedds, got '" + out + "'");
    }
  }
}

void parse_machine_section(const YamlValue& value, MachineConfig& out) {
  const YamlMap map =
      value.map({"name", "cycle_us", "deadline_cycles", "domain", "program_dir", "retained_file",
                 "call_wait_timeout_ms", "middleware", "roudi", "link_cycle_us", "security_dir"});
  out.name = read_name(map.required("name"));
  read_optional_int(map, "cycle_us", 100, 100000, out.cycle_us);
  read_optional_int(map, "link_cycle_us", 100, 100000, out.link_cycle_us);
  read_optional_int(map, "deadline_cycles", 1, 1000, out.deadline_cycles);
  read_optional_int(map, "call_wait_timeout_ms", 0, 3600000, out.call_wait_timeout_ms);
  // 232 is the highest domain whose RTPS ports still fit in 16 bits.
  read_optional_int(map, "domain", 0, 232, out.domain);
  read_optional_middleware(map, out.middleware);
  if (auto roudi = map.optional("roudi")) {
    const std::string text = roudi->string();
    if (text != "start" && text != "running") {
      roudi->fail(
          "roudi must be start (mcnc-launch starts one when none runs) or running (the "
          "host runs one, as a service), got '" +
          text + "'");
    }
    out.roudi_running = text == "running";
  }
  if (auto dir = map.optional("program_dir")) {
    out.program_dir = dir->string();
    if (out.program_dir.empty()) {
      dir->fail("program_dir must name a directory");
    }
  }
  if (auto file = map.optional("retained_file")) {
    out.retained_file = file->string();
    if (out.retained_file.empty()) {
      file->fail("retained_file must name a file");
    }
  }
  if (auto dir = map.optional("security_dir")) {
    out.security_dir = dir->string();
    if (out.security_dir.empty()) {
      dir->fail("security_dir must name the directory `mcnc certs` made");
    }
  }
}

BusConfig parse_bus(const YamlValue& value) {
  const YamlMap map = value.map({"name", "uri", "bitrate", "sync_producer", "sync_offset_us"});
  BusConfig bus;
  bus.name = read_name(map.required("name"));
  const YamlValue uri = map.required("uri");
  bus.uri = uri.string();
  check_uri(uri, bus.uri);
  read_optional_int(map, "bitrate", 10000, 1000000, bus.bitrate);
  bus.sync_producer = read_name(map.required("sync_producer"));
  read_optional_int(map, "sync_offset_us", 0, 1000000, bus.sync_offset_us);
  return bus;
}

ChannelMotionConfig parse_channel_motion(const YamlValue& value) {
  const YamlMap map = value.map({"lookahead_blocks", "path_tolerance", "profile", "rapid"});
  ChannelMotionConfig motion;
  read_optional_int(map, "lookahead_blocks", 2, 100000, motion.lookahead_blocks);
  read_optional_positive(map, "path_tolerance", motion.path_tolerance);
  if (auto profile = map.optional("profile")) {
    const std::string text = profile->string();
    if (text != "s_curve" && text != "trapezoid") {
      profile->fail("profile must be s_curve or trapezoid, got '" + text + "'");
    }
    motion.jerk_limited = text == "s_curve";
  }
  if (auto rapid = map.optional("rapid")) {
    const std::string text = rapid->string();
    if (text != "interpolated" && text != "axis") {
      rapid->fail("rapid must be interpolated or axis, got '" + text + "'");
    }
    motion.rapid_interpolated = text == "interpolated";
  }
  return motion;
}

// An axis address of one of `letters` ("XYZ": linear, "ABC": rotary), as the program writes it.
char read_address(const YamlValue& value, std::string_view letters) {
  const std::string text = value.string();
  if (text.size() != 1 || letters.find(text[0]) == std::string_view::npos) {
    std::string choices;
    for (const char c : letters) {
      choices += choices.empty() ? std::string(1, c) : std::string(", ") + c;
    }
    value.fail("an axis address of " + choices + ", got '" + text + "'");
  }
  return text[0];
}

ChannelConfig parse_channel(const YamlValue& value, std::vector<YamlValue>& axis_refs,
                            std::vector<YamlValue>& spindle_refs) {
  const YamlMap map = value.map(
      {"name",      "axes",       "spindles",   "exchange_axes", "motion",
       "feed_mode", "middleware", "dialect",    "polar",         "cylindrical_parallel",
       "normal",    "inclined",   "skip_input", "torque_skip",   "speed_arrival",
       "overload",  "polygon",    "cam",        "egb",           "reset_leaves_torque_mode"});
  ChannelConfig channel;
  channel.name = read_name(map.required("name"));
  read_optional_middleware(map, channel.middleware);
  const YamlValue axes = map.required("axes");
  axis_refs = axes.list();
  if (axis_refs.empty()) {
    axes.fail("a channel needs at least one axis");
  }
  for (const YamlValue& ref : axis_refs) {
    channel.axes.push_back(read_name(ref));
  }
  if (auto spindles = map.optional("spindles")) {
    spindle_refs = spindles->list();
    for (const YamlValue& ref : spindle_refs) {
      channel.spindles.push_back(read_name(ref));
    }
  }
  if (auto exchange = map.optional("exchange_axes")) {
    for (const YamlValue& ref : exchange->list()) {
      channel.exchange_axes.push_back(read_name(ref));
    }
  }
  if (auto motion = map.optional("motion")) {
    channel.motion = parse_channel_motion(*motion);
  }
  if (auto feed_mode = map.optional("feed_mode")) {
    const std::string text = feed_mode->string();
    if (text != "per_min" && text != "per_rev") {
      feed_mode->fail("feed_mode must be per_min (G98) or per_rev (G99), got '" + text + "'");
    }
    // Feed per revolution needs a spindle to measure the revolution by.
    if (text == "per_rev" && channel.spindles.empty()) {
      feed_mode->fail(
          "feed_mode per_rev (G99 at power-on) needs a spindle in the channel's "
          "spindles");
    }
    channel.feed_per_rev = text == "per_rev";
  }
  if (auto dialect = map.optional("dialect")) {
    const std::string text = dialect->string();
    channel.dialect = std::string(canonical_dialect_name(text));
    if (channel.dialect.empty()) {
      dialect->fail("dialect must be " + dialect_choices() + ", got '" + text + "'");
    }
  }
  if (auto polar = map.optional("polar")) {
    // Which axes they are is checked with the channel's program axes (check_interpolation_axes).
    const YamlMap p = polar->map({"linear", "rotary", "tolerance"});
    channel.polar_linear = read_address(p.required("linear"), "XYZ");
    channel.polar_rotary = read_address(p.required("rotary"), "ABC");
    if (auto tolerance = p.optional("tolerance")) {
      channel.polar_tolerance = tolerance->positive_number();
      if (channel.polar_tolerance < 1e-6 || channel.polar_tolerance > 1.0) {
        tolerance->fail("tolerance must be 0.000001 to 1 mm");
      }
    }
  }
  if (auto parallel = map.optional("cylindrical_parallel")) {
    channel.cylindrical_parallel = read_address(*parallel, "XYZ");
  }
  if (auto normal = map.optional("normal")) {
    // That the channel programs the axis is checked with its program axes (check_program_axis).
    const YamlMap n = normal->map({"axis", "feed"});
    channel.normal_axis = read_address(n.required("axis"), "ABC");
    if (auto feed = n.optional("feed")) {
      channel.normal_feed = feed->positive_number();
    }
  }
  if (auto inclined = map.optional("inclined")) {
    // Both are checked with the channel's program axes (check_interpolation_axes).
    const YamlMap n = inclined->map({"axis", "orthogonal", "angle"});
    channel.inclined_axis = read_address(n.required("axis"), "XYZ");
    channel.inclined_orthogonal = read_address(n.required("orthogonal"), "XYZ");
    const YamlValue angle = n.required("angle");
    channel.inclined_degrees = angle.number();
    if (!(std::fabs(channel.inclined_degrees) < 90.0)) {
      angle.fail("angle must be more than -90 and less than 90 degrees");
    }
    if (channel.inclined_axis == channel.inclined_orthogonal) {
      n.required("orthogonal").fail("orthogonal must be another axis than axis");
    }
  }
  if (auto polygon = map.optional("polygon")) {
    // Which axes they are is checked with the machine's axes (check_polygon).
    const YamlMap p = polygon->map({"master", "slave", "max_rpm", "no_wait"});
    (void)p.required("master");
    (void)p.required("slave");
    channel.polygon_master = -1;  // named: check_polygon resolves both
    channel.polygon_slave = -1;
    if (auto max_rpm = p.optional("max_rpm")) {
      channel.polygon_max_rpm = max_rpm->positive_number();
    }
    if (auto no_wait = p.optional("no_wait")) {
      channel.polygon_no_wait = no_wait->boolean();
    }
  }
  if (auto cam = map.optional("cam")) {
    const YamlMap m = cam->map({"master", "slave"});
    (void)m.required("master");
    (void)m.required("slave");
    channel.cam_master = -1;  // named: check_cam resolves both
    channel.cam_slave = -1;
  }
  if (auto egb = map.optional("egb")) {
    const YamlMap m =
        egb->map({"tool", "work", "axial", "stop_time", "deviation_rpm", "deviation_time",
                  "synchronous", "no_wait", "reset", "reverse", "helix_reverse"});
    (void)m.required("tool");
    (void)m.required("work");
    channel.egb_tool = -1;  // named: check_egb resolves them
    channel.egb_work = -1;
    channel.egb_axial = m.optional("axial") ? -1 : 0;
    if (auto t = m.optional("stop_time")) {
      channel.egb_stop_time_s = t->positive_number();
    }
    if (auto d = m.optional("deviation_rpm")) {
      channel.egb_deviation_rpm = d->positive_number();
    }
    if (auto t = m.optional("deviation_time")) {
      channel.egb_deviation_time_s = t->positive_number();
    }
    // Param 5320's bits 1-5.
    if (auto b = m.optional("synchronous")) {
      channel.egb_synchronous = b->boolean();
    }
    if (auto b = m.optional("no_wait")) {
      channel.egb_no_wait = b->boolean();
    }
    if (auto r = m.optional("reset")) {
      const std::string text = r->string();
      if (text != "at_once" && text != "when_tool_stops") {
        r->fail("reset must be at_once or when_tool_stops (parameter 5320.4), got '" + text + "'");
      }
      channel.egb_reset_at_once = text == "at_once";
    }
    if (auto b = m.optional("reverse")) {
      channel.egb_reverse = b->boolean();
    }
    if (auto b = m.optional("helix_reverse")) {
      channel.egb_helix_reverse = b->boolean();
    }
  }
  if (auto skip = map.optional("skip_input")) {
    channel.skip_input = read_int(*skip, 1, 99);
  }
  if (auto torque = map.optional("torque_skip")) {
    // Params 5515/5516: what G160 takes without P and without Q.
    const YamlMap t = torque->map({"limit", "deviation"});
    if (auto limit = t.optional("limit")) {
      channel.torque_skip_limit = limit->number();
      if (!(channel.torque_skip_limit > 0.0 && channel.torque_skip_limit <= 1000.0)) {
        limit->fail("limit is a torque limit above 0 and up to 1000 (% of the rated torque)");
      }
    }
    if (auto deviation = t.optional("deviation")) {
      channel.torque_skip_deviation = deviation->number();
      if (!(channel.torque_skip_deviation >= 0.0)) {
        deviation->fail("deviation is a following error of 0 or more (the axis's unit)");
      }
    }
  }
  if (auto leaves = map.optional("reset_leaves_torque_mode")) {
    channel.reset_leaves_torque_mode = leaves->boolean();  // param 5520.1
  }
  if (auto arrival = map.optional("speed_arrival")) {
    const YamlMap a = arrival->map({"tolerance", "timeout"});
    read_optional_positive(a, "tolerance", channel.speed_arrival_rpm);
    read_optional_positive(a, "timeout", channel.speed_arrival_timeout_s);
  }
  if (auto overload = map.optional("overload")) {
    // Params 5100.2-5100.4 and 5113 (drilling), 5200.4-5200.6 and 5251 (tapping).
    const YamlMap o = overload->map({"drilling", "tapping"});
    const auto read = [](const YamlValue& v, ChannelConfig::Overload& out) {
      const YamlMap m = v.map({"retract", "retry", "alarm", "variable"});
      if (auto b = m.optional("retract")) {
        out.retract = b->boolean();
      }
      if (auto b = m.optional("retry")) {
        out.retry = b->boolean();
      }
      if (auto b = m.optional("alarm")) {
        out.alarm = b->boolean();
      }
      if (auto n = m.optional("variable")) {
        out.variable = read_int(*n, 1, 999);
      }
    };
    if (auto d = o.optional("drilling")) {
      read(*d, channel.drill_overload);
    }
    if (auto t = o.optional("tapping")) {
      read(*t, channel.tap_overload);
    }
  }
  return channel;
}

// A position of the simulated drive and the side it acts on: `{at, <side_key>: above|below}`;
// side +1 above, -1 below.
void read_drive_position(const YamlMap& m, const char* side_key, const std::string& what,
                         double& at, int& side) {
  at = m.required("at").number();
  const YamlValue key = m.required(side_key);
  const std::string name = key.string();
  if (name != "above" && name != "below") {
    key.fail(what + " above or below its position, got '" + name + "'");
  }
  side = name == "above" ? 1 : -1;
}

DriveSimConfig parse_drive(const YamlValue& value) {
  const YamlMap map =
      value.map({"time_constant_s", "max_velocity", "quick_stop_decel", "units_per_rev", "inertia",
                 "friction", "torque_limit", "rated_torque", "velocity_bandwidth_hz", "objects",
                 "probe", "contact"});
  DriveSimConfig drive;
  read_optional_positive(map, "time_constant_s", drive.time_constant_s);
  read_optional_positive(map, "max_velocity", drive.max_velocity);
  read_optional_positive(map, "quick_stop_decel", drive.quick_stop_decel);
  read_optional_positive(map, "units_per_rev", drive.units_per_rev);
  read_optional_positive(map, "inertia", drive.inertia);
  read_optional_positive(map, "friction", drive.friction);
  read_optional_positive(map, "torque_limit", drive.torque_limit);
  read_optional_positive(map, "rated_torque", drive.rated_torque);
  read_optional_positive(map, "velocity_bandwidth_hz", drive.velocity_bandwidth_hz);
  if (auto probe = map.optional("probe")) {
    const YamlMap p = probe->map({"at", "on", "teeth"});
    read_drive_position(p, "on", "the probe's input is on", drive.probe_at, drive.probe_side);
    if (auto teeth = p.optional("teeth")) {
      const YamlMap t = teeth->map({"pitch", "width", "count"});
      const YamlValue pitch = t.required("pitch");
      drive.probe_pitch = pitch.number();
      drive.probe_width = t.required("width").number();
      drive.probe_count = read_int(t.required("count"), 1, 10000);
      if (!(drive.probe_pitch > 0.0 && drive.probe_width > 0.0 &&
            drive.probe_width < drive.probe_pitch)) {
        pitch.fail("the teeth need 0 < width < pitch");
      }
    }
  }
  if (auto contact = map.optional("contact")) {
    read_drive_position(contact->map({"at", "blocks"}), "blocks", "the contact blocks the load",
                        drive.contact_at, drive.contact_side);
  }
  if (auto objects = map.optional("objects")) {
    const std::vector<YamlValue> list = objects->list();
    if (list.size() > 16) {
      objects->fail("at most 16 objects");
    }
    for (const YamlValue& entry : list) {
      const YamlMap o = entry.map({"index", "sub", "value"});
      DriveObjectDefault d;
      const YamlValue index = o.required("index");
      const std::string text = index.string();
      char* end = nullptr;
      const long parsed = text.rfind("0x", 0) == 0 && text.size() == 6
                              ? std::strtol(text.c_str() + 2, &end, 16)
                              : -1;
      if (parsed < 0x1000 || end == nullptr || *end != '\0') {
        index.fail("index must be 0x1000..0xFFFF in hex (0x6085), got '" + text + "'");
      }
      d.index = static_cast<int>(parsed);
      if (auto sub = o.optional("sub")) {
        d.sub = read_int(*sub, 0, 255);
      }
      d.value = o.required("value").integer(-2147483648LL, 4294967295LL);
      drive.objects.push_back(d);
    }
  }
  return drive;
}

AxisConfig parse_axis(const YamlValue& value) {
  const YamlMap map = value.map({"name",
                                 "address",
                                 "type",
                                 "diameter",
                                 "bus",
                                 "node_id",
                                 "counts_per_unit",
                                 "rapid_rate",
                                 "max_feed",
                                 "acceleration",
                                 "jerk",
                                 "in_position",
                                 "drive",
                                 "soft_limits",
                                 "following_error_limit",
                                 "homing",
                                 "heartbeat_ms",
                                 "quick_stop_deceleration",
                                 "tpdo2",
                                 "touch_probe",
                                 "torque_skip",
                                 "torque_mode",
                                 "torque_mode_speed",
                                 "skip_load",
                                 "torque_scale",
                                 "exchange",
                                 "axis_sync",
                                 "oscillation",
                                 "c_axis",
                                 "middleware"});
  AxisConfig axis;
  axis.name = read_name(map.required("name"));
  read_optional_middleware(map, axis.middleware);

  if (auto type = map.optional("type")) {
    const std::string text = type->string();
    if (text == "linear") {
      axis.type = AxisType::linear;
    } else if (text == "rotary") {
      axis.type = AxisType::rotary;
    } else if (text == "spindle") {
      axis.type = AxisType::spindle;
    } else {
      type->fail("type must be linear, rotary or spindle, got '" + text + "'");
    }
  }

  if (axis.type == AxisType::spindle) {
    // A spindle is commanded by S and M codes, not by an address of its own.
    if (auto address = map.optional("address")) {
      address->fail("a spindle has no program address");
    }
    axis.address = 'S';
  } else {
    const YamlValue address = map.required("address");
    const std::string letter = address.string();
    if (letter.size() != 1 ||
        std::string_view("XYZABC").find(letter[0]) == std::string_view::npos) {
      address.fail("address must be one of X Y Z A B C, got '" + letter + "'");
    }
    axis.address = letter[0];
  }
  if (auto diameter = map.optional("diameter")) {
    axis.diameter = diameter->boolean();
    // Diameter programming halves a length; an angle has no diameter.
    if (axis.diameter && axis.type != AxisType::linear) {
      diameter->fail("only a linear axis can be programmed in diameter");
    }
  }
  axis.bus = read_name(map.required("bus"));
  // CANopen node ids are 1..127; 0 addresses every node in NMT commands.
  axis.node_id = read_int(map.required("node_id"), 1, 127);
  read_optional_positive(map, "counts_per_unit", axis.counts_per_unit);
  read_optional_positive(map, "rapid_rate", axis.rapid_rate);
  read_optional_positive(map, "max_feed", axis.max_feed);
  read_optional_positive(map, "acceleration", axis.acceleration);
  read_optional_positive(map, "jerk", axis.jerk);
  if (axis.jerk == 0.0) {
    axis.jerk = 50.0 * axis.acceleration;  // 20 ms to reach the acceleration
  }
  read_optional_positive(map, "in_position", axis.in_position);
  read_optional_positive(map, "following_error_limit", axis.following_error_limit);
  read_optional_int(map, "heartbeat_ms", 0, 65535, axis.heartbeat_ms);
  if (auto exchange = map.optional("exchange")) {
    if (axis.type == AxisType::spindle) {
      exchange->fail("a spindle is not exchanged by G140/G141");
    }
    read_optional_int(map, "exchange", 1, 9999, axis.exchange);
  }
  if (auto sync = map.optional("axis_sync")) {
    if (axis.type == AxisType::spindle) {
      sync->fail("a spindle follows another by G114.1 (spindle_sync), not by G51.4");
    }
    if (axis.exchange != 0) {
      // Its coupling is its node's, whichever channel would own it: kept simple, one owner.
      sync->fail("an axis that may follow another (G51.4) is not exchanged by G140/G141");
    }
    axis.sync_slave = true;
    const YamlMap s = sync->map({"master", "at_power_on"});
    if (auto at_power_on = s.optional("at_power_on")) {
      axis.sync_at_power_on = at_power_on->boolean();
    }
  }
  if (auto oscillation = map.optional("oscillation")) {
    if (axis.type == AxisType::spindle) {
      oscillation->fail("a spindle does not oscillate (G81.1)");
    }
    axis.oscillation = oscillation->boolean();
  }
  if (auto decel = map.optional("quick_stop_deceleration")) {
    axis.quick_stop_deceleration = decel->positive_number();
    // Written to 0x6085 in increments/s^2, an UNSIGNED32.
    if (axis.quick_stop_deceleration * axis.counts_per_unit > 4294967295.0) {
      decel->fail("more than 0x6085 can hold at this counts_per_unit (4294967295 increments/s^2)");
    }
  }
  if (auto tpdo2 = map.optional("tpdo2")) {
    for (const YamlValue& entry : tpdo2->list()) {
      const std::string what = entry.string();
      if (what == "velocity_actual") {
        axis.tpdo2_velocity = true;
      } else if (what == "following_error_actual") {
        axis.tpdo2_following_error = true;
      } else if (what == "torque_actual") {
        axis.tpdo2_torque = true;
      } else {
        entry.fail("tpdo2 maps velocity_actual, following_error_actual and torque_actual, got '" +
                   what + "'");
      }
    }
    if (tpdo2_bytes(axis) > 8) {
      tpdo2->fail(
          "tpdo2 holds 8 bytes: velocity_actual (4), following_error_actual (4) and "
          "torque_actual (2) do not all fit");
    }
  }
  if (auto probe = map.optional("touch_probe")) {
    const YamlMap p = probe->map({"input"});
    axis.probe_input = read_int(p.required("input"), 1, 99);
    // Its objects fill RPDO1, TPDO1 and TPDO2 of a CSP axis (canopen::add_touch_probe).
    if (axis.type == AxisType::spindle || map.optional("homing") || tpdo2_bytes(axis) > 0) {
      probe->fail(
          "a touch probe is on a linear or rotary axis without homing and without tpdo2 (its "
          "objects take those PDOs' room)");
    }
  }
  if (auto torque = map.optional("torque_skip")) {
    axis.torque_skip = torque->boolean();
    // RPDO2 takes 0x6072 and TPDO2 0x6077 (canopen::add_torque_limit).
    if (axis.torque_skip &&
        (axis.type == AxisType::spindle || axis.tpdo2_torque || tpdo2_bytes(axis) > 8)) {
      torque->fail(
          "torque_skip is on a linear or rotary axis whose tpdo2 leaves room for torque_actual "
          "(it maps 0x6077 itself)");
    }
    if (axis.torque_skip && axis.probe_input > 0) {
      torque->fail("torque_skip and touch_probe do not fit one TPDO2");
    }
  }
  if (auto mode = map.optional("torque_mode")) {
    axis.torque_mode = mode->boolean();
    // add_torque_mode puts 0x6071/0x6080 after add_torque_limit's 0x6072 in RPDO2, and the mode
    // in RPDO1/TPDO1, where a homed axis has it already.
    if (axis.torque_mode && !axis.torque_skip) {
      mode->fail(
          "torque_mode needs torque_skip: true (the drive's torque limit and its torque, whose "
          "RPDO2 takes the target torque)");
    }
    if (axis.torque_mode && map.optional("homing")) {
      mode->fail("torque_mode is on an axis without homing (both map the mode of operation)");
    }
  }
  if (auto speed = map.optional("torque_mode_speed")) {
    // Param 5521: G10 L14 P10's motor speed where no P11 set one.
    axis.torque_mode_speed = speed->number();
    if (!(axis.torque_mode_speed > 0.0 && axis.torque_mode_speed <= 100000.0)) {
      speed->fail("torque_mode_speed is a motor speed above 0 and up to 100000 (rpm)");
    }
    if (!axis.torque_mode) {
      speed->fail("torque_mode_speed needs torque_mode: true");
    }
  }
  if (auto scale = map.optional("torque_scale")) {
    // Param 5522: the servo's torque scaling (decision 164).
    axis.torque_scale = scale->number();
    if (!(axis.torque_scale >= 1.0 && axis.torque_scale <= 1000.0)) {
      scale->fail("torque_scale is 1-1000 (% of the rated torque the drive's 1000 per mille are)");
    }
    if (!axis.torque_skip) {
      scale->fail("torque_scale needs torque_skip: true (the drive's torque objects)");
    }
  }
  if (auto load = map.optional("skip_load")) {
    // Param 5511: G31 P98/P99 limit the torque to it and skip where the axis is held back.
    axis.skip_load = load->number();
    if (!(axis.skip_load > 0.0 && axis.skip_load <= 1000.0)) {
      load->fail("skip_load is a load ratio above 0 and up to 1000 (% of the rated torque)");
    }
    if (!axis.torque_skip) {
      load->fail("skip_load needs torque_skip: true (the drive's torque limit and its torque)");
    }
  }
  if (auto homing = map.optional("homing")) {
    if (axis.type == AxisType::spindle) {
      homing->fail("a spindle is not homed (its angle is set by orientation)");
    }
    const YamlMap h = homing->map({"method", "offset"});
    // CiA 402 homing methods 1..37 (what a drive supports is its own: a method it refuses is
    // an SDO abort at start-up, naming 0x6098).
    axis.homing_method = read_int(h.required("method"), 1, 37);
    if (auto offset = h.optional("offset")) {
      axis.home_offset = offset->number();
    }
    axis.has_homing = true;
  }
  if (auto limits = map.optional("soft_limits")) {
    const std::vector<YamlValue> pair = limits->list();
    if (pair.size() != 2) {
      limits->fail("soft_limits must be [min, max]");
    }
    axis.soft_limit_min = pair[0].number();
    axis.soft_limit_max = pair[1].number();
    if (!(axis.soft_limit_min < axis.soft_limit_max)) {
      limits->fail("soft_limits: min must be below max");
    }
    axis.has_soft_limits = true;
  }
  if (auto drive = map.optional("drive")) {
    axis.drive = parse_drive(*drive);
  }
  if (auto c = map.optional("c_axis")) {
    if (axis.type != AxisType::spindle) {
      c->fail("only a spindle has a C axis (its position control, C1 mode)");
    }
    axis.c_axis = read_name(
        c->map({"name", "address", "rapid_rate", "max_feed", "acceleration", "jerk", "in_position"})
            .required("name"));
  }
  return axis;
}

// A spindle's C axis: a rotary axis of the spindle's channel on the spindle's node, in degrees
// (the spindle's unit), programmed while the spindle is under position control.
AxisConfig parse_c_axis(const YamlValue& value, const AxisConfig& spindle) {
  const YamlMap map = value.map(
      {"name", "address", "rapid_rate", "max_feed", "acceleration", "jerk", "in_position"});
  AxisConfig c;
  c.name = read_name(map.required("name"));
  c.type = AxisType::rotary;
  c.address = 'C';
  if (auto address = map.optional("address")) {
    const std::string letter = address->string();
    if (letter.size() != 1 || std::string_view("ABC").find(letter[0]) == std::string_view::npos) {
      address->fail("a spindle's C axis is rotary: address A, B or C, got '" + letter + "'");
    }
    c.address = letter[0];
  }
  c.id = spindle.id;
  c.bus = spindle.bus;
  c.node_id = spindle.node_id;
  c.counts_per_unit = spindle.counts_per_unit;
  c.following_error_limit = spindle.following_error_limit;
  c.spindle = spindle.name;
  c.rapid_rate = 36000.0;  // deg/min: 100 rpm
  c.max_feed = 36000.0;
  c.acceleration = 3600.0;  // deg/s^2
  c.in_position = 0.01;     // deg
  read_optional_positive(map, "rapid_rate", c.rapid_rate);
  read_optional_positive(map, "max_feed", c.max_feed);
  read_optional_positive(map, "acceleration", c.acceleration);
  read_optional_positive(map, "jerk", c.jerk);
  if (c.jerk == 0.0) {
    c.jerk = 50.0 * c.acceleration;
  }
  read_optional_positive(map, "in_position", c.in_position);
  return c;
}

// Rejects a name already seen in the same list; `seen` maps name -> index.
void check_unique(std::map<std::string, std::size_t>& seen, const std::string& name,
                  const YamlValue& item, std::size_t index, const std::string& list,
                  const std::string& what) {
  const auto [it, inserted] = seen.emplace(name, index);
  if (!inserted) {
    item.child("name").fail("duplicate " + what + " name " + name + " (also " +
                            detail::join_index(list, it->second) + ")");
  }
}

// `name`, `name=1` (on) or `name=0` (off), of a signal of the given kind.
PlcCondition read_condition(const YamlValue& value, const PlcConfig& plc, bool output) {
  std::string text = value.string();
  bool on = true;
  if (const auto eq = text.find('='); eq != std::string::npos) {
    const std::string state = text.substr(eq + 1);
    if (state != "0" && state != "1") {
      value.fail("write a signal as NAME, NAME=1 or NAME=0, got '" + text + "'");
    }
    on = state == "1";
    text.resize(eq);
  }
  const PlcSignal* s = plc.find_signal(text);
  if (s == nullptr) {
    value.fail("unknown signal " + text + " (plc.signals)");
  }
  if (s->output != output) {
    value.fail("signal " + text + " is an " + (s->output ? "output" : "input") + "; " +
               (output ? "only outputs are set" : "only inputs are waited for or required"));
  }
  return PlcCondition{s->index, on};
}

std::vector<PlcCondition> read_conditions(const YamlMap& map, std::string_view key,
                                          const PlcConfig& plc, bool output) {
  std::vector<PlcCondition> out;
  if (auto list = map.optional(key)) {
    for (const YamlValue& v : list->list()) {
      out.push_back(read_condition(v, plc, output));
    }
  }
  return out;
}

int spindle_id(const YamlValue& value, const MachineConfig& config) {
  const std::string name = read_name(value);
  const AxisConfig* a = config.find_axis(name);
  if (a == nullptr || a->type != AxisType::spindle) {
    value.fail(name + " is not a spindle of this machine");
  }
  return a->id;
}

void parse_plc(const YamlValue& value, MachineConfig& config) {
  const YamlMap map =
      value.map({"signals", "m_codes", "spindle_start", "tool_change_ms", "middleware"});
  PlcConfig& plc = config.plc;
  plc.present = true;
  read_optional_middleware(map, plc.middleware);
  if (auto signals = map.optional("signals")) {
    const std::vector<YamlValue> list = signals->list();
    if (list.size() > kMaxPlcSignals) {
      signals->fail("at most " + std::to_string(kMaxPlcSignals) + " signals");
    }
    for (const YamlValue& v : list) {
      const YamlMap s = v.map(
          {"name", "type", "follows", "invert", "delay_ms", "initial", "port", "skip", "position"});
      PlcSignal signal;
      signal.name = read_name(s.required("name"));
      const YamlValue type = s.required("type");
      const std::string t = type.string();
      if (t != "input" && t != "output") {
        type.fail("type must be input or output, got '" + t + "'");
      }
      signal.output = t == "output";
      if (plc.find_signal(signal.name) != nullptr) {
        v.fail("signal " + signal.name + " is defined twice");
      }
      if (auto f = s.optional("follows")) {
        if (signal.output) {
          f->fail("an output does not follow anything: the PLC sets it");
        }
        signal.follows = read_name(*f);
        const PlcSignal* target = plc.find_signal(signal.follows);
        if (target == nullptr || !target->output) {
          f->fail(signal.follows + " is not an output defined before this signal");
        }
        signal.follows_index = target->index;
      }
      if (auto invert = s.optional("invert")) {
        signal.invert = invert->boolean();
      }
      read_optional_int(s, "delay_ms", 0, 600000, signal.delay_ms);
      if (auto initial = s.optional("initial")) {
        signal.initial = initial->boolean();
      }
      if (auto port = s.optional("port")) {
        if (signal.output) {
          port->fail("an output has no port: G04 I waits on inputs");
        }
        signal.port = read_int(*port, 1, 99);
        for (const PlcSignal& other : plc.signals) {
          if (other.port == signal.port) {
            port->fail("port " + std::to_string(signal.port) + " is " + other.name + "'s already");
          }
        }
      }
      if (auto skip = s.optional("skip")) {
        if (signal.output) {
          skip->fail("an output is no skip signal: G31 P skips on inputs");
        }
        signal.skip = read_int(*skip, 1, 8);
        for (const PlcSignal& other : plc.signals) {
          if (other.skip == signal.skip) {
            skip->fail("skip signal " + std::to_string(signal.skip) + " is " + other.name +
                       "'s already");
          }
        }
      }
      if (auto position = s.optional("position")) {
        if (signal.output || !signal.follows.empty()) {
          position->fail("only an input that follows no output is on at an axis's position");
        }
        const YamlMap p = position->map({"axis", "at", "on"});
        const YamlValue axis = p.required("axis");
        const AxisConfig* a = config.find_axis(axis.string());
        if (a == nullptr || a->type == AxisType::spindle) {
          axis.fail(axis.string() + " is not a linear or rotary axis of this machine");
        }
        signal.at_axis = a->id;
        signal.at = p.required("at").number();
        const YamlValue on = p.required("on");
        const std::string side = on.string();
        if (side != "above" && side != "below") {
          on.fail("the input is on above or below its position, got '" + side + "'");
        }
        signal.at_side = side == "above" ? 1 : -1;
      }
      signal.index = static_cast<int>(plc.signals.size());
      plc.signals.push_back(signal);
    }
  }
  if (auto codes = map.optional("m_codes")) {
    for (const YamlValue& v : codes->list()) {
      const YamlMap m =
          v.map({"code", "channels", "set", "wait", "requires", "spindle_stopped", "timeout_ms"});
      PlcMCode code;
      code.code = read_int(m.required("code"), 0, 9999);
      // The channel runs these itself (program flow, the spindle words, subprograms).
      // The channel runs these itself (program flow, subprograms, the spindle words, also
      // with a spindle prefix: M103, M205, M319): they never reach the PLC.
      const int unit = code.code % 100;
      const bool spindle_word = unit == 3 || unit == 4 || unit == 5 || unit == 19;
      const bool flow = code.code == 0 || code.code == 1 || code.code == 2 || code.code == 30 ||
                        code.code == 91 || code.code == 92 || code.code == 98 || code.code == 99;
      if (flow || (spindle_word && code.code < 1000)) {
        m.required("code").fail("M" + std::to_string(code.code) +
                                " is run by the channel, not by the PLC");
      }
      if (auto channels = m.optional("channels")) {
        for (const YamlValue& c : channels->list()) {
          const ChannelConfig* ch = config.find_channel(read_name(c));
          if (ch == nullptr) {
            c.fail("unknown channel " + c.string());
          }
          code.channels.push_back(ch->id);
        }
      }
      for (const PlcMCode& other : plc.m_codes) {
        bool overlap = other.code == code.code && (other.channels.empty() || code.channels.empty());
        for (int a : other.channels) {
          for (int b : code.channels) {
            overlap = overlap || (other.code == code.code && a == b);
          }
        }
        if (overlap) {
          v.fail("M" + std::to_string(code.code) + " is defined twice for a channel");
        }
      }
      code.set = read_conditions(m, "set", plc, true);
      code.wait = read_conditions(m, "wait", plc, false);
      code.requires_ = read_conditions(m, "requires", plc, false);
      if (auto s = m.optional("spindle_stopped")) {
        code.spindle_stopped = spindle_id(*s, config);
      }
      read_optional_int(m, "timeout_ms", 1, 600000, code.timeout_ms);
      plc.m_codes.push_back(code);
    }
  }
  if (auto starts = map.optional("spindle_start")) {
    for (const YamlValue& v : starts->list()) {
      const YamlMap s = v.map({"spindle", "requires"});
      PlcSpindleStart start;
      start.spindle = spindle_id(s.required("spindle"), config);
      start.requires_ = read_conditions(s, "requires", plc, false);
      plc.spindle_start.push_back(start);
    }
  }
  read_optional_int(map, "tool_change_ms", 0, 600000, plc.tool_change_ms);
}

void parse_hmi(const YamlValue& value, HmiConfig& hmi) {
  const YamlMap map = value.map({"listen", "operator_token", "viewer_token", "middleware"});
  read_optional_middleware(map, hmi.middleware);
  if (auto listen = map.optional("listen")) {
    hmi.listen = listen->string();
    const std::size_t colon = hmi.listen.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == hmi.listen.size()) {
      listen->fail("listen is HOST:PORT, e.g. 127.0.0.1:8080");
    }
  }
  // A token short enough to guess protects nothing.
  for (const char* key : {"operator_token", "viewer_token"}) {
    if (auto token = map.optional(key)) {
      std::string& field = key[0] == 'o' ? hmi.operator_token : hmi.viewer_token;
      field = token->string();
      if (field.size() < 16) {
        token->fail(std::string(key) + " needs at least 16 characters");
      }
    }
  }
  if (!hmi.viewer_token.empty() && hmi.viewer_token == hmi.operator_token) {
    map.required("viewer_token").fail("viewer_token must differ from operator_token");
  }
}

// `hosts:` (docs/configuration.md "Hosts"): every channel, axis, bus and the PLC on exactly one
// host, each axis on its bus's host; the HMI on the first host unless one names it. A machine
// whose channels command axes on other hosts runs at the link's cycle or slower: 2000 us unless
// the file says otherwise.
void parse_hosts(const YamlValue& value, MachineConfig& config, bool has_plc,
                 const std::optional<YamlValue>& cycle_value) {
  const std::vector<YamlValue> hosts = value.list();
  if (hosts.empty()) {
    value.fail("hosts: needs at least one host (without it the machine runs on one host)");
  }
  // What each name in `runs` may be.
  std::map<std::string, std::string> kinds;
  auto add_kind = [&](const std::string& name, const std::string& kind) {
    const auto [it, inserted] = kinds.emplace(name, kind);
    if (!inserted) {
      value.fail("'" + name + "' names both a " + it->second + " and a " + kind +
                 ": a machine on several hosts needs distinct names");
    }
  };
  for (const ChannelConfig& c : config.channels) {
    add_kind(c.name, "channel");
  }
  for (const AxisConfig& a : config.axes) {
    add_kind(a.name, "axis");
  }
  for (const BusConfig& b : config.buses) {
    add_kind(b.name, "bus");
  }
  if (has_plc) {
    add_kind("plc", "PLC");
  }
  add_kind("hmi", "HMI");

  std::map<std::string, std::size_t> host_index;
  std::map<std::string, std::pair<std::size_t, YamlValue>> placed;  // name -> host, where
  for (std::size_t h = 0; h < hosts.size(); ++h) {
    const YamlMap map = hosts[h].map({"name", "address", "runs"});
    HostConfig host;
    host.name = read_name(map.required("name"));
    check_unique(host_index, host.name, hosts[h], h, "hosts", "host");
    if (auto address = map.optional("address")) {
      host.address = address->string();
      if (host.address.empty() || host.address.find_first_of(" \t/") != std::string::npos) {
        address->fail("an address is an IPv4 address or a host name, got '" + host.address + "'");
      }
    }
    for (const YamlValue& entry : map.required("runs").list()) {
      const std::string name = entry.string();
      if (kinds.find(name) == kinds.end()) {
        const auto c_axis = std::find_if(config.c_axes.begin(), config.c_axes.end(),
                                         [&](const AxisConfig& a) { return a.name == name; });
        if (c_axis != config.c_axes.end()) {
          entry.fail(name + " is spindle " + c_axis->spindle +
                     "'s C axis: it runs where its spindle runs");
        }
        entry.fail("no channel, axis, bus" + std::string(has_plc ? ", plc" : "") +
                   " or hmi of this machine is called '" + name + "'");
      }
      const auto [it, inserted] = placed.emplace(name, std::make_pair(h, entry));
      if (!inserted) {
        entry.fail(kinds.at(name) + " " + name + " already runs on host " +
                   config.hosts[it->second.first].name);
      }
      host.runs.push_back(name);
    }
    config.hosts.push_back(std::move(host));
  }
  for (const auto& [name, kind] : kinds) {
    if (kind != "HMI" && placed.find(name) == placed.end()) {
      value.fail(kind + " " + name + " runs on no host");
    }
  }
  if (placed.find("hmi") == placed.end()) {
    config.hosts.front().runs.push_back("hmi");
  }
  for (const AxisConfig& a : config.axes) {
    const std::size_t axis_host = placed.at(a.name).first;
    const std::size_t bus_host = placed.at(a.bus).first;
    if (axis_host != bus_host) {
      placed.at(a.name).second.fail("axis " + a.name + " is on bus " + a.bus + ", which host " +
                                    config.hosts[bus_host].name +
                                    " runs: an axis node runs on the host its bus is wired to");
    }
  }
  // A channel that commands an axis on another host: the axis's setpoints cross the link.
  std::string crossing;
  for (const ChannelConfig& c : config.channels) {
    const std::size_t channel_host = placed.at(c.name).first;
    for (const auto* list : {&c.axes, &c.exchange_axes, &c.spindles}) {
      for (const std::string& a : *list) {
        if (crossing.empty() && placed.at(a).first != channel_host) {
          crossing = "channel " + c.name + " (host " + config.hosts[channel_host].name +
                     ") commands " + a + " on host " + config.hosts[placed.at(a).first].name;
        }
      }
    }
  }
  if (crossing.empty()) {
    return;
  }
  if (!cycle_value) {
    config.cycle_us = std::max(config.cycle_us, config.link_cycle_us);
  } else if (config.cycle_us < config.link_cycle_us) {
    cycle_value->fail(std::to_string(config.cycle_us) + " us is below the " +
                      std::to_string(config.link_cycle_us) + " us the hosts' link allows, and " +
                      crossing + " (link_cycle_us sets the link's cycle)");
  }
}

// `address` (at `where` below the channel's `value`) names an axis the channel programs (its
// axes, exchange_axes or its spindle's C axis) of `type`.
void check_program_axis(const MachineConfig& config, const ChannelConfig& channel,
                        const YamlValue& where, char address, AxisType type, const char* kind) {
  for (const std::string& name : channel.program_axes()) {
    const AxisConfig* axis = config.find_axis(name);
    if (axis->address == address) {
      if (axis->type != type) {
        where.fail("axis " + axis->name + " (address " + std::string(1, address) + ") is not " +
                   kind);
      }
      return;
    }
  }
  where.fail("channel " + channel.name + " programs no axis " + std::string(1, address) +
             " (its axes, exchange_axes and its spindle's c_axis)");
}

// A spindle of `channel` named at `ref`: its axis id.
int spindle_of_channel(const YamlValue& ref, const ChannelConfig& channel, MachineConfig& config) {
  const int id = spindle_id(ref, config);
  const std::string& name = config.axes[static_cast<std::size_t>(id - 1)].name;
  if (std::find(channel.spindles.begin(), channel.spindles.end(), name) == channel.spindles.end()) {
    ref.fail(name + " is not a spindle of channel " + channel.name);
  }
  return id;
}

// One of `channel`'s own axes named at `ref`, that a coupling (`what`) moves over what the
// channel commands it. An axis that may follow another (G51.4) has its setpoint from elsewhere
// at times.
const AxisConfig& commanded_axis_of_channel(const YamlValue& ref, const ChannelConfig& channel,
                                            const MachineConfig& config, const char* what) {
  const std::string name = read_name(ref);
  if (std::find(channel.axes.begin(), channel.axes.end(), name) == channel.axes.end()) {
    ref.fail(name + " is not an axis of channel " + channel.name + " (its `axes`: " + what +
             " is laid over what the channel commands it)");
  }
  const AxisConfig* axis = config.find_axis(name);
  if (axis->sync_slave) {
    ref.fail(name +
             " may follow another axis (G51.4, axis_sync): its setpoint is not the "
             "channel's alone");
  }
  return *axis;
}

// `polygon` names the master spindle of the channel (param 5310), which holds the work, and the
// polygon axis (5311), a driven tool that follows it: another spindle of the channel, or one of
// its own rotary servo axes (the spec allows both, L2897-2899). A spindle that is a G114.1 slave
// follows its own master already; an axis that may follow another (G51.4) has its setpoint
// from elsewhere at times, and an axis with soft limits could not turn without end. Without
// max_rpm (param 5312) the polygon axis may turn as fast as its drive.
void check_polygon(MachineConfig& config, ChannelConfig& channel, const YamlValue& value) {
  if (channel.polygon_master == 0) {
    return;
  }
  const YamlValue polygon = value.child("polygon");
  channel.polygon_master = spindle_of_channel(polygon.child("master"), channel, config);
  const YamlValue slave_ref = polygon.child("slave");
  const AxisConfig* named = config.find_axis(read_name(slave_ref));
  if (named != nullptr && named->type != AxisType::spindle) {
    const AxisConfig& axis =
        commanded_axis_of_channel(slave_ref, channel, config, "the polygon axis's turning");
    if (axis.type != AxisType::rotary) {
      slave_ref.fail(axis.name + " is not a rotary axis (the polygon axis turns with the master)");
    }
    if (axis.has_soft_limits) {
      slave_ref.fail(axis.name + " has soft_limits: the polygon axis turns without end");
    }
    channel.polygon_slave = axis.id;
  } else {
    channel.polygon_slave = spindle_of_channel(slave_ref, channel, config);
  }
  if (channel.polygon_master == channel.polygon_slave) {
    slave_ref.fail("a spindle cannot follow itself");
  }
  for (const SpindleSyncGroup& g : config.spindle_sync) {
    if (g.slave == channel.polygon_slave) {
      slave_ref.fail("the spindle is already the slave of G114.1 group " + std::to_string(g.group) +
                     " (spindle_sync)");
    }
  }
  const AxisConfig& slave = config.axes[static_cast<std::size_t>(channel.polygon_slave - 1)];
  const double drive_rpm = slave.drive.max_velocity / 6.0;
  if (channel.polygon_max_rpm == 0.0) {
    channel.polygon_max_rpm = drive_rpm;
  } else if (channel.polygon_max_rpm > drive_rpm) {
    polygon.child("max_rpm").fail("max_rpm is above what " + slave.name + "'s drive can turn (" +
                                  std::to_string(static_cast<int>(drive_rpm)) + " rpm)");
  }
}

// `cam` names the master spindle of G51.8 (param 5350), a spindle of the channel, and its slave
// (param 5351), one of the channel's own axes.
void check_cam(MachineConfig& config, ChannelConfig& channel, const YamlValue& value) {
  if (channel.cam_master == 0) {
    return;
  }
  const YamlValue cam = value.child("cam");
  channel.cam_master = spindle_of_channel(cam.child("master"), channel, config);
  channel.cam_slave =
      commanded_axis_of_channel(cam.child("slave"), channel, config, "the cam's lift").id;
  if (channel.cam_slave == channel.polygon_slave) {
    cam.child("slave").fail(read_name(cam.child("slave")) + " is the channel's polygon axis");
  }
}

// `egb` names G81.4's tool spindle (param 5330), a spindle of the channel; its work axis (5331),
// one of the channel's own rotary axes, not the cam's slave; and the axial feed axis of helical
// gears (5332), optional, another of its axes, linear.
void check_egb(MachineConfig& config, ChannelConfig& channel, const YamlValue& value) {
  if (channel.egb_tool == 0) {
    return;
  }
  const YamlValue egb = value.child("egb");
  channel.egb_tool = spindle_of_channel(egb.child("tool"), channel, config);
  const AxisConfig& work =
      commanded_axis_of_channel(egb.child("work"), channel, config, "the gear box's angle");
  if (work.type != AxisType::rotary) {
    egb.child("work").fail(work.name +
                           " is not a rotary axis (the work axis turns with the "
                           "tool spindle)");
  }
  if (work.id == channel.cam_slave) {
    egb.child("work").fail(work.name + " is the slave of the channel's cam already");
  }
  if (work.id == channel.polygon_slave) {
    egb.child("work").fail(work.name + " is the channel's polygon axis");
  }
  channel.egb_work = work.id;
  if (channel.egb_axial != 0) {
    const YamlValue axial = egb.child("axial");
    const std::string name = read_name(axial);
    if (std::find(channel.axes.begin(), channel.axes.end(), name) == channel.axes.end()) {
      axial.fail(name + " is not an axis of channel " + channel.name);
    }
    const AxisConfig* axis = config.find_axis(name);
    if (axis->type != AxisType::linear) {
      axial.fail(name + " is not a linear axis (the hob's feed along the work)");
    }
    channel.egb_axial = axis->id;
  }
}

// `polar` names a linear and a rotary axis the channel programs: G12.1 turns the work on the
// one while the tool moves on the other. `normal` names a rotary axis it programs: G41.1 keeps
// it normal to the path. `inclined` names two linear axes it programs: the inclined one and
// the one it is compensated on.
void check_interpolation_axes(const MachineConfig& config, const ChannelConfig& channel,
                              const YamlValue& value) {
  if (channel.polar_linear != 0) {
    check_program_axis(config, channel, value.child("polar").child("linear"), channel.polar_linear,
                       AxisType::linear, "linear");
    check_program_axis(config, channel, value.child("polar").child("rotary"), channel.polar_rotary,
                       AxisType::rotary, "rotary");
  }
  if (channel.normal_axis != 0) {
    check_program_axis(config, channel, value.child("normal").child("axis"), channel.normal_axis,
                       AxisType::rotary, "rotary");
  }
  if (channel.inclined_axis != 0) {
    check_program_axis(config, channel, value.child("inclined").child("axis"),
                       channel.inclined_axis, AxisType::linear, "linear");
    check_program_axis(config, channel, value.child("inclined").child("orthogonal"),
                       channel.inclined_orthogonal, AxisType::linear, "linear");
  }
}

MachineConfig parse_document(const YAML::Node& root) {
  const YamlValue top(root, "");
  if (!root.IsMap()) {
    top.fail("a machine file is a map with the keys machine, buses, channels and axes");
  }
  const YamlMap doc =
      top.map({"machine", "buses", "channels", "axes", "plc", "spindle_sync", "hmi", "hosts"});
  MachineConfig config;
  parse_machine_section(doc.required("machine"), config);

  // Per-item checks first (types, ranges, unknown keys), in file order.
  const YamlValue buses_value = doc.required("buses");
  const std::vector<YamlValue> buses = buses_value.list();
  if (buses.empty()) {
    buses_value.fail("a machine needs at least one bus");
  }
  std::map<std::string, std::size_t> bus_index;
  std::map<std::string, std::size_t> bus_uri;
  for (std::size_t i = 0; i < buses.size(); ++i) {
    config.buses.push_back(parse_bus(buses[i]));
    check_unique(bus_index, config.buses[i].name, buses[i], i, "buses", "bus");
    // Two buses on one medium would share node ids and SYNC without the loader noticing.
    const auto [it, inserted] = bus_uri.emplace(config.buses[i].uri, i);
    if (!inserted) {
      buses[i].child("uri").fail("uri " + config.buses[i].uri + " is already used by " +
                                 detail::join_index("buses", it->second));
    }
  }

  const YamlValue axes_value = doc.required("axes");
  const std::vector<YamlValue> axes = axes_value.list();
  if (axes.empty()) {
    axes_value.fail("a machine needs at least one axis");
  }
  std::map<std::string, std::size_t> axis_index;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    config.axes.push_back(parse_axis(axes[i]));
    config.axes[i].id = static_cast<int>(i) + 1;
    check_unique(axis_index, config.axes[i].name, axes[i], i, "axes", "axis");
  }
  std::vector<YamlValue> c_axis_values;  // where each of config.c_axes was written
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (config.axes[i].c_axis.empty()) {
      continue;
    }
    c_axis_values.push_back(axes[i].child("c_axis"));
    config.c_axes.push_back(parse_c_axis(c_axis_values.back(), config.axes[i]));
    if (axis_index.contains(config.c_axes.back().name) ||
        (config.c_axes.size() > 1 &&
         std::any_of(config.c_axes.begin(), config.c_axes.end() - 1,
                     [&](const AxisConfig& a) { return a.name == config.c_axes.back().name; }))) {
      c_axis_values.back().child("name").fail("duplicate axis name " + config.c_axes.back().name);
    }
  }

  const YamlValue channels_value = doc.required("channels");
  const std::vector<YamlValue> channels = channels_value.list();
  if (channels.empty()) {
    channels_value.fail("a machine needs at least one channel");
  }
  if (channels.size() > kMaxChannels) {
    channels_value.fail("a machine has at most " + std::to_string(kMaxChannels) +
                        " channels (G04.1 and the channel status name channels 1-64)");
  }
  std::vector<std::vector<YamlValue>> channel_refs(channels.size());
  std::vector<std::vector<YamlValue>> spindle_refs(channels.size());
  std::map<std::string, std::size_t> channel_index;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    config.channels.push_back(parse_channel(channels[i], channel_refs[i], spindle_refs[i]));
    config.channels[i].id = static_cast<int>(i) + 1;
    check_unique(channel_index, config.channels[i].name, channels[i], i, "channels", "channel");
  }

  // Cross references.
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    const AxisConfig& axis = config.axes[i];
    if (!bus_index.contains(axis.bus)) {
      axes[i].child("bus").fail("unknown bus " + axis.bus);
    }
  }

  // A channel's axes and spindles: each known, of the right kind, in one channel only.
  const auto claim = [&](const YamlValue& ref, const std::string& name, const std::string& channel,
                         bool spindle) -> AxisConfig& {
    const auto found = axis_index.find(name);
    if (found == axis_index.end()) {
      ref.fail("unknown axis " + name);
    }
    AxisConfig& axis = config.axes[found->second];
    if (!axis.channel.empty()) {
      ref.fail("axis " + axis.name + " is already in channel " + axis.channel);
    }
    if (spindle != (axis.type == AxisType::spindle)) {
      ref.fail(spindle ? "axis " + axis.name + " is not a spindle (type: spindle)"
                       : "axis " + axis.name + " is a spindle: list it in the channel's spindles");
    }
    axis.channel = channel;
    return axis;
  };
  for (std::size_t c = 0; c < config.channels.size(); ++c) {
    ChannelConfig& channel = config.channels[c];
    std::map<char, std::string> addresses;  // address -> axis name, within this channel
    for (std::size_t j = 0; j < channel.axes.size(); ++j) {
      const YamlValue& ref = channel_refs[c][j];
      const AxisConfig& axis = claim(ref, channel.axes[j], channel.name, false);
      // One address per channel: X also claims its incremental twin U, Z claims W, and so on.
      const auto [other, inserted] = addresses.emplace(axis.address, axis.name);
      if (!inserted) {
        ref.fail("axis " + axis.name + " has address " + std::string(1, axis.address) +
                 ", already used by axis " + other->second + " in channel " + channel.name);
      }
    }
    for (std::size_t j = 0; j < channel.spindles.size(); ++j) {
      claim(spindle_refs[c][j], channel.spindles[j], channel.name, true);
    }
  }

  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    if (config.axes[i].channel.empty()) {
      axes[i].fail("axis " + config.axes[i].name + " is in no channel");
    }
  }

  // G51.4 masters (param 5610): an axis of the same kind that is no slave itself, so that a
  // slave never follows a slave.
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    AxisConfig& axis = config.axes[i];
    if (!axis.sync_slave) {
      continue;
    }
    const YamlValue sync = axes[i].child("axis_sync");
    const YamlMap s = sync.map({"master", "at_power_on"});
    const auto master = s.optional("master");
    if (!master) {
      if (axis.sync_at_power_on) {
        sync.fail("at_power_on needs a master");
      }
      continue;
    }
    const std::string name = read_name(*master);
    const auto found = axis_index.find(name);
    if (found == axis_index.end()) {
      master->fail("unknown axis " + name);
    }
    const AxisConfig& m = config.axes[found->second];
    if (m.name == axis.name) {
      master->fail("an axis cannot follow itself");
    }
    if (m.type != axis.type) {
      master->fail("axis " + m.name + " is not of the same kind as " + axis.name);
    }
    if (m.sync_slave) {
      master->fail("axis " + m.name + " may follow another axis itself (axis_sync)");
    }
    axis.sync_master = m.id;
  }

  // Exchange numbers name one axis machine-wide; a channel's exchange axes are exchangeable
  // axes of other channels whose address is free in it.
  std::map<int, std::string> exchange_numbers;
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    const AxisConfig& axis = config.axes[i];
    if (axis.exchange == 0) {
      continue;
    }
    const auto [other, inserted] = exchange_numbers.emplace(axis.exchange, axis.name);
    if (!inserted) {
      axes[i]
          .child("exchange")
          .fail("exchange number " + std::to_string(axis.exchange) + " is already axis " +
                other->second + "'s");
    }
  }
  for (std::size_t c = 0; c < config.channels.size(); ++c) {
    const ChannelConfig& channel = config.channels[c];
    if (channel.exchange_axes.empty()) {
      continue;
    }
    const std::vector<YamlValue> refs = channels[c].child("exchange_axes").list();
    std::map<char, std::string> addresses;
    for (const std::string& name : channel.axes) {
      addresses.emplace(config.axes[axis_index.at(name)].address, name);
    }
    for (std::size_t j = 0; j < refs.size(); ++j) {
      const auto found = axis_index.find(channel.exchange_axes[j]);
      if (found == axis_index.end()) {
        refs[j].fail("unknown axis " + channel.exchange_axes[j]);
      }
      const AxisConfig& axis = config.axes[found->second];
      if (axis.exchange == 0) {
        refs[j].fail("axis " + axis.name + " has no exchange number (exchange:)");
      }
      if (axis.channel == channel.name) {
        refs[j].fail("axis " + axis.name + " is already in channel " + channel.name);
      }
      const auto [other, inserted] = addresses.emplace(axis.address, axis.name);
      if (!inserted) {
        refs[j].fail("axis " + axis.name + " has address " + std::string(1, axis.address) +
                     ", already used by axis " + other->second + " in channel " + channel.name);
      }
    }
  }

  // A spindle's C axis is programmed in the spindle's channel, under an address free there; only
  // the channel's first spindle is programmed (M03-M05, M18/M17) in this version.
  for (std::size_t k = 0; k < config.c_axes.size(); ++k) {
    AxisConfig& c = config.c_axes[k];
    const AxisConfig& spindle = config.axes[axis_index.at(c.spindle)];
    ChannelConfig& channel =
        *std::find_if(config.channels.begin(), config.channels.end(),
                      [&](const ChannelConfig& ch) { return ch.name == spindle.channel; });
    if (channel.spindles.front() != spindle.name) {
      c_axis_values[k].fail("only a channel's first spindle has a C axis in this version (" +
                            spindle.name + " is not " + channel.name + "'s first)");
    }
    for (const std::string& name : channel.program_axes()) {
      if (config.find_axis(name)->address == c.address) {
        c_axis_values[k].fail("axis " + c.name + " has address " + std::string(1, c.address) +
                              ", already used by axis " + name + " in channel " + channel.name);
      }
    }
    c.channel = channel.name;
    channel.c_axes.push_back(c.name);
  }
  for (std::size_t i = 0; i < config.channels.size(); ++i) {
    if (config.channels[i].program_axes().size() > kMaxProgramAxes) {
      channels[i].fail("a channel programs at most " + std::to_string(kMaxProgramAxes) +
                       " axes (its axes, exchange_axes and its spindle's c_axis)");
    }
    check_interpolation_axes(config, config.channels[i], channels[i]);
  }

  if (auto hosts = doc.optional("hosts")) {
    std::optional<YamlValue> cycle_value;  // where the file sets the cycle, if it does
    if (root["machine"]["cycle_us"]) {
      cycle_value = doc.required("machine").child("cycle_us");
    }
    parse_hosts(*hosts, config, doc.optional("plc").has_value(), cycle_value);
  }

  // Node ids per bus, and the axes each bus carries.
  std::map<std::string, std::map<int, std::string>> nodes;  // bus -> node id -> axis
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    const AxisConfig& axis = config.axes[i];
    const auto [other, inserted] = nodes[axis.bus].emplace(axis.node_id, axis.name);
    if (!inserted) {
      axes[i].child("node_id").fail("node id " + std::to_string(axis.node_id) +
                                    " is already used by axis " + other->second + " on bus " +
                                    axis.bus);
    }
  }

  for (std::size_t b = 0; b < config.buses.size(); ++b) {
    BusConfig& bus = config.buses[b];
    if (bus.sync_offset_us < 0) {
      bus.sync_offset_us = config.cycle_us / 2;
    } else if (bus.sync_offset_us >= config.cycle_us) {
      buses[b]
          .child("sync_offset_us")
          .fail("must be below the cycle (" + std::to_string(config.cycle_us) + " us)");
    }
    const auto on_bus = nodes.find(bus.name);
    if (on_bus == nodes.end()) {
      buses[b].fail("no axis is on bus " + bus.name);
    }
    const auto producer = axis_index.find(bus.sync_producer);
    if (producer == axis_index.end()) {
      buses[b].child("sync_producer").fail("unknown axis " + bus.sync_producer);
    }
    if (config.axes[producer->second].bus != bus.name) {
      buses[b]
          .child("sync_producer")
          .fail("axis " + bus.sync_producer + " is not on bus " + bus.name);
    }
    int count = 0;
    int spindle_count = 0;
    long long bits = can_frame_bits(1);  // SYNC
    for (const auto& [node, name] : on_bus->second) {
      const AxisConfig& axis = config.axes[axis_index.at(name)];
      (axis.type == AxisType::spindle ? spindle_count : count) += 1;
      bits += axis_bits_per_cycle(axis);
    }
    // Integer comparison, so a bus exactly at the limit is accepted on every platform.
    const long long capacity =
        static_cast<long long>(bus.bitrate) * config.cycle_us;  // 1e6 x bits/cycle
    if (bits * 1000000LL * 100 > capacity * kMaxBusLoadPercent) {
      std::ostringstream reason;
      reason.precision(1);
      reason << std::fixed << count << (count == 1 ? " axis" : " axes");
      if (spindle_count > 0) {
        reason << " and " << spindle_count << (spindle_count == 1 ? " spindle" : " spindles");
      }
      reason << (count + spindle_count == 1 ? " needs " : " need ") << bits << " bits per "
             << config.cycle_us << " us cycle, "
             << 100.0 * static_cast<double>(bits) / (static_cast<double>(capacity) * 1e-6)
             << " % of " << bus.bitrate << " bit/s; the limit is " << kMaxBusLoadPercent << " %";
      buses[b].fail(reason.str());
    }
  }
  if (auto plc = doc.optional("plc")) {
    parse_plc(*plc, config);
  }
  if (auto hmi = doc.optional("hmi")) {
    parse_hmi(*hmi, config.hmi);
  }
  if (auto groups = doc.optional("spindle_sync")) {
    for (const YamlValue& v : groups->list()) {
      const YamlMap g = v.map({"group", "master", "slave"});
      SpindleSyncGroup group;
      group.group = read_int(g.required("group"), 1, 3);
      group.master = spindle_id(g.required("master"), config);
      group.slave = spindle_id(g.required("slave"), config);
      if (group.master == group.slave) {
        g.required("slave").fail("a spindle cannot follow itself");
      }
      for (const SpindleSyncGroup& other : config.spindle_sync) {
        if (other.group == group.group) {
          g.required("group").fail("group " + std::to_string(group.group) + " is defined twice");
        }
        if (other.slave == group.slave) {
          g.required("slave").fail("the spindle is already the slave of group " +
                                   std::to_string(other.group));
        }
      }
      const AxisConfig& master = config.axes[static_cast<std::size_t>(group.master - 1)];
      group.channel = config.find_channel(master.channel)->id;
      config.spindle_sync.push_back(group);
    }
  }
  for (std::size_t i = 0; i < config.channels.size(); ++i) {
    check_polygon(config, config.channels[i], channels[i]);
    check_cam(config, config.channels[i], channels[i]);
    check_egb(config, config.channels[i], channels[i]);
  }
  return config;
}

}  // namespace

std::uint64_t cycles_of(int ms, int cycle_us) noexcept {
  const auto us = static_cast<std::uint64_t>(ms) * 1000U;
  const auto per = static_cast<std::uint64_t>(cycle_us);
  return (us + per - 1) / per;
}

std::uint64_t MachineConfig::cycles_of(int ms) const noexcept {
  return config::cycles_of(ms, cycle_us);
}

const AxisConfig* MachineConfig::find_axis(const std::string& name) const noexcept {
  for (const std::vector<AxisConfig>* list : {&axes, &c_axes}) {
    for (const AxisConfig& axis : *list) {
      if (axis.name == name) {
        return &axis;
      }
    }
  }
  return nullptr;
}

std::vector<std::string> ChannelConfig::program_axes() const {
  std::vector<std::string> all = axes;
  all.insert(all.end(), exchange_axes.begin(), exchange_axes.end());
  all.insert(all.end(), c_axes.begin(), c_axes.end());
  return all;
}

const ChannelConfig* MachineConfig::find_channel(const std::string& name) const noexcept {
  for (const ChannelConfig& channel : channels) {
    if (channel.name == name) {
      return &channel;
    }
  }
  return nullptr;
}

const HostConfig* MachineConfig::host_of(const std::string& process) const noexcept {
  for (const HostConfig& h : hosts) {
    if (std::find(h.runs.begin(), h.runs.end(), process) != h.runs.end()) {
      return &h;
    }
  }
  return nullptr;
}

std::string MachineConfig::middleware_of(const std::string& process) const {
  std::string own;
  if (const ChannelConfig* ch = find_channel(process)) {
    own = ch->middleware;
  } else if (const AxisConfig* axis = find_axis(process)) {
    own = axis->middleware;
  } else if (process == "PLC") {
    own = plc.middleware;
  } else if (process == "HMI") {
    own = hmi.middleware;
  }
  return own.empty() ? middleware : own;
}

const BusConfig* MachineConfig::find_bus(const std::string& name) const noexcept {
  for (const BusConfig& bus : buses) {
    if (bus.name == name) {
      return &bus;
    }
  }
  return nullptr;
}

int can_frame_bits(int data_bytes) noexcept {
  // 47 fixed bits (SOF, 11-bit id, RTR, IDE, r0, DLC, CRC, delimiters, ACK, EOF, intermission),
  // plus the worst-case stuff bits over the 34 + 8n bits that are subject to stuffing.
  return 47 + 8 * data_bytes + (34 + 8 * data_bytes - 1) / 4;
}

int bus_bits_per_cycle(int axis_count, int spindle_count) noexcept {
  constexpr int kSyncBytes = 1;  // SYNC carries the 1-byte counter
  constexpr int kPdoBytes = 6;   // CSP: controlword + target position / statusword + position
  // A spindle: RPDO1 and TPDO1 carry the mode (7 bytes), RPDO2 the target velocity (4).
  constexpr int kSpindlePdoBytes = 7;
  constexpr int kVelocityBytes = 4;
  return can_frame_bits(kSyncBytes) + axis_count * 2 * can_frame_bits(kPdoBytes) +
         spindle_count * (2 * can_frame_bits(kSpindlePdoBytes) + can_frame_bits(kVelocityBytes));
}

int tpdo2_bytes(const AxisConfig& axis) noexcept {
  return (axis.tpdo2_velocity ? 4 : 0) + (axis.tpdo2_following_error ? 4 : 0) +
         (axis.tpdo2_torque || axis.torque_skip ? 2 : 0);
}

int axis_bits_per_cycle(const AxisConfig& axis) noexcept {
  if (axis.probe_input > 0) {
    return 3 * can_frame_bits(8);  // RPDO1, TPDO1 and TPDO2 full (canopen::add_touch_probe)
  }
  const int bytes = tpdo2_bytes(axis);
  const int tpdo2 = bytes > 0 ? can_frame_bits(bytes) : 0;
  if (axis.type == AxisType::spindle) {
    return 2 * can_frame_bits(7) + can_frame_bits(4) + tpdo2;
  }
  if (axis.torque_mode) {
    // The mode and its display in RPDO1/TPDO1; 0x6072, 0x6071 and 0x6080 in RPDO2.
    return 2 * can_frame_bits(7) + tpdo2 + can_frame_bits(8);
  }
  const int rpdo2 = axis.torque_skip ? can_frame_bits(2) : 0;  // 0x6072
  return 2 * can_frame_bits(axis.has_homing ? 7 : 6) + tpdo2 + rpdo2;
}

double bus_load(int axis_count, int bitrate, int cycle_us, int spindle_count) noexcept {
  if (bitrate <= 0 || cycle_us <= 0) {
    return 0.0;
  }
  const double bits_per_cycle = bus_bits_per_cycle(axis_count, spindle_count);
  return bits_per_cycle / (static_cast<double>(bitrate) * cycle_us * 1e-6);
}

MachineConfig parse_machine_yaml(const std::string& yaml_text) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::Exception& error) {
    // yaml-cpp counts lines and columns from 0.
    throw ConfigError("", "invalid YAML at line " + std::to_string(error.mark.line + 1) +
                              ", column " + std::to_string(error.mark.column + 1) + ": " +
                              error.msg);
  }
  if (documents.empty()) {
    throw ConfigError("", "the machine file is empty");
  }
  if (documents.size() > 1) {
    // A stray "---" would otherwise hide everything after it.
    throw ConfigError("", "the machine file holds " + std::to_string(documents.size()) +
                              " YAML documents; it must hold one");
  }
  return parse_document(documents.front());
}

MachineConfig load_machine_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ConfigError(path, std::string("cannot open the machine file: ") + std::strerror(errno));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    throw ConfigError(path, "cannot read the machine file");
  }
  try {
    MachineConfig machine = parse_machine_yaml(text.str());
    if (!machine.program_dir.empty()) {
      std::filesystem::path dir(machine.program_dir);
      if (dir.is_relative()) {
        dir = std::filesystem::path(path).parent_path() / dir;
      }
      std::error_code ec;
      if (!std::filesystem::is_directory(dir, ec)) {
        throw ConfigError("machine.program_dir", "no directory " + dir.string());
      }
      machine.program_dir = dir.lexically_normal().string();
    }
    if (!machine.retained_file.empty() &&
        std::filesystem::path(machine.retained_file).is_relative()) {
      machine.retained_file = (std::filesystem::path(path).parent_path() / machine.retained_file)
                                  .lexically_normal()
                                  .string();
    }
    // Its files are checked by whoever uses them (process::resolve_security_or_exit), which
    // names the file that is wrong; `mcnc certs` makes the directory after the file names it.
    if (!machine.security_dir.empty() &&
        std::filesystem::path(machine.security_dir).is_relative()) {
      machine.security_dir = std::filesystem::absolute(std::filesystem::path(path).parent_path() /
                                                       machine.security_dir)
                                 .lexically_normal()
                                 .string();
    }
    return machine;
  } catch (const ConfigError& error) {
    // Only whole-file errors (syntax, empty) have no key path; name the file instead.
    if (!error.key_path().empty()) {
      throw;
    }
    const std::string what = error.what();  // ": reason" for an empty key path
    throw ConfigError(path, what.substr(2));
  }
}

}  // namespace mcnc::config
