// Machine file loader: a good file parsed completely, defaults, and every rejection with its exact
// key path.
#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace mcnc::config {
namespace {

const std::string kSourceDir = MCNC_SOURCE_DIR;

// Two channels, two buses, four axes: enough structure for every cross-reference rule.
constexpr const char* kBase = R"(
machine:
  name: twin
  cycle_us: 1000
buses:
  - name: can0
    uri: udp:239.255.42.1:42000
    sync_producer: X1
  - name: can1
    uri: socketcan:can1
    bitrate: 1000000
    sync_producer: X2
channels:
  - name: CH1
    axes: [X1, Z1]
  - name: CH2
    axes: [X2, Z2]
axes:
  - name: X1
    address: X
    diameter: true
    bus: can0
    node_id: 1
    drive:
      max_velocity: 300
  - name: Z1
    address: Z
    bus: can0
    node_id: 2
  - name: X2
    address: X
    diameter: true
    bus: can1
    node_id: 1
  - name: Z2
    address: Z
    bus: can1
    node_id: 2
)";

using Mutation = std::function<void(YAML::Node&)>;

std::string mutated(const Mutation& mutate) {
  YAML::Node root = YAML::Load(kBase);
  mutate(root);
  return YAML::Dump(root);
}

// The key path of the rejection, or "<accepted>" so a missing rejection shows in the assertion.
std::string rejection_path(const std::string& text, std::string* what = nullptr) {
  try {
    (void)parse_machine_yaml(text);
  } catch (const ConfigError& error) {
    if (what != nullptr) {
      *what = error.what();
    }
    return error.key_path();
  }
  return "<accepted>";
}

std::string text_with_axes(int axis_count, int cycle_us, int bitrate) {
  YAML::Node root;
  root["machine"]["name"] = "load";
  root["machine"]["cycle_us"] = cycle_us;
  YAML::Node bus;
  bus["name"] = "can0";
  bus["uri"] = "udp:239.255.42.1:42000";
  bus["bitrate"] = bitrate;
  bus["sync_producer"] = "A1";
  root["buses"].push_back(bus);
  for (int i = 1; i <= axis_count; ++i) {
    // One channel cannot hold two axes with one address, so put each axis in its own channel.
    YAML::Node ch;
    ch["name"] = "CH" + std::to_string(i);
    ch["axes"].push_back("A" + std::to_string(i));
    root["channels"].push_back(ch);
    YAML::Node axis;
    axis["name"] = "A" + std::to_string(i);
    axis["address"] = "X";
    axis["bus"] = "can0";
    axis["node_id"] = i;
    root["axes"].push_back(axis);
  }
  return YAML::Dump(root);
}

// A time from the machine file as cycles: rounded up, so that a time is never cut short.
TEST(MachineConfig, MillisecondsBecomeWholeCyclesRoundedUp) {
  EXPECT_EQ(cycles_of(0, 2000), 0U);
  EXPECT_EQ(cycles_of(1, 2000), 1U);
  EXPECT_EQ(cycles_of(4, 2000), 2U);
  EXPECT_EQ(cycles_of(5, 2000), 3U);
  MachineConfig m;
  m.cycle_us = 1000;
  EXPECT_EQ(m.cycles_of(10000), 10000U);
}

// Every machine file the project ships loads: a key it adds is checked like a user's.
TEST(MachineConfig, EveryShippedMachineFileLoads) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir + "/launch/machines")) {
    if (entry.path().extension() != ".yaml") {
      continue;
    }
    ++files;
    EXPECT_NO_THROW((void)load_machine_file(entry.path().string())) << entry.path();
  }
  EXPECT_GE(files, 6);
  const MachineConfig twin = load_machine_file(kSourceDir + "/launch/machines/twin_turret.yaml");
  EXPECT_EQ(twin.channels.size(), 3U);
  const MachineConfig gantry = load_machine_file(kSourceDir + "/launch/machines/gantry_cell.yaml");
  EXPECT_TRUE(gantry.find_axis("X1")->sync_at_power_on);
  EXPECT_EQ(gantry.find_axis("X1")->sync_master, gantry.find_axis("X")->id);
}

TEST(MachineConfig, SmallLatheFileIsFullyParsed) {
  const MachineConfig config = load_machine_file(kSourceDir + "/launch/machines/small_lathe.yaml");
  EXPECT_EQ(config.name, "small_lathe");
  EXPECT_EQ(config.cycle_us, 1000);
  EXPECT_DOUBLE_EQ(config.cycle_s(), 0.001);
  EXPECT_EQ(config.deadline_cycles, 20);
  EXPECT_EQ(config.domain, 0);

  ASSERT_EQ(config.buses.size(), 1u);
  EXPECT_EQ(config.buses[0].name, "can0");
  EXPECT_EQ(config.buses[0].uri, "udp:239.255.42.1:29000");
  EXPECT_EQ(config.buses[0].bitrate, 1000000);
  EXPECT_EQ(config.buses[0].sync_producer, "X1");

  ASSERT_EQ(config.channels.size(), 1u);
  EXPECT_EQ(config.channels[0].name, "CH1");
  EXPECT_EQ(config.channels[0].id, 1);
  EXPECT_EQ(config.channels[0].axes, (std::vector<std::string>{"X1", "Z1"}));

  ASSERT_EQ(config.axes.size(), 2u);
  const AxisConfig& x = config.axes[0];
  EXPECT_EQ(x.name, "X1");
  EXPECT_EQ(x.id, 1);
  EXPECT_EQ(x.address, 'X');
  EXPECT_EQ(x.type, AxisType::linear);
  EXPECT_TRUE(x.diameter);
  EXPECT_EQ(x.channel, "CH1");
  EXPECT_EQ(x.bus, "can0");
  EXPECT_EQ(x.node_id, 1);
  EXPECT_DOUBLE_EQ(x.counts_per_unit, 10000.0);
  EXPECT_DOUBLE_EQ(x.rapid_rate, 8000.0);
  EXPECT_DOUBLE_EQ(x.max_feed, 5000.0);
  EXPECT_DOUBLE_EQ(x.acceleration, 1500.0);
  EXPECT_DOUBLE_EQ(x.in_position, 0.0005);
  EXPECT_DOUBLE_EQ(x.drive.time_constant_s, 0.004);
  EXPECT_DOUBLE_EQ(x.drive.max_velocity, 200.0);
  EXPECT_DOUBLE_EQ(x.drive.quick_stop_decel, 5000.0);

  const AxisConfig& z = config.axes[1];
  EXPECT_EQ(z.name, "Z1");
  EXPECT_EQ(z.id, 2);
  EXPECT_EQ(z.address, 'Z');
  EXPECT_FALSE(z.diameter);
  EXPECT_EQ(z.channel, "CH1");
  EXPECT_EQ(z.node_id, 2);
  EXPECT_DOUBLE_EQ(z.rapid_rate, 10000.0);
  EXPECT_DOUBLE_EQ(z.drive.max_velocity, 250.0);
}

TEST(MachineConfig, DefaultsAreApplied) {
  const MachineConfig config = parse_machine_yaml(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: A}]
channels: [{name: C, axes: [A]}]
axes: [{name: A, address: C, type: rotary, bus: b, node_id: 127}]
)");
  EXPECT_EQ(config.cycle_us, 1000);
  EXPECT_EQ(config.deadline_cycles, 5);
  EXPECT_EQ(config.domain, 0);
  EXPECT_EQ(config.buses[0].bitrate, 1000000);
  const AxisConfig& a = config.axes[0];
  EXPECT_EQ(a.type, AxisType::rotary);
  EXPECT_EQ(a.address, 'C');
  EXPECT_FALSE(a.diameter);
  EXPECT_EQ(a.node_id, 127);
  EXPECT_DOUBLE_EQ(a.counts_per_unit, 10000.0);
  EXPECT_DOUBLE_EQ(a.rapid_rate, 12000.0);
  EXPECT_DOUBLE_EQ(a.max_feed, 6000.0);
  EXPECT_DOUBLE_EQ(a.acceleration, 1000.0);
  EXPECT_DOUBLE_EQ(a.in_position, 0.0005);
  EXPECT_DOUBLE_EQ(a.drive.time_constant_s, 0.004);
  EXPECT_DOUBLE_EQ(a.drive.max_velocity, 500.0);
  EXPECT_DOUBLE_EQ(a.drive.quick_stop_decel, 5000.0);
  EXPECT_DOUBLE_EQ(a.jerk, 50000.0);  // 50 x acceleration
  EXPECT_FALSE(a.has_soft_limits);
  EXPECT_DOUBLE_EQ(a.following_error_limit, 2.0);
  EXPECT_EQ(config.channels[0].motion.lookahead_blocks, 200);
  EXPECT_TRUE(config.channels[0].motion.jerk_limited);
}

TEST(MachineConfig, DriveMechanicsKeys) {
  const MachineConfig config = parse_machine_yaml(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: A}]
channels: [{name: C, axes: [A]}]
axes: [{name: A, address: X, bus: b, node_id: 1, drive: {units_per_rev: 5, inertia: 0.002, friction: 0.01, torque_limit: 2.5, velocity_bandwidth_hz: 120}}]
)");
  const DriveSimConfig& d = config.axes[0].drive;
  EXPECT_DOUBLE_EQ(d.units_per_rev, 5.0);
  EXPECT_DOUBLE_EQ(d.inertia, 0.002);
  EXPECT_DOUBLE_EQ(d.friction, 0.01);
  EXPECT_DOUBLE_EQ(d.torque_limit, 2.5);
  EXPECT_DOUBLE_EQ(d.velocity_bandwidth_hz, 120.0);
  EXPECT_DOUBLE_EQ(d.max_velocity, 500.0);  // the defaults beside them
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][0]["drive"]["inertia"] = 0; })),
            "axes[0].drive.inertia");
}

TEST(MachineConfig, SyncOffsetIsHalfTheCycleUnlessGivenAndStaysInsideIt) {
  EXPECT_EQ(parse_machine_yaml(kBase).buses[0].sync_offset_us, 500);  // 1000 us cycle
  const MachineConfig given =
      parse_machine_yaml(mutated([](YAML::Node& r) { r["buses"][0]["sync_offset_us"] = 700; }));
  EXPECT_EQ(given.buses[0].sync_offset_us, 700);
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["buses"][0]["sync_offset_us"] = 1000; })),
            "buses[0].sync_offset_us");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["buses"][0]["sync_offset_us"] = -1; })),
            "buses[0].sync_offset_us");
}

// An axis and a spindle on one bus; the tests add the channel.
constexpr const char* kAxisAndSpindle = R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
axes:
  - {name: X, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, bus: b, node_id: 2, counts_per_unit: 1000}
)";

// G81.1 (param 5700.1): an axis oscillates only when its `oscillation` says so; a spindle never.
TEST(MachineConfig, OscillationEnablesAnAxisForG811) {
  const MachineConfig config = parse_machine_yaml(R"(
machine: {name: m, cycle_us: 1000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
axes:
  - {name: X, address: X, bus: b, node_id: 1}
  - {name: Z, address: Z, bus: b, node_id: 2, oscillation: true}
channels: [{name: C, axes: [X, Z]}]
)");
  EXPECT_FALSE(config.find_axis("X")->oscillation);
  EXPECT_TRUE(config.find_axis("Z")->oscillation);
  std::string spindle = kAxisAndSpindle;
  const std::string s1 = "counts_per_unit: 1000}";
  spindle.replace(spindle.find(s1), s1.size(), "counts_per_unit: 1000, oscillation: true}");
  EXPECT_EQ(rejection_path(spindle + "channels: [{name: C, axes: [X], spindles: [S1]}]\n"),
            "axes[1].oscillation");
}

TEST(MachineConfig, SpindlesBelongToAChannelAndWeighMoreOnTheBus) {
  const std::string base = kAxisAndSpindle;
  const MachineConfig config =
      parse_machine_yaml(base + "channels: [{name: C, axes: [X], spindles: [S1]}]\n");
  ASSERT_EQ(config.channels[0].spindles, std::vector<std::string>{"S1"});
  const AxisConfig* s1 = config.find_axis("S1");
  ASSERT_NE(s1, nullptr);
  EXPECT_EQ(s1->type, AxisType::spindle);
  EXPECT_EQ(s1->channel, "C");
  // A spindle takes an RPDO and a TPDO of 7 bytes and an RPDO of 4 per cycle.
  EXPECT_EQ(bus_bits_per_cycle(1, 1) - bus_bits_per_cycle(1, 0),
            2 * can_frame_bits(7) + can_frame_bits(4));

  EXPECT_EQ(rejection_path(base + "channels: [{name: C, axes: [X, S1]}]\n"), "channels[0].axes[1]");
  EXPECT_EQ(rejection_path(base + "channels: [{name: C, axes: [X], spindles: [X]}]\n"),
            "channels[0].spindles[0]");
  EXPECT_EQ(rejection_path(base + "channels: [{name: C, axes: [X]}]\n"), "axes[1]");  // in none
  EXPECT_EQ(rejection_path(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
axes:
  - {name: X, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, address: C, bus: b, node_id: 2}
channels: [{name: C, axes: [X], spindles: [S1]}]
)"),
            "axes[1].address");
}

// Param 2201.3: a channel powers on in G98 (feed per minute) unless `feed_mode: per_rev` (G99),
// which needs a spindle of the channel to count revolutions of.
TEST(MachineConfig, PowerOnFeedModeOfAChannel) {
  const std::string base = kAxisAndSpindle;
  EXPECT_FALSE(parse_machine_yaml(base + "channels: [{name: C, axes: [X], spindles: [S1]}]\n")
                   .channels[0]
                   .feed_per_rev);
  EXPECT_TRUE(parse_machine_yaml(
                  base + "channels: [{name: C, axes: [X], spindles: [S1], feed_mode: per_rev}]\n")
                  .channels[0]
                  .feed_per_rev);
  EXPECT_FALSE(parse_machine_yaml(
                   base + "channels: [{name: C, axes: [X], spindles: [S1], feed_mode: per_min}]\n")
                   .channels[0]
                   .feed_per_rev);
  std::string what;
  EXPECT_EQ(rejection_path(base + "channels: [{name: C, axes: [X], spindles: [S1], feed_mode: "
                                  "G99}]\n"),
            "channels[0].feed_mode");
  EXPECT_EQ(rejection_path(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
axes: [{name: X, address: X, bus: b, node_id: 1}]
channels: [{name: C, axes: [X], feed_mode: per_rev}]
)",
                           &what),
            "channels[0].feed_mode");
  EXPECT_NE(what.find("needs a spindle"), std::string::npos) << what;
}

// A channel's interpreter dialect by name (common/config/dialect_names.hpp); Dafeng by default.
TEST(MachineConfig, DialectOfAChannel) {
  const std::string base = kAxisAndSpindle;
  EXPECT_EQ(parse_machine_yaml(base + "channels: [{name: C, axes: [X], spindles: [S1]}]\n")
                .channels[0]
                .dialect,
            "dafeng");
  EXPECT_EQ(parse_machine_yaml(
                base + "channels: [{name: C, axes: [X], spindles: [S1], dialect: fanuc-mill}]\n")
                .channels[0]
                .dialect,
            "fanuc-mill");
  EXPECT_EQ(parse_machine_yaml(
                base + "channels: [{name: C, axes: [X], spindles: [S1], dialect: fanuc-lathe}]\n")
                .channels[0]
                .dialect,
            "dafeng");  // the alias is read as the dialect's name
  std::string what;
  EXPECT_EQ(rejection_path(
                base + "channels: [{name: C, axes: [X], spindles: [S1], dialect: fanuc}]\n", &what),
            "channels[0].dialect");
  EXPECT_NE(what.find("dafeng, gsk or fanuc-mill"), std::string::npos) << what;
}

// Polar interpolation's axes (params 5530/5531) and the axis G07.1's rotary axis is parallel to
// (param 0016), per channel: the linear and the rotary axis of `polar` are axes the channel
// programs, its own, its exchange axes or its spindle's C axis.
constexpr const char* kMillTurn = R"(
machine: {name: m, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: C1, address: C, type: rotary, exchange: 15, bus: b, node_id: 3}
  - {name: X2, address: X, bus: b, node_id: 4}
  - {name: S2, type: spindle, bus: b, node_id: 5, c_axis: {name: C2, address: B}}
)";

TEST(MachineConfig, PolarAndCylindricalAxesOfAChannel) {
  const std::string base = kMillTurn;
  const MachineConfig plain = parse_machine_yaml(
      base + "channels: [{name: A, axes: [X1, Z1, C1]}, {name: B, axes: [X2], spindles: [S2]}]\n");
  EXPECT_EQ(plain.channels[0].polar_linear, 0);  // none: G12.1 is an alarm
  EXPECT_EQ(plain.channels[0].cylindrical_parallel, 'Y');
  EXPECT_DOUBLE_EQ(plain.channels[0].polar_tolerance, 0.001);

  const MachineConfig set = parse_machine_yaml(
      base +
      "channels:\n"
      "  - {name: A, axes: [X1, Z1, C1], polar: {linear: X, rotary: C, tolerance: 0.002},\n"
      "     cylindrical_parallel: Z}\n"
      "  - {name: B, axes: [X2], spindles: [S2], exchange_axes: [C1], polar: {linear: X, "
      "rotary: C}}\n");
  EXPECT_EQ(set.channels[0].polar_linear, 'X');
  EXPECT_EQ(set.channels[0].polar_rotary, 'C');
  EXPECT_DOUBLE_EQ(set.channels[0].polar_tolerance, 0.002);
  EXPECT_EQ(set.channels[0].cylindrical_parallel, 'Z');
  EXPECT_EQ(set.channels[1].polar_rotary, 'C');  // C1, which B may take with G141
  EXPECT_EQ(
      parse_machine_yaml(base + "channels: [{name: A, axes: [X1, Z1, C1]}, {name: B, axes: [X2], "
                                "spindles: [S2], polar: {linear: X, rotary: B}}]\n")
          .channels[1]
          .polar_rotary,
      'B');  // its spindle's C axis

  const std::string two = "  - {name: B, axes: [X2], spindles: [S2]}\n";
  std::string what;
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], polar: {linear: "
                           "X}}\n" +
                           two),
            "channels[0].polar.rotary");
  EXPECT_EQ(rejection_path(base +
                               "channels:\n  - {name: A, axes: [X1, Z1, C1], polar: {linear: "
                               "C, rotary: C}}\n" +
                               two,
                           &what),
            "channels[0].polar.linear");
  EXPECT_NE(what.find("an axis address of X, Y, Z, got 'C'"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(base +
                               "channels:\n  - {name: A, axes: [X1, Z1, C1], polar: {linear: "
                               "Y, rotary: C}}\n" +
                               two,
                           &what),
            "channels[0].polar.linear");
  EXPECT_NE(what.find("channel A programs no axis Y"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(base + "channels:\n  - {name: A, axes: [X1, Z1], polar: {linear: "
                                  "X, rotary: C}}\n  - {name: B, axes: [X2, C1], spindles: "
                                  "[S2]}\n"),
            "channels[0].polar.rotary");
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], polar: {linear: "
                           "X, rotary: C, tolerance: 2}}\n" +
                           two),
            "channels[0].polar.tolerance");
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], polar: {linear: "
                           "X, rotary: C, angle: 0}}\n" +
                           two),
            "channels[0].polar.angle");
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], "
                           "cylindrical_parallel: C}\n" +
                           two),
            "channels[0].cylindrical_parallel");
}

// Normal direction control's rotary axis and speed (params 5550/5551), per channel.
TEST(MachineConfig, NormalDirectionAxisOfAChannel) {
  const std::string base = kMillTurn;
  const std::string two = "  - {name: B, axes: [X2], spindles: [S2]}\n";
  const MachineConfig plain =
      parse_machine_yaml(base + "channels:\n  - {name: A, axes: [X1, Z1, C1]}\n" + two);
  EXPECT_EQ(plain.channels[0].normal_axis, 0);  // none: G41.1 is an alarm
  const MachineConfig set = parse_machine_yaml(
      base + "channels:\n  - {name: A, axes: [X1, Z1, C1], normal: {axis: C, feed: 7200}}\n" + two);
  EXPECT_EQ(set.channels[0].normal_axis, 'C');
  EXPECT_DOUBLE_EQ(set.channels[0].normal_feed, 7200.0);
  std::string what;
  EXPECT_EQ(rejection_path(base + "channels:\n  - {name: A, axes: [X1, Z1], normal: {axis: C}}\n" +
                               "  - {name: B, axes: [X2, C1], spindles: [S2]}\n",
                           &what),
            "channels[0].normal.axis");
  EXPECT_NE(what.find("channel A programs no axis C"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], normal: {axis: "
                           "X}}\n" +
                           two),
            "channels[0].normal.axis");
  EXPECT_EQ(rejection_path(base +
                           "channels:\n  - {name: A, axes: [X1, Z1, C1], normal: {axis: "
                           "C, feed: 0}}\n" +
                           two),
            "channels[0].normal.feed");
}

// Inclined-axis control (params 5680.1, 5690-5692), per channel: two linear axes it programs
// and an angle within -90..90.
TEST(MachineConfig, InclinedAxisControlOfAChannel) {
  const std::string base = kMillTurn;
  const std::string two = "  - {name: B, axes: [X2], spindles: [S2]}\n";
  const std::string a = "channels:\n  - {name: A, axes: [X1, Z1, C1], inclined: ";
  const MachineConfig plain =
      parse_machine_yaml(base + "channels:\n  - {name: A, axes: [X1, Z1, C1]}\n" + two);
  EXPECT_EQ(plain.channels[0].inclined_axis, 0);  // off
  const MachineConfig set =
      parse_machine_yaml(base + a + "{axis: X, orthogonal: Z, angle: -30}}\n" + two);
  EXPECT_EQ(set.channels[0].inclined_axis, 'X');
  EXPECT_EQ(set.channels[0].inclined_orthogonal, 'Z');
  EXPECT_DOUBLE_EQ(set.channels[0].inclined_degrees, -30.0);
  std::string what;
  EXPECT_EQ(rejection_path(base + a + "{axis: X, orthogonal: C, angle: 30}}\n" + two, &what),
            "channels[0].inclined.orthogonal");
  EXPECT_EQ(rejection_path(base + a + "{axis: Y, orthogonal: Z, angle: 30}}\n" + two, &what),
            "channels[0].inclined.axis");
  EXPECT_NE(what.find("channel A programs no axis Y"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(base + a + "{axis: X, orthogonal: X, angle: 30}}\n" + two),
            "channels[0].inclined.orthogonal");
  EXPECT_EQ(rejection_path(base + a + "{axis: X, orthogonal: Z, angle: 90}}\n" + two),
            "channels[0].inclined.angle");
  EXPECT_EQ(rejection_path(base + a + "{axis: X, orthogonal: Z}}\n" + two),
            "channels[0].inclined.angle");
}

// A linear axis under a rotary address (a lathe's linear B) is no polar rotary axis.
TEST(MachineConfig, PolarRotaryAxisMustBeRotary) {
  std::string what;
  EXPECT_EQ(rejection_path(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
axes:
  - {name: X, address: X, bus: b, node_id: 1}
  - {name: B, address: B, bus: b, node_id: 2}
channels: [{name: C, axes: [X, B], polar: {linear: X, rotary: B}}]
)",
                           &what),
            "channels[0].polar.rotary");
  EXPECT_NE(what.find("axis B (address B) is not rotary"), std::string::npos) << what;
}

TEST(MachineConfig, HomingKeysAndTheirWeightOnTheBus) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][0]["homing"]["method"] = 37;
    r["axes"][0]["homing"]["offset"] = -12.5;
  }));
  const AxisConfig& x = config.axes[0];
  EXPECT_TRUE(x.has_homing);
  EXPECT_EQ(x.homing_method, 37);
  EXPECT_DOUBLE_EQ(x.home_offset, -12.5);
  EXPECT_FALSE(config.axes[1].has_homing);
  EXPECT_EQ(axis_bits_per_cycle(x), 2 * can_frame_bits(7));
  EXPECT_EQ(axis_bits_per_cycle(config.axes[1]), 2 * can_frame_bits(6));
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][0]["homing"]["method"] = 38; })),
            "axes[0].homing.method");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][0]["homing"]["speed"] = 3; })),
            "axes[0].homing.speed");
}

// G160: an axis's torque limit on the bus (torque_skip) and the simulated drive's contact.
TEST(MachineConfig, TorqueSkipAndTheDrivesContact) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][1]["torque_skip"] = true;
    r["axes"][1]["drive"]["contact"]["at"] = -150.0;
    r["axes"][1]["drive"]["contact"]["blocks"] = "below";
  }));
  const AxisConfig& z = config.axes[1];
  EXPECT_TRUE(z.torque_skip);
  EXPECT_FALSE(config.axes[0].torque_skip);
  EXPECT_DOUBLE_EQ(z.drive.contact_at, -150.0);
  EXPECT_EQ(z.drive.contact_side, -1);
  EXPECT_EQ(config.axes[0].drive.contact_side, 0);
  // RPDO2 (0x6072) and TPDO2 (0x6077), 2 bytes each, beside the axis's two PDOs.
  EXPECT_EQ(tpdo2_bytes(z), 2);
  EXPECT_EQ(axis_bits_per_cycle(z), 2 * can_frame_bits(6) + 2 * can_frame_bits(2));
  // Not on a spindle, beside a touch probe or a tpdo2 that maps the torque or leaves no room.
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["axes"][1]["tpdo2"].push_back("torque_actual");
              r["axes"][1]["torque_skip"] = true;
            })),
            "axes[1].torque_skip");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["axes"][1]["tpdo2"].push_back("velocity_actual");
              r["axes"][1]["tpdo2"].push_back("following_error_actual");
              r["axes"][1]["torque_skip"] = true;
            })),
            "axes[1].torque_skip");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["axes"][1]["touch_probe"]["input"] = 13;
              r["axes"][1]["torque_skip"] = true;
            })),
            "axes[1].torque_skip");
  std::string what;
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
                             r["axes"][1]["drive"]["contact"]["at"] = 1.0;
                             r["axes"][1]["drive"]["contact"]["blocks"] = "left";
                           }),
                           &what),
            "axes[1].drive.contact.blocks");
  EXPECT_NE(what.find("the contact blocks the load above or below its position"), std::string::npos)
      << what;
  EXPECT_EQ(rejection_path(mutated(
                [](YAML::Node& r) { r["axes"][1]["drive"]["contact"]["blocks"] = "below"; })),
            "axes[1].drive.contact.at");
}

// G31.8: the simulated drive's probe passing teeth.
TEST(MachineConfig, TheDrivesProbeMayPassTeeth) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][1]["drive"]["probe"]["at"] = -10.0;
    r["axes"][1]["drive"]["probe"]["on"] = "below";
    r["axes"][1]["drive"]["probe"]["teeth"]["pitch"] = 2.0;
    r["axes"][1]["drive"]["probe"]["teeth"]["width"] = 1.0;
    r["axes"][1]["drive"]["probe"]["teeth"]["count"] = 3;
  }));
  const DriveSimConfig& z = config.axes[1].drive;
  EXPECT_DOUBLE_EQ(z.probe_at, -10.0);
  EXPECT_EQ(z.probe_side, -1);
  EXPECT_DOUBLE_EQ(z.probe_pitch, 2.0);
  EXPECT_DOUBLE_EQ(z.probe_width, 1.0);
  EXPECT_EQ(z.probe_count, 3);
  EXPECT_DOUBLE_EQ(config.axes[0].drive.probe_pitch, 0.0);  // no teeth: one face
  const auto teeth = [](double pitch, double width) {
    return mutated([pitch, width](YAML::Node& r) {
      r["axes"][1]["drive"]["probe"]["at"] = -10.0;
      r["axes"][1]["drive"]["probe"]["on"] = "below";
      r["axes"][1]["drive"]["probe"]["teeth"]["pitch"] = pitch;
      r["axes"][1]["drive"]["probe"]["teeth"]["width"] = width;
      r["axes"][1]["drive"]["probe"]["teeth"]["count"] = 3;
    });
  };
  for (const auto& [pitch, width] :
       {std::pair{2.0, 2.0}, std::pair{2.0, 0.0}, std::pair{0.0, 1.0}}) {
    EXPECT_EQ(rejection_path(teeth(pitch, width)), "axes[1].drive.probe.teeth.pitch")
        << pitch << " " << width;
  }
}

// G31 P98/P99: an axis's load ratio (param 5511), only where the drive takes a torque limit.
TEST(MachineConfig, SkipLoadIsTheLoadRatioOfAnAxisWithATorqueLimit) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][1]["torque_skip"] = true;
    r["axes"][1]["skip_load"] = 40.0;
  }));
  EXPECT_DOUBLE_EQ(config.axes[1].skip_load, 40.0);
  EXPECT_DOUBLE_EQ(config.axes[0].skip_load, 0.0);
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][1]["skip_load"] = 40.0; })),
            "axes[1].skip_load");
  for (const double bad : {0.0, -5.0, 1000.5}) {
    EXPECT_EQ(rejection_path(mutated([bad](YAML::Node& r) {
                r["axes"][1]["torque_skip"] = true;
                r["axes"][1]["skip_load"] = bad;
              })),
              "axes[1].skip_load")
        << bad;
  }
}

// G10 L14 P10-P12: an axis's torque mode needs its drive's torque limit (torque_skip); its
// mapping is counted in the bus load; param 5521 is the axis's torque_mode_speed.
TEST(MachineConfig, TorqueModeNeedsTorqueSkipAndIsCountedInTheBusLoad) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["machine"]["cycle_us"] = 2000;  // at 1 ms the two axes would take 75.5 % of the bus
    r["axes"][1]["torque_skip"] = true;
    r["axes"][1]["torque_mode"] = true;
    r["axes"][1]["torque_mode_speed"] = 300.0;
  }));
  const AxisConfig& z = config.axes[1];
  EXPECT_TRUE(z.torque_mode);
  EXPECT_DOUBLE_EQ(z.torque_mode_speed, 300.0);
  EXPECT_FALSE(config.axes[0].torque_mode);
  EXPECT_DOUBLE_EQ(config.axes[0].torque_mode_speed, 0.0);
  // The mode in RPDO1/TPDO1 (7 bytes), RPDO2 with 0x6072, 0x6071 and 0x6080 (8), TPDO2 0x6077.
  EXPECT_EQ(axis_bits_per_cycle(z), 2 * can_frame_bits(7) + can_frame_bits(8) + can_frame_bits(2));
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][1]["torque_mode"] = true; })),
            "axes[1].torque_mode");
  std::string what;
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
                             r["axes"][1]["torque_skip"] = true;
                             r["axes"][1]["torque_mode"] = true;
                             r["axes"][1]["homing"]["method"] = 35;
                           }),
                           &what),
            "axes[1].torque_mode");
  EXPECT_NE(what.find("homing"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["axes"][1]["torque_skip"] = true;
              r["axes"][1]["torque_mode_speed"] = 300.0;
            })),
            "axes[1].torque_mode_speed");
  for (const double bad : {0.0, -5.0, 100000.5}) {
    EXPECT_EQ(rejection_path(mutated([bad](YAML::Node& r) {
                r["axes"][1]["torque_skip"] = true;
                r["axes"][1]["torque_mode"] = true;
                r["axes"][1]["torque_mode_speed"] = bad;
              })),
              "axes[1].torque_mode_speed")
        << bad;
  }
}

// G10 L14 P7/P8: the channel's params 5100.2-5100.4/5113 and 5200.4-5200.6/5251 (decision 162).
TEST(MachineConfig, TheChannelsOverloadSaysWhatADrillingOrTappingOverloadDoes) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["channels"][0]["overload"]["drilling"]["retract"] = true;
    r["channels"][0]["overload"]["drilling"]["alarm"] = true;
    r["channels"][0]["overload"]["drilling"]["variable"] = 120;
    r["channels"][0]["overload"]["tapping"]["retract"] = true;
    r["channels"][0]["overload"]["tapping"]["retry"] = true;
  }));
  const ChannelConfig& ch = config.channels[0];
  EXPECT_TRUE(ch.drill_overload.retract);
  EXPECT_FALSE(ch.drill_overload.retry);
  EXPECT_TRUE(ch.drill_overload.alarm);
  EXPECT_EQ(ch.drill_overload.variable, 120);
  EXPECT_TRUE(ch.tap_overload.retract);
  EXPECT_TRUE(ch.tap_overload.retry);
  EXPECT_FALSE(ch.tap_overload.alarm);
  EXPECT_EQ(ch.tap_overload.variable, 0);
  const MachineConfig none = parse_machine_yaml(mutated([](YAML::Node&) {}));
  EXPECT_FALSE(none.channels[0].drill_overload.retract);  // the parameters' 0
  EXPECT_EQ(rejection_path(mutated(
                [](YAML::Node& r) { r["channels"][0]["overload"]["drilling"]["variable"] = 0; })),
            "channels[0].overload.drilling.variable");
  EXPECT_EQ(rejection_path(mutated(
                [](YAML::Node& r) { r["channels"][0]["overload"]["boring"]["retract"] = true; })),
            "channels[0].overload.boring");
}

// Param 5522: what the drive's torque objects count as 1000 per mille (decision 164).
TEST(MachineConfig, TheTorqueScaleIsParam5522AndNeedsTheDrivesTorque) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["machine"]["cycle_us"] = 2000;
    r["axes"][1]["torque_skip"] = true;
    r["axes"][1]["torque_scale"] = 300.0;
  }));
  EXPECT_DOUBLE_EQ(config.axes[1].torque_scale, 300.0);
  EXPECT_DOUBLE_EQ(config.axes[0].torque_scale, 100.0);  // CiA 402: of the rated torque
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][1]["torque_scale"] = 300.0; })),
            "axes[1].torque_scale");
  for (const double bad : {0.0, 1000.5}) {
    EXPECT_EQ(rejection_path(mutated([bad](YAML::Node& r) {
                r["axes"][1]["torque_skip"] = true;
                r["axes"][1]["torque_scale"] = bad;
              })),
              "axes[1].torque_scale")
        << bad;
  }
}

// G160 without P and Q: the channel's params 5515/5516.
TEST(MachineConfig, TheChannelsTorqueSkipIsWhatG160TakesWithoutPAndQ) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["channels"][0]["torque_skip"]["limit"] = 80.0;
    r["channels"][0]["torque_skip"]["deviation"] = 0.5;
  }));
  EXPECT_DOUBLE_EQ(config.channels[0].torque_skip_limit, 80.0);
  EXPECT_DOUBLE_EQ(config.channels[0].torque_skip_deviation, 0.5);
  const MachineConfig none = parse_machine_yaml(mutated([](YAML::Node&) {}));
  EXPECT_DOUBLE_EQ(none.channels[0].torque_skip_limit, 0.0);
  EXPECT_DOUBLE_EQ(none.channels[0].torque_skip_deviation, 0.0);
  for (const double bad : {0.0, 1001.0}) {
    EXPECT_EQ(rejection_path(mutated(
                  [bad](YAML::Node& r) { r["channels"][0]["torque_skip"]["limit"] = bad; })),
              "channels[0].torque_skip.limit")
        << bad;
  }
  EXPECT_EQ(rejection_path(mutated(
                [](YAML::Node& r) { r["channels"][0]["torque_skip"]["deviation"] = -0.1; })),
            "channels[0].torque_skip.deviation");
  EXPECT_EQ(
      rejection_path(mutated([](YAML::Node& r) { r["channels"][0]["torque_skip"]["force"] = 1; })),
      "channels[0].torque_skip.force");
}

TEST(MachineConfig, CanopenSettingsAndObjectDefaults) {
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][0]["heartbeat_ms"] = 50;
    r["axes"][0]["quick_stop_deceleration"] = 2500;
    r["axes"][0]["tpdo2"].push_back("velocity_actual");
    r["axes"][0]["tpdo2"].push_back("following_error_actual");
    YAML::Node o;
    o["index"] = "0x6085";
    o["value"] = 30000000;
    r["axes"][0]["drive"]["objects"].push_back(o);
  }));
  const AxisConfig& x = config.axes[0];
  EXPECT_EQ(x.heartbeat_ms, 50);
  EXPECT_DOUBLE_EQ(x.quick_stop_deceleration, 2500.0);
  EXPECT_TRUE(x.tpdo2_velocity);
  EXPECT_TRUE(x.tpdo2_following_error);
  ASSERT_EQ(x.drive.objects.size(), 1U);
  EXPECT_EQ(x.drive.objects[0].index, 0x6085);
  EXPECT_EQ(x.drive.objects[0].sub, 0);
  EXPECT_EQ(x.drive.objects[0].value, 30000000);
  EXPECT_EQ(config.axes[1].heartbeat_ms, 100);  // the default
  // TPDO2 with both objects: one 8-byte frame more per cycle.
  EXPECT_EQ(axis_bits_per_cycle(x), 2 * can_frame_bits(6) + can_frame_bits(8));

  EXPECT_EQ(
      rejection_path(mutated([](YAML::Node& r) { r["axes"][0]["tpdo2"].push_back("torque"); })),
      "axes[0].tpdo2[0]");
  // The torque (2 bytes) fits beside one of the others, not both.
  const MachineConfig loaded = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["axes"][0]["tpdo2"].push_back("velocity_actual");
    r["axes"][0]["tpdo2"].push_back("torque_actual");
    r["axes"][0]["drive"]["rated_torque"] = 4.5;
  }));
  EXPECT_TRUE(loaded.axes[0].tpdo2_torque);
  EXPECT_DOUBLE_EQ(loaded.axes[0].drive.rated_torque, 4.5);
  EXPECT_EQ(tpdo2_bytes(loaded.axes[0]), 6);
  EXPECT_EQ(axis_bits_per_cycle(loaded.axes[0]), 2 * can_frame_bits(6) + can_frame_bits(6));
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              for (const char* o : {"velocity_actual", "following_error_actual", "torque_actual"}) {
                r["axes"][0]["tpdo2"].push_back(o);
              }
            })),
            "axes[0].tpdo2");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["axes"][0]["heartbeat_ms"] = 70000; })),
            "axes[0].heartbeat_ms");
  for (const char* bad : {"6085", "0x60", "0xZZZZ", "0x0FFF"}) {
    EXPECT_EQ(rejection_path(mutated([&](YAML::Node& r) {
                YAML::Node o;
                o["index"] = bad;
                o["value"] = 1;
                r["axes"][0]["drive"]["objects"].push_back(o);
              })),
              "axes[0].drive.objects[0].index")
        << bad;
  }
}

TEST(MachineConfig, TheProgramDirectoryIsFoundBesideTheMachineFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mcnc-progdir-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "progs");
  const std::string text = mutated([](YAML::Node& r) { r["machine"]["program_dir"] = "progs"; });
  std::ofstream(dir / "m.yaml") << text;
  const MachineConfig config = load_machine_file((dir / "m.yaml").string());
  EXPECT_EQ(config.program_dir, (dir / "progs").lexically_normal().string());
  std::filesystem::remove(dir / "progs");
  try {
    (void)load_machine_file((dir / "m.yaml").string());
    ADD_FAILURE() << "a missing program directory must be rejected";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "machine.program_dir");
  }
  std::filesystem::remove_all(dir);
}

TEST(MachineConfig, MotionAndLimitKeys) {
  const MachineConfig config = parse_machine_yaml(R"(
machine: {name: m}
buses: [{name: b, uri: "socketcan:can0", sync_producer: A}]
channels: [{name: C, axes: [A], motion: {lookahead_blocks: 1000, path_tolerance: 0.05, profile: trapezoid, rapid: axis}}]
axes: [{name: A, address: X, bus: b, node_id: 1, jerk: 20000, soft_limits: [-120.5, 3], following_error_limit: 0.8}]
)");
  const AxisConfig& a = config.axes[0];
  EXPECT_DOUBLE_EQ(a.jerk, 20000.0);
  EXPECT_TRUE(a.has_soft_limits);
  EXPECT_DOUBLE_EQ(a.soft_limit_min, -120.5);
  EXPECT_DOUBLE_EQ(a.soft_limit_max, 3.0);
  EXPECT_DOUBLE_EQ(a.following_error_limit, 0.8);
  const ChannelMotionConfig& m = config.channels[0].motion;
  EXPECT_EQ(m.lookahead_blocks, 1000);
  EXPECT_DOUBLE_EQ(m.path_tolerance, 0.05);
  EXPECT_FALSE(m.jerk_limited);
  EXPECT_FALSE(m.rapid_interpolated);
  const auto rejects = [](const std::string& text, const std::string& path) {
    try {
      (void)parse_machine_yaml(text);
      ADD_FAILURE() << "accepted: " << path;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key_path(), path) << e.what();
    }
  };
  const std::string head =
      "machine: {name: m}\nbuses: [{name: b, uri: \"socketcan:can0\", sync_producer: A}]\n";
  rejects(head +
              "channels: [{name: C, axes: [A]}]\naxes: [{name: A, address: X, bus: b, node_id: 1, "
              "soft_limits: [3, -3]}]\n",
          "axes[0].soft_limits");
  rejects(head +
              "channels: [{name: C, axes: [A], motion: {profile: smooth}}]\naxes: [{name: A, "
              "address: X, bus: b, node_id: 1}]\n",
          "channels[0].motion.profile");
  rejects(head +
              "channels: [{name: C, axes: [A], motion: {lookahead_blocks: 1}}]\naxes: [{name: A, "
              "address: X, bus: b, node_id: 1}]\n",
          "channels[0].motion.lookahead_blocks");
}

TEST(MachineConfig, IdsChannelsAndLookups) {
  const MachineConfig config = parse_machine_yaml(kBase);
  ASSERT_EQ(config.axes.size(), 4u);
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    EXPECT_EQ(config.axes[i].id, static_cast<int>(i) + 1);
  }
  EXPECT_EQ(config.channels[1].id, 2);
  EXPECT_EQ(config.axes[2].channel, "CH2");
  EXPECT_EQ(config.axes[3].channel, "CH2");
  EXPECT_DOUBLE_EQ(config.axes[0].drive.max_velocity, 300.0);
  EXPECT_DOUBLE_EQ(config.axes[0].drive.time_constant_s, 0.004);  // default kept beside it

  ASSERT_NE(config.find_axis("Z2"), nullptr);
  EXPECT_EQ(config.find_axis("Z2")->id, 4);
  EXPECT_EQ(config.find_axis("Q9"), nullptr);
  ASSERT_NE(config.find_channel("CH2"), nullptr);
  EXPECT_EQ(config.find_channel("CH2")->id, 2);
  EXPECT_EQ(config.find_channel("CH3"), nullptr);
  ASSERT_NE(config.find_bus("can1"), nullptr);
  EXPECT_EQ(config.find_bus("can1")->uri, "socketcan:can1");
  EXPECT_EQ(config.find_bus("can2"), nullptr);
}

TEST(MachineConfig, AcceptedVariants) {
  // Same node id on different buses, same address in different channels (the base has both).
  EXPECT_EQ(rejection_path(kBase), "<accepted>");
  // Range ends are inclusive.
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["machine"]["cycle_us"] = 100000;
              r["machine"]["deadline_cycles"] = 1000;
              r["machine"]["domain"] = 232;
              r["axes"][1]["node_id"] = 127;
            })),
            "<accepted>");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["machine"]["deadline_cycles"] = 1;
              r["buses"][0]["uri"] = "udp:224.0.0.1:1";
            })),
            "<accepted>");
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["buses"][0]["uri"] = "udp:239.255.255.255:65535";
              r["buses"][1]["uri"] = "socketcan:abcdefghijklmno";  // 15 characters
            })),
            "<accepted>");
  // Numbers may be written with an exponent or a sign.
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) {
              r["axes"][0]["acceleration"] = "1.5e3";
              r["axes"][0]["in_position"] = "+0.001";
              r["axes"][0]["diameter"] = "True";
            })),
            "<accepted>");
}

struct RejectCase {
  const char* label;
  Mutation mutate;
  const char* key_path;
};

// Keeps gtest from printing the case as raw bytes.
void PrintTo(const RejectCase& value, std::ostream* out) {
  *out << value.label;
}

class Rejects : public testing::TestWithParam<RejectCase> {};

TEST_P(Rejects, WithKeyPath) {
  std::string what;
  EXPECT_EQ(rejection_path(mutated(GetParam().mutate), &what), GetParam().key_path) << what;
}

std::string case_name(const testing::TestParamInfo<RejectCase>& info) {
  return info.param.label;
}

// Unknown keys, at every level.
INSTANTIATE_TEST_SUITE_P(
    UnknownKey, Rejects,
    testing::Values(
        RejectCase{"TopLevel", [](YAML::Node& r) { r["spindles"] = 1; }, "spindles"},
        RejectCase{"Machine", [](YAML::Node& r) { r["machine"]["cycle"] = 1; }, "machine.cycle"},
        RejectCase{"Bus", [](YAML::Node& r) { r["buses"][1]["baud"] = 1; }, "buses[1].baud"},
        RejectCase{"Channel", [](YAML::Node& r) { r["channels"][0]["mode"] = 1; },
                   "channels[0].mode"},
        RejectCase{"Axis", [](YAML::Node& r) { r["axes"][1]["accel"] = 1; }, "axes[1].accel"},
        RejectCase{"Drive", [](YAML::Node& r) { r["axes"][0]["drive"]["tau"] = 1; },
                   "axes[0].drive.tau"}),
    case_name);

// Missing required keys.
INSTANTIATE_TEST_SUITE_P(
    MissingKey, Rejects,
    testing::Values(
        RejectCase{"Machine", [](YAML::Node& r) { r.remove("machine"); }, "machine"},
        RejectCase{"Buses", [](YAML::Node& r) { r.remove("buses"); }, "buses"},
        RejectCase{"Channels", [](YAML::Node& r) { r.remove("channels"); }, "channels"},
        RejectCase{"Axes", [](YAML::Node& r) { r.remove("axes"); }, "axes"},
        RejectCase{"MachineName", [](YAML::Node& r) { r["machine"].remove("name"); },
                   "machine.name"},
        RejectCase{"BusName", [](YAML::Node& r) { r["buses"][1].remove("name"); }, "buses[1].name"},
        RejectCase{"BusUri", [](YAML::Node& r) { r["buses"][0].remove("uri"); }, "buses[0].uri"},
        RejectCase{"SyncProducer", [](YAML::Node& r) { r["buses"][0].remove("sync_producer"); },
                   "buses[0].sync_producer"},
        RejectCase{"ChannelName", [](YAML::Node& r) { r["channels"][1].remove("name"); },
                   "channels[1].name"},
        RejectCase{"ChannelAxes", [](YAML::Node& r) { r["channels"][0].remove("axes"); },
                   "channels[0].axes"},
        RejectCase{"AxisName", [](YAML::Node& r) { r["axes"][2].remove("name"); }, "axes[2].name"},
        RejectCase{"AxisAddress", [](YAML::Node& r) { r["axes"][1].remove("address"); },
                   "axes[1].address"},
        RejectCase{"AxisBus", [](YAML::Node& r) { r["axes"][0].remove("bus"); }, "axes[0].bus"},
        RejectCase{"AxisNodeId", [](YAML::Node& r) { r["axes"][3].remove("node_id"); },
                   "axes[3].node_id"}),
    case_name);

// Wrong types.
INSTANTIATE_TEST_SUITE_P(
    WrongType, Rejects,
    testing::Values(
        RejectCase{"StringForInteger", [](YAML::Node& r) { r["machine"]["cycle_us"] = "fast"; },
                   "machine.cycle_us"},
        RejectCase{"FractionForInteger", [](YAML::Node& r) { r["axes"][1]["node_id"] = 1.5; },
                   "axes[1].node_id"},
        RejectCase{"ExponentForInteger", [](YAML::Node& r) { r["buses"][0]["bitrate"] = "1e6"; },
                   "buses[0].bitrate"},
        RejectCase{"StringForNumber", [](YAML::Node& r) { r["axes"][0]["rapid_rate"] = "high"; },
                   "axes[0].rapid_rate"},
        RejectCase{"InfinityForNumber", [](YAML::Node& r) { r["axes"][0]["max_feed"] = "inf"; },
                   "axes[0].max_feed"},
        RejectCase{"NullForNumber",
                   [](YAML::Node& r) { r["axes"][0]["acceleration"] = YAML::Node(); },
                   "axes[0].acceleration"},
        RejectCase{"ListForNumber",
                   [](YAML::Node& r) {
                     YAML::Node list(YAML::NodeType::Sequence);
                     list.push_back(1);
                     r["axes"][0]["drive"]["max_velocity"] = list;
                   },
                   "axes[0].drive.max_velocity"},
        RejectCase{"WordForBoolean", [](YAML::Node& r) { r["axes"][0]["diameter"] = "yes"; },
                   "axes[0].diameter"},
        RejectCase{"MapForList",
                   [](YAML::Node& r) {
                     r.remove("channels");
                     r["channels"]["CH1"] = "X1";
                   },
                   "channels"},
        RejectCase{"ScalarForList", [](YAML::Node& r) { r["channels"][0]["axes"] = "X1"; },
                   "channels[0].axes"},
        RejectCase{"ListForMap",
                   [](YAML::Node& r) {
                     r.remove("machine");
                     r["machine"].push_back("twin");
                   },
                   "machine"},
        RejectCase{"ScalarForMap", [](YAML::Node& r) { r["axes"][0]["drive"] = 5; },
                   "axes[0].drive"},
        RejectCase{"ScalarForListItem", [](YAML::Node& r) { r["axes"][1] = "Z1"; }, "axes[1]"},
        RejectCase{"ListForName",
                   [](YAML::Node& r) {
                     r["axes"][0]["name"] = YAML::Node(YAML::NodeType::Sequence);
                     r["axes"][0]["name"].push_back("X1");
                   },
                   "axes[0].name"},
        RejectCase{"MapForAxisReference",
                   [](YAML::Node& r) {
                     YAML::Node map;
                     map["name"] = "Z1";
                     r["channels"][0]["axes"][1] = map;
                   },
                   "channels[0].axes[1]"}),
    case_name);

// Values out of range or malformed.
INSTANTIATE_TEST_SUITE_P(
    OutOfRange, Rejects,
    testing::Values(
        RejectCase{"CycleTooShort", [](YAML::Node& r) { r["machine"]["cycle_us"] = 99; },
                   "machine.cycle_us"},
        RejectCase{"CycleTooLong", [](YAML::Node& r) { r["machine"]["cycle_us"] = 100001; },
                   "machine.cycle_us"},
        RejectCase{"DeadlineZero", [](YAML::Node& r) { r["machine"]["deadline_cycles"] = 0; },
                   "machine.deadline_cycles"},
        RejectCase{"DeadlineTooLarge",
                   [](YAML::Node& r) { r["machine"]["deadline_cycles"] = 1001; },
                   "machine.deadline_cycles"},
        RejectCase{"DomainNegative", [](YAML::Node& r) { r["machine"]["domain"] = -1; },
                   "machine.domain"},
        RejectCase{"DomainTooLarge", [](YAML::Node& r) { r["machine"]["domain"] = 233; },
                   "machine.domain"},
        RejectCase{"IntegerOverflow",
                   [](YAML::Node& r) { r["machine"]["domain"] = "99999999999999999999999"; },
                   "machine.domain"},
        RejectCase{"BitrateTooLow", [](YAML::Node& r) { r["buses"][1]["bitrate"] = 9999; },
                   "buses[1].bitrate"},
        RejectCase{"BitrateTooHigh", [](YAML::Node& r) { r["buses"][1]["bitrate"] = 1000001; },
                   "buses[1].bitrate"},
        RejectCase{"NodeIdZero", [](YAML::Node& r) { r["axes"][2]["node_id"] = 0; },
                   "axes[2].node_id"},
        RejectCase{"NodeIdTooLarge", [](YAML::Node& r) { r["axes"][2]["node_id"] = 128; },
                   "axes[2].node_id"},
        RejectCase{"CountsZero", [](YAML::Node& r) { r["axes"][0]["counts_per_unit"] = 0; },
                   "axes[0].counts_per_unit"},
        RejectCase{"RapidNegative", [](YAML::Node& r) { r["axes"][0]["rapid_rate"] = -1; },
                   "axes[0].rapid_rate"},
        RejectCase{"FeedZero", [](YAML::Node& r) { r["axes"][1]["max_feed"] = 0; },
                   "axes[1].max_feed"},
        RejectCase{"AccelerationZero", [](YAML::Node& r) { r["axes"][1]["acceleration"] = 0.0; },
                   "axes[1].acceleration"},
        RejectCase{"InPositionZero", [](YAML::Node& r) { r["axes"][1]["in_position"] = 0; },
                   "axes[1].in_position"},
        RejectCase{"TimeConstantZero",
                   [](YAML::Node& r) { r["axes"][0]["drive"]["time_constant_s"] = 0; },
                   "axes[0].drive.time_constant_s"},
        RejectCase{"DriveVelocityNegative",
                   [](YAML::Node& r) { r["axes"][0]["drive"]["max_velocity"] = -5; },
                   "axes[0].drive.max_velocity"},
        RejectCase{"QuickStopZero",
                   [](YAML::Node& r) { r["axes"][0]["drive"]["quick_stop_decel"] = 0; },
                   "axes[0].drive.quick_stop_decel"},
        RejectCase{"AddressUnknown", [](YAML::Node& r) { r["axes"][1]["address"] = "Q"; },
                   "axes[1].address"},
        RejectCase{"AddressIncremental", [](YAML::Node& r) { r["axes"][1]["address"] = "W"; },
                   "axes[1].address"},
        RejectCase{"AddressLowercase", [](YAML::Node& r) { r["axes"][1]["address"] = "z"; },
                   "axes[1].address"},
        RejectCase{"AddressTwoLetters", [](YAML::Node& r) { r["axes"][1]["address"] = "ZZ"; },
                   "axes[1].address"},
        RejectCase{"TypeUnknown", [](YAML::Node& r) { r["axes"][1]["type"] = "turret"; },
                   "axes[1].type"},
        RejectCase{"RotaryInDiameter", [](YAML::Node& r) { r["axes"][0]["type"] = "rotary"; },
                   "axes[0].diameter"},
        RejectCase{"NameWithSpace", [](YAML::Node& r) { r["channels"][0]["name"] = "CH 1"; },
                   "channels[0].name"},
        RejectCase{"NameEmpty", [](YAML::Node& r) { r["machine"]["name"] = ""; }, "machine.name"},
        RejectCase{"NameTooLong",
                   [](YAML::Node& r) { r["machine"]["name"] = std::string(32, 'm'); },
                   "machine.name"},
        RejectCase{"UriScheme", [](YAML::Node& r) { r["buses"][0]["uri"] = "tcp:1.2.3.4:5"; },
                   "buses[0].uri"},
        RejectCase{"UriNoPort", [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:239.255.42.1"; },
                   "buses[0].uri"},
        RejectCase{"UriNotMulticast",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:192.168.1.10:42000"; },
                   "buses[0].uri"},
        RejectCase{"UriAboveMulticast",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:240.0.0.1:42000"; },
                   "buses[0].uri"},
        RejectCase{"UriShortAddress",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:239.255.42:42000"; },
                   "buses[0].uri"},
        RejectCase{"UriOctetTooLarge",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:239.256.42.1:42000"; },
                   "buses[0].uri"},
        RejectCase{"UriPortZero",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:239.255.42.1:0"; },
                   "buses[0].uri"},
        RejectCase{"UriPortTooLarge",
                   [](YAML::Node& r) { r["buses"][0]["uri"] = "udp:239.255.42.1:65536"; },
                   "buses[0].uri"},
        RejectCase{"UriEmptyIfname", [](YAML::Node& r) { r["buses"][1]["uri"] = "socketcan:"; },
                   "buses[1].uri"},
        RejectCase{"UriLongIfname",
                   [](YAML::Node& r) { r["buses"][1]["uri"] = "socketcan:abcdefghijklmnop"; },
                   "buses[1].uri"}),
    case_name);

// Inconsistencies between sections.
INSTANTIATE_TEST_SUITE_P(
    CrossCheck, Rejects,
    testing::Values(
        RejectCase{"DuplicateAxisName", [](YAML::Node& r) { r["axes"][3]["name"] = "X2"; },
                   "axes[3].name"},
        RejectCase{"DuplicateChannelName", [](YAML::Node& r) { r["channels"][1]["name"] = "CH1"; },
                   "channels[1].name"},
        RejectCase{"DuplicateBusName", [](YAML::Node& r) { r["buses"][1]["name"] = "can0"; },
                   "buses[1].name"},
        RejectCase{"DuplicateBusUri",
                   [](YAML::Node& r) { r["buses"][1]["uri"] = "udp:239.255.42.1:42000"; },
                   "buses[1].uri"},
        RejectCase{"NoBuses",
                   [](YAML::Node& r) { r["buses"] = YAML::Node(YAML::NodeType::Sequence); },
                   "buses"},
        RejectCase{"NoAxes",
                   [](YAML::Node& r) { r["axes"] = YAML::Node(YAML::NodeType::Sequence); }, "axes"},
        RejectCase{"NoChannels",
                   [](YAML::Node& r) { r["channels"] = YAML::Node(YAML::NodeType::Sequence); },
                   "channels"},
        RejectCase{
            "ChannelWithoutAxes",
            [](YAML::Node& r) { r["channels"][1]["axes"] = YAML::Node(YAML::NodeType::Sequence); },
            "channels[1].axes"},
        RejectCase{"AxisInNoChannel",
                   [](YAML::Node& r) {
                     r["channels"][1]["axes"] = YAML::Node(YAML::NodeType::Sequence);
                     r["channels"][1]["axes"].push_back("X2");
                   },
                   "axes[3]"},
        RejectCase{"SameAxisTwiceInChannel",
                   [](YAML::Node& r) { r["channels"][0]["axes"].push_back("X1"); },
                   "channels[0].axes[2]"},
        RejectCase{"UnknownAxisInChannel",
                   [](YAML::Node& r) { r["channels"][0]["axes"][1] = "Y1"; },
                   "channels[0].axes[1]"},
        RejectCase{"SameAddressInChannel", [](YAML::Node& r) { r["axes"][1]["address"] = "X"; },
                   "channels[0].axes[1]"},
        RejectCase{"UnknownBus", [](YAML::Node& r) { r["axes"][2]["bus"] = "can7"; },
                   "axes[2].bus"},
        RejectCase{"NodeIdTwiceOnBus", [](YAML::Node& r) { r["axes"][3]["node_id"] = 1; },
                   "axes[3].node_id"},
        RejectCase{"SyncProducerUnknown",
                   [](YAML::Node& r) { r["buses"][0]["sync_producer"] = "Y9"; },
                   "buses[0].sync_producer"},
        RejectCase{"SyncProducerOnOtherBus",
                   [](YAML::Node& r) { r["buses"][0]["sync_producer"] = "X2"; },
                   "buses[0].sync_producer"},
        RejectCase{"BusWithoutAxes",
                   [](YAML::Node& r) {
                     r["axes"][2]["bus"] = "can0";
                     r["axes"][2]["node_id"] = 3;
                     r["axes"][3]["bus"] = "can0";
                     r["axes"][3]["node_id"] = 4;
                     r["machine"]["cycle_us"] = 2000;  // four axes fit at 2 ms
                   },
                   "buses[1]"},
        RejectCase{"BusOverloaded",
                   [](YAML::Node& r) {
                     r["axes"][2]["bus"] = "can0";
                     r["axes"][2]["node_id"] = 3;
                     r["buses"][1]["sync_producer"] = "Z2";
                   },
                   "buses[0]"},
        RejectCase{"BusOverloadedAtLowBitrate",
                   [](YAML::Node& r) { r["buses"][1]["bitrate"] = 500000; }, "buses[1]"}),
    case_name);

TEST(MachineConfig, AxisInTwoChannelsNamesTheFirstChannel) {
  const std::string text = mutated([](YAML::Node& r) {
    r["channels"][1]["axes"] = YAML::Node(YAML::NodeType::Sequence);
    r["channels"][1]["axes"].push_back("X1");
    r["channels"][1]["axes"].push_back("X2");
    r["channels"][1]["axes"].push_back("Z2");
  });
  try {
    (void)parse_machine_yaml(text);
    FAIL() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key_path(), "channels[1].axes[0]");
    EXPECT_EQ(std::string(error.what())
                  .rfind("channels[1].axes[0]: axis X1 is already in channel CH1", 0),
              0u)
        << error.what();
  }
}

// kBase with its first `from` replaced by `to`, for cases a YAML::Node cannot express.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = kBase;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(MachineConfig, TextLevelRejections) {
  // A quoted number is a string.
  EXPECT_EQ(rejection_path(edited("cycle_us: 1000", "cycle_us: \"1000\"")), "machine.cycle_us");
  // A repeated key is an error, not "the last one wins".
  EXPECT_EQ(rejection_path(edited("name: twin", "name: twin\n  name: other")), "machine.name");
  // An empty value is not a default.
  EXPECT_EQ(rejection_path(edited("cycle_us: 1000", "cycle_us:")), "machine.cycle_us");
  // YAML 1.1 booleans are refused.
  EXPECT_EQ(rejection_path(edited("diameter: true", "diameter: on")), "axes[0].diameter");
  // Hexadecimal, octal and digit separators are refused.
  EXPECT_EQ(rejection_path(edited("cycle_us: 1000", "cycle_us: 0x3e8")), "machine.cycle_us");
  EXPECT_EQ(rejection_path(edited("cycle_us: 1000", "cycle_us: 0o1750")), "machine.cycle_us");
  EXPECT_EQ(rejection_path(edited("bitrate: 1000000", "bitrate: 1_000_000")), "buses[1].bitrate");
  // A flow list and a block list are the same thing.
  EXPECT_EQ(rejection_path(edited("axes: [X1, Z1]", "axes:\n      - X1\n      - Z1")),
            "<accepted>");
}

TEST(MachineConfig, WholeFileErrorsHaveAnEmptyKeyPath) {
  std::string what;
  EXPECT_EQ(rejection_path("machine:\n  name: [m\n", &what), "");
  EXPECT_NE(what.find("line "), std::string::npos) << what;
  EXPECT_NE(what.find("column "), std::string::npos) << what;
  EXPECT_EQ(rejection_path(""), "");
  EXPECT_EQ(rejection_path("# only a comment\n"), "");
  EXPECT_EQ(rejection_path("- machine\n"), "");
  EXPECT_EQ(rejection_path("plain text\n"), "");
  EXPECT_EQ(rejection_path(std::string(kBase) + "---\nmachine: {name: other}\n"), "");
}

TEST(MachineConfig, ErrorsGiveTheLine) {
  std::string what;
  EXPECT_EQ(rejection_path("machine:\n  name: m\n  cycle_us: 5\n", &what), "machine.cycle_us");
  EXPECT_NE(what.find("(line 3, column 13)"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(edited("node_id: 2", "node_id: 200"), &what), "axes[1].node_id");
  EXPECT_NE(what.find("(line 29, column 14)"), std::string::npos) << what;
}

class TempFile {
 public:
  explicit TempFile(const std::string& text)
      : path_(std::filesystem::temp_directory_path() /
              ("mcnc_config_test_" +
               std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml")) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  [[nodiscard]] std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

TEST(LoadMachineFile, MissingFileNamesThePath) {
  const std::string path = kSourceDir + "/tests/fixtures/machines/does_not_exist.yaml";
  try {
    (void)load_machine_file(path);
    FAIL() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key_path(), path);
  }
}

TEST(LoadMachineFile, SyntaxErrorNamesTheFileAndLine) {
  const TempFile file("machine:\n  name: m\n buses: [\n");
  try {
    (void)load_machine_file(file.path());
    FAIL() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key_path(), file.path());
    EXPECT_NE(std::string(error.what()).find("line "), std::string::npos) << error.what();
  }
}

TEST(LoadMachineFile, ValidationErrorKeepsTheKeyPath) {
  const TempFile file("machine:\n  name: m\n  deadline_cycles: 0\n");
  try {
    (void)load_machine_file(file.path());
    FAIL() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key_path(), "machine.deadline_cycles");
  }
}

std::string fixture_rejection(const std::string& name) {
  try {
    (void)load_machine_file(kSourceDir + "/tests/fixtures/machines/" + name);
  } catch (const ConfigError& error) {
    return error.key_path();
  }
  return "<accepted>";
}

TEST(LoadMachineFile, BadFixtures) {
  EXPECT_EQ(fixture_rejection("bad_two_channels.yaml"), "channels[1].axes[0]");
  EXPECT_EQ(fixture_rejection("bad_unknown_key.yaml"), "axes[1].acceleraton");
  EXPECT_EQ(fixture_rejection("bad_node_id.yaml"), "axes[1].node_id");
}

TEST(BusLoad, FrameBits) {
  EXPECT_EQ(can_frame_bits(0), 55);   // 47 + 0 + floor(33 / 4)
  EXPECT_EQ(can_frame_bits(1), 65);   // SYNC: 47 + 8 + floor(41 / 4)
  EXPECT_EQ(can_frame_bits(6), 115);  // PDO: 47 + 48 + floor(81 / 4)
  EXPECT_EQ(can_frame_bits(8), 135);  // 47 + 64 + floor(97 / 4)
  EXPECT_EQ(bus_bits_per_cycle(0), 65);
  EXPECT_EQ(bus_bits_per_cycle(2), 525);
  EXPECT_EQ(bus_bits_per_cycle(3), 755);
  EXPECT_DOUBLE_EQ(bus_load(2, 1000000, 1000), 0.525);
  EXPECT_DOUBLE_EQ(bus_load(3, 1000000, 2000), 0.3775);
  EXPECT_DOUBLE_EQ(bus_load(1, 0, 1000), 0.0);
}

TEST(BusLoad, LimitAtOneMegabit) {
  // 1 ms: 2 axes take 52.5 %, 3 take 75.5 %.
  EXPECT_EQ(rejection_path(text_with_axes(2, 1000, 1000000)), "<accepted>");
  EXPECT_EQ(rejection_path(text_with_axes(3, 1000, 1000000)), "buses[0]");
  // 2 ms: 5 axes take 60.75 %, 6 take 72.25 %.
  EXPECT_EQ(rejection_path(text_with_axes(5, 2000, 1000000)), "<accepted>");
  EXPECT_EQ(rejection_path(text_with_axes(6, 2000, 1000000)), "buses[0]");
  // 500 kbit/s at 2 ms is the same budget as 1 Mbit/s at 1 ms.
  EXPECT_EQ(rejection_path(text_with_axes(2, 2000, 500000)), "<accepted>");
  EXPECT_EQ(rejection_path(text_with_axes(3, 2000, 500000)), "buses[0]");
}

TEST(BusLoad, ExactlySeventyPercentIsAccepted) {
  // Two axes need 525 bits per cycle, exactly 70 % of 750 bits: 750000 bit/s at 1 ms.
  EXPECT_EQ(rejection_path(text_with_axes(2, 1000, 750000)), "<accepted>");
  EXPECT_EQ(rejection_path(text_with_axes(2, 1000, 749999)), "buses[0]");
}

// G140/G141 (spec dafeng §3.3): an exchange number (param 5660) names one axis machine-wide; a
// channel lists the axes of other channels it may acquire, each under a free address.
TEST(MachineConfig, ExchangeNumbersAndExchangeAxes) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: A1, address: A, type: rotary, bus: b, node_id: 2, exchange: 14}
  - {name: X2, address: X, bus: b, node_id: 3}
)";
  const MachineConfig config = parse_machine_yaml(
      base +
      "channels: [{name: C1, axes: [X1, A1]}, {name: C2, axes: [X2], exchange_axes: [A1]}]\n");
  EXPECT_EQ(config.find_axis("A1")->exchange, 14);
  EXPECT_EQ(config.find_axis("A1")->channel, "C1");  // its home stays channel 1
  EXPECT_EQ(config.channels[1].program_axes(), (std::vector<std::string>{"X2", "A1"}));
  EXPECT_EQ(config.channels[0].program_axes(), (std::vector<std::string>{"X1", "A1"}));

  const std::string two = "channels: [{name: C1, axes: [X1, A1]}, {name: C2, axes: [X2], ";
  EXPECT_EQ(rejection_path(base + two + "exchange_axes: [X1]}]\n"), "channels[1].exchange_axes[0]")
      << "X1 has no exchange number";
  EXPECT_EQ(rejection_path(base + two + "exchange_axes: [Q]}]\n"), "channels[1].exchange_axes[0]");
  EXPECT_EQ(rejection_path(base + "channels: [{name: C1, axes: [X1, A1], exchange_axes: [A1]}, "
                                  "{name: C2, axes: [X2]}]\n"),
            "channels[0].exchange_axes[0]")
      << "a channel's own axis";
  std::string same_number = base;
  same_number.replace(same_number.find("node_id: 3}"), 11, "node_id: 3, exchange: 14}");
  EXPECT_EQ(rejection_path(same_number + "channels: [{name: C1, axes: [X1, A1]}, "
                                         "{name: C2, axes: [X2]}]\n"),
            "axes[2].exchange");
  EXPECT_EQ(
      rejection_path(base + "  - {name: S1, type: spindle, bus: b, node_id: 4, exchange: 5}\n" +
                     "channels: [{name: C1, axes: [X1, A1], spindles: [S1]}, "
                     "{name: C2, axes: [X2]}]\n"),
      "axes[3].exchange");
}

// G51.4 (spec dafeng §3.2): `axis_sync` makes an axis a possible slave (param 5600.1) with an
// optional default master (5610) it may follow from power-on (5600.3 = 0). The master is an
// axis of the same kind that is no slave itself.
TEST(MachineConfig, AxisSyncSlavesAndTheirMasters) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X}]
channels: [{name: C1, axes: [X, Y, A]}, {name: C2, axes: [X2]}]
axes:
  - {name: X, address: X, bus: b, node_id: 1}
  - {name: A, address: A, type: rotary, bus: b, node_id: 2}
)";
  const MachineConfig config =
      parse_machine_yaml(base + "  - {name: Y, address: Y, bus: b, node_id: 3, axis_sync: {}}\n" +
                         "  - {name: X2, address: X, bus: b, node_id: 4, axis_sync: {master: X, "
                         "at_power_on: true}}\n");
  EXPECT_FALSE(config.find_axis("X")->sync_slave);
  EXPECT_TRUE(config.find_axis("Y")->sync_slave);
  EXPECT_EQ(config.find_axis("Y")->sync_master, 0);
  EXPECT_FALSE(config.find_axis("Y")->sync_at_power_on);
  EXPECT_EQ(config.find_axis("X2")->sync_master, 1);
  EXPECT_TRUE(config.find_axis("X2")->sync_at_power_on);

  const std::string y = "  - {name: Y, address: Y, bus: b, node_id: 3, axis_sync: {}}\n";
  auto x2 = [](const std::string& sync) {
    return "  - {name: X2, address: X, bus: b, node_id: 4, axis_sync: " + sync + "}\n";
  };
  EXPECT_EQ(rejection_path(base + y + x2("{master: Q}")), "axes[3].axis_sync.master");
  EXPECT_EQ(rejection_path(base + y + x2("{master: X2}")), "axes[3].axis_sync.master");
  EXPECT_EQ(rejection_path(base + y + x2("{master: A}")), "axes[3].axis_sync.master")
      << "a rotary master for a linear slave";
  EXPECT_EQ(rejection_path(base + y + x2("{master: Y}")), "axes[3].axis_sync.master")
      << "a slave does not lead";
  EXPECT_EQ(rejection_path(base + y + x2("{at_power_on: true}")), "axes[3].axis_sync")
      << "from power-on, but following whom?";
  EXPECT_EQ(rejection_path(base + y + x2("{master: X, speed: 3}")), "axes[3].axis_sync.speed");
  EXPECT_EQ(rejection_path(base + y +
                           "  - {name: X2, address: X, bus: b, node_id: 4, exchange: 3, "
                           "axis_sync: {}}\n"),
            "axes[3].axis_sync");
}

// Each process's DDS implementation: its own entry's, else the machine's, else none named.
TEST(MachineConfig, MiddlewareOfEachProcess) {
  EXPECT_EQ(parse_machine_yaml(kBase).middleware_of("CH1"), "");
  const MachineConfig config = parse_machine_yaml(mutated([](YAML::Node& r) {
    r["machine"]["middleware"] = "cyclonedds";
    r["channels"][1]["middleware"] = "fastdds";
    r["axes"][2]["middleware"] = "fastdds";
    r["machine"]["roudi"] = "running";
  }));
  EXPECT_EQ(config.middleware_of("CH1"), "cyclonedds");
  EXPECT_EQ(config.middleware_of("CH2"), "fastdds");
  EXPECT_EQ(config.middleware_of("X1"), "cyclonedds");
  EXPECT_EQ(config.middleware_of("X2"), "fastdds");
  EXPECT_EQ(config.middleware_of("launch"), "cyclonedds");
  EXPECT_TRUE(config.roudi_running);
  EXPECT_FALSE(parse_machine_yaml(kBase).roudi_running);
  std::string what;
  EXPECT_EQ(
      rejection_path(mutated([](YAML::Node& r) { r["axes"][1]["middleware"] = "opendds"; }), &what),
      "axes[1].middleware");
  EXPECT_NE(what.find("fastdds or cyclonedds"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(mutated([](YAML::Node& r) { r["machine"]["roudi"] = "maybe"; })),
            "machine.roudi");
}

}  // namespace
}  // namespace mcnc::config

namespace mcnc::config {
namespace {

// Param 1420 (spec dafeng §2.6.13): G114.1 groups name a master and a slave spindle.
TEST(MachineConfig, SpindleSyncGroups) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
  - {name: b2, uri: "socketcan:can1", sync_producer: X2}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, bus: b, node_id: 2}
  - {name: X2, address: X, bus: b2, node_id: 1}
  - {name: S2, type: spindle, bus: b2, node_id: 2}
channels: [{name: C1, axes: [X1], spindles: [S1]}, {name: C2, axes: [X2], spindles: [S2]}]
)";
  const MachineConfig config =
      parse_machine_yaml(base + "spindle_sync: [{group: 1, master: S1, slave: S2}]\n");
  ASSERT_EQ(config.spindle_sync.size(), 1U);
  EXPECT_EQ(config.spindle_sync[0].master, 2);
  EXPECT_EQ(config.spindle_sync[0].slave, 4);
  EXPECT_EQ(config.spindle_sync[0].channel, 1);  // commanded by the master's channel
  EXPECT_EQ(rejection_path(base + "spindle_sync: [{group: 1, master: S1, slave: X2}]\n"),
            "spindle_sync[0].slave");
  EXPECT_EQ(rejection_path(base + "spindle_sync: [{group: 4, master: S1, slave: S2}]\n"),
            "spindle_sync[0].group");
  EXPECT_EQ(rejection_path(base + "spindle_sync: [{group: 1, master: S1, slave: S1}]\n"),
            "spindle_sync[0].slave");
  EXPECT_EQ(rejection_path(base + "spindle_sync: [{group: 1, master: S1, slave: S2}, "
                                  "{group: 2, master: S1, slave: S2}]\n"),
            "spindle_sync[1].slave");
}

}  // namespace
}  // namespace mcnc::config

namespace mcnc::config {
namespace {

// C1 mode: a spindle's C axis is a program axis of the spindle's channel, after its exchange
// axes, on the spindle's node; it is not an axis with a node of its own.
TEST(MachineConfig, ASpindlesCAxis) {
  const std::string head = R"(
machine: {name: m, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: X2, address: X, bus: b, node_id: 3}
)";
  const std::string s1 = "  - {name: S1, type: spindle, bus: b, node_id: 4, counts_per_unit: 100, ";
  const std::string s2 = "  - {name: S2, type: spindle, bus: b, node_id: 5}\n";
  const std::string channels =
      "channels: [{name: CH1, axes: [X1], spindles: [S1, S2]}, {name: CH2, axes: [X2]}]\n";
  const MachineConfig config =
      parse_machine_yaml(head + s1 + "c_axis: {name: C1, acceleration: 720}}\n" + s2 + channels);
  ASSERT_EQ(config.axes.size(), 4U);  // no node of its own
  ASSERT_EQ(config.c_axes.size(), 1U);
  const AxisConfig* c = config.find_axis("C1");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->spindle, "S1");
  EXPECT_EQ(config.find_axis("S1")->c_axis, "C1");
  EXPECT_EQ(c->address, 'C');
  EXPECT_EQ(c->type, AxisType::rotary);
  EXPECT_EQ(c->id, config.find_axis("S1")->id);  // the spindle's node and feedback
  EXPECT_EQ(c->node_id, 4);
  EXPECT_EQ(c->counts_per_unit, 100.0);
  EXPECT_EQ(c->acceleration, 720.0);
  EXPECT_EQ(c->jerk, 50.0 * 720.0);
  EXPECT_EQ(c->channel, "CH1");
  EXPECT_EQ(config.channels[0].program_axes(), (std::vector<std::string>{"X1", "C1"}));

  EXPECT_EQ(rejection_path(head + s1 + "c_axis: {name: C1}}\n" + s2 +
                           "channels: [{name: CH1, axes: [X1], spindles: [S2, S1]}, "
                           "{name: CH2, axes: [X2]}]\n"),
            "axes[2].c_axis")
      << "only the channel's first spindle";
  EXPECT_EQ(rejection_path(head + s1 + "c_axis: {name: C1, address: X}}\n" + s2 + channels),
            "axes[2].c_axis.address");
  EXPECT_EQ(rejection_path(head + s1 + "c_axis: {name: X2}}\n" + s2 + channels),
            "axes[2].c_axis.name")
      << "a name another axis has";
  std::string taken = head;
  taken.replace(taken.find("name: X1, address: X"), 20, "name: X1, address: C");
  EXPECT_EQ(rejection_path(taken + s1 + "c_axis: {name: C1}}\n" + s2 + channels), "axes[2].c_axis")
      << "C is X1's address in CH1";
  EXPECT_EQ(rejection_path(head + s1 + "c_axis: {name: C1, speed: 3}}\n" + s2 + channels),
            "axes[2].c_axis.speed");
  std::string on_axis = head;
  on_axis.replace(on_axis.find("node_id: 3}"), 11, "node_id: 3, c_axis: {name: C9}}");
  EXPECT_EQ(rejection_path(on_axis + s1 + "c_axis: {name: C1}}\n" + s2 + channels),
            "axes[1].c_axis");
}

}  // namespace
}  // namespace mcnc::config

namespace mcnc::config {
namespace {

// Params 5310-5312 (spec dafeng §2.6.6): a channel's polygon axis is one of its spindles that
// follows another of them, never also a G114.1 slave, no faster than its drive.
TEST(MachineConfig, PolygonAxisOfAChannel) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
  - {name: b2, uri: "socketcan:can1", sync_producer: X2}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, bus: b, node_id: 2}
  - {name: T1, type: spindle, bus: b, node_id: 3, drive: {max_velocity: 24000}}
  - {name: C1, address: C, type: rotary, bus: b2, node_id: 3}
  - {name: X2, address: X, bus: b2, node_id: 1}
  - {name: S2, type: spindle, bus: b2, node_id: 2}
)";
  const auto with = [&](const std::string& polygon, const std::string& more = "") {
    return base + "channels: [{name: CH1, axes: [X1, C1], spindles: [S1, T1], polygon: " + polygon +
           "}, {name: CH2, axes: [X2], spindles: [S2]}]\n" + more;
  };
  const MachineConfig config = parse_machine_yaml(with("{master: S1, slave: T1, max_rpm: 3000}"));
  EXPECT_EQ(config.channels[0].polygon_master, 2);
  EXPECT_EQ(config.channels[0].polygon_slave, 3);
  EXPECT_EQ(config.channels[0].polygon_max_rpm, 3000.0);
  EXPECT_EQ(config.channels[1].polygon_master, 0);  // none
  // Without max_rpm: as fast as the drive (24000 deg/s).
  EXPECT_EQ(parse_machine_yaml(with("{master: S1, slave: T1}")).channels[0].polygon_max_rpm,
            4000.0);
  std::string what;
  EXPECT_EQ(rejection_path(with("{master: S1, slave: T1, max_rpm: 5000}"), &what),
            "channels[0].polygon.max_rpm");
  EXPECT_NE(what.find("above what T1's drive can turn (4000 rpm)"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: S1, slave: S1}")), "channels[0].polygon.slave");
  EXPECT_EQ(rejection_path(with("{master: S1, slave: S2}"), &what), "channels[0].polygon.slave");
  EXPECT_NE(what.find("S2 is not a spindle of channel CH1"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: S1}")), "channels[0].polygon.slave");
  EXPECT_EQ(rejection_path(with("{master: C1, slave: T1}"), &what), "channels[0].polygon.master");
  EXPECT_NE(what.find("C1 is not a spindle of this machine"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: S1, slave: T1}",
                                "spindle_sync: [{group: 1, master: S2, slave: T1}]\n"),
                           &what),
            "channels[0].polygon.slave");
  EXPECT_NE(what.find("already the slave of G114.1 group 1"), std::string::npos) << what;
}

// Param 5311 may name a servo axis too (spec dafeng L2897-2899): one of the channel's own rotary
// axes, which the channel stops commanding while it follows (decision 157).
TEST(MachineConfig, PolygonAxisMayBeARotaryServoAxisOfTheChannel) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
  - {name: b2, uri: "socketcan:can1", sync_producer: X2}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: S1, type: spindle, bus: b, node_id: 2}
  - {name: X2, address: X, bus: b2, node_id: 1}
  - {name: C2, address: C, type: rotary, bus: b2, node_id: 2}
  - {name: S2, type: spindle, bus: b2, node_id: 3}
)";
  const auto with = [&](const std::string& c1, const std::string& channel_keys) {
    return base + "  - {name: C1, address: C, type: rotary, bus: b, node_id: 3" + c1 +
           "}\nchannels: [{name: CH1, axes: [X1, C1], spindles: [S1]" + channel_keys +
           "}, {name: CH2, axes: [X2, C2], spindles: [S2]}]\n";
  };
  const MachineConfig config = parse_machine_yaml(
      with(", drive: {max_velocity: 12000}", ", polygon: {master: S1, slave: C1}"));
  EXPECT_EQ(config.channels[0].polygon_master, 2);
  EXPECT_EQ(config.channels[0].polygon_slave, 6);         // C1, the last axis of the file
  EXPECT_EQ(config.channels[0].polygon_max_rpm, 2000.0);  // its drive's 12000 deg/s
  EXPECT_FALSE(config.channels[0].polygon_no_wait);
  // Param 5300.5 = 1: G51.2 does not wait for the lock, the next cutting block does.
  EXPECT_TRUE(parse_machine_yaml(with("", ", polygon: {master: S1, slave: C1, no_wait: true}"))
                  .channels[0]
                  .polygon_no_wait);
  std::string what;
  EXPECT_EQ(rejection_path(with("", ", polygon: {master: S1, slave: X1}"), &what),
            "channels[0].polygon.slave");
  EXPECT_NE(what.find("X1 is not a rotary axis"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("", ", polygon: {master: S1, slave: C2}"), &what),
            "channels[0].polygon.slave");
  EXPECT_NE(what.find("C2 is not an axis of channel CH1"), std::string::npos) << what;
  EXPECT_EQ(
      rejection_path(with(", soft_limits: [-10, 10]", ", polygon: {master: S1, slave: C1}"), &what),
      "channels[0].polygon.slave");
  EXPECT_NE(what.find("turns without end"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with(", axis_sync: {}", ", polygon: {master: S1, slave: C1}"), &what),
            "channels[0].polygon.slave");
  EXPECT_NE(what.find("may follow another axis"), std::string::npos) << what;
  EXPECT_EQ(
      rejection_path(with("", ", polygon: {master: S1, slave: C1}, cam: {master: S1, slave: C1}"),
                     &what),
      "channels[0].cam.slave");
  EXPECT_NE(what.find("C1 is the channel's polygon axis"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(
                with("", ", polygon: {master: S1, slave: C1}, egb: {tool: S1, work: C1}"), &what),
            "channels[0].egb.work");
  EXPECT_NE(what.find("C1 is the channel's polygon axis"), std::string::npos) << what;
}

}  // namespace
}  // namespace mcnc::config

namespace mcnc::config {
namespace {

// Params 5350/5351 (spec dafeng §2.6.7, L3036-3042): G51.8's master is a spindle of the channel
// and its slave one of the channel's own axes, which follows no other axis.
TEST(MachineConfig, CamMasterAndSlaveOfAChannel) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
  - {name: b2, uri: "socketcan:can1", sync_producer: X2}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 4, axis_sync: {master: X1}}
  - {name: S1, type: spindle, bus: b, node_id: 2}
  - {name: X2, address: X, bus: b2, node_id: 1}
  - {name: S2, type: spindle, bus: b2, node_id: 2}
)";
  const auto with = [&](const std::string& cam) {
    return base + "channels: [{name: CH1, axes: [X1, Z1], spindles: [S1], cam: " + cam +
           "}, {name: CH2, axes: [X2], spindles: [S2]}]\n";
  };
  const MachineConfig config = parse_machine_yaml(with("{master: S1, slave: X1}"));
  EXPECT_EQ(config.channels[0].cam_master, 3);
  EXPECT_EQ(config.channels[0].cam_slave, 1);
  EXPECT_EQ(config.channels[1].cam_master, 0);  // none
  std::string what;
  EXPECT_EQ(rejection_path(with("{master: S2, slave: X1}"), &what), "channels[0].cam.master");
  EXPECT_NE(what.find("S2 is not a spindle of channel CH1"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: X1, slave: X1}")), "channels[0].cam.master");
  EXPECT_EQ(rejection_path(with("{master: S1, slave: X2}"), &what), "channels[0].cam.slave");
  EXPECT_NE(what.find("X2 is not an axis of channel CH1"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: S1, slave: S1}")), "channels[0].cam.slave");
  EXPECT_EQ(rejection_path(with("{master: S1, slave: Z1}"), &what), "channels[0].cam.slave");
  EXPECT_NE(what.find("G51.4"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{master: S1}")), "channels[0].cam.slave");
}

}  // namespace
TEST(MachineConfig, EgbNamesAToolSpindleAndARotaryWorkAxisOfTheChannel) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: C1, address: C, type: rotary, bus: b, node_id: 3}
  - {name: B1, address: B, type: rotary, bus: b, node_id: 4, axis_sync: {master: C1}}
  - {name: S1, type: spindle, bus: b, node_id: 5}
)";
  const auto with = [&](const std::string& egb) {
    return base + "channels: [{name: CH1, axes: [X1, Z1, C1, B1], spindles: [S1], egb: " + egb +
           "}]\n";
  };
  const MachineConfig config =
      parse_machine_yaml(with("{tool: S1, work: C1, axial: Z1, stop_time: 0.4}"));
  EXPECT_EQ(config.channels[0].egb_tool, 5);
  EXPECT_EQ(config.channels[0].egb_work, 3);
  EXPECT_EQ(config.channels[0].egb_axial, 2);
  EXPECT_DOUBLE_EQ(config.channels[0].egb_stop_time_s, 0.4);
  const MachineConfig spur = parse_machine_yaml(with("{tool: S1, work: C1}"));
  EXPECT_EQ(spur.channels[0].egb_axial, 0);  // no helical gears
  std::string what;
  EXPECT_EQ(rejection_path(with("{tool: X1, work: C1}")), "channels[0].egb.tool");
  EXPECT_EQ(rejection_path(with("{tool: S1, work: X1}"), &what), "channels[0].egb.work");
  EXPECT_NE(what.find("not a rotary axis"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{tool: S1, work: B1}"), &what), "channels[0].egb.work");
  EXPECT_NE(what.find("G51.4"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{tool: S1, work: S1}")), "channels[0].egb.work");
  EXPECT_EQ(rejection_path(with("{tool: S1, work: C1, axial: C1}"), &what),
            "channels[0].egb.axial");
  EXPECT_NE(what.find("not a linear axis"), std::string::npos) << what;
  EXPECT_EQ(rejection_path(with("{tool: S1, work: C1, stop_time: 0}")),
            "channels[0].egb.stop_time");
  EXPECT_EQ(rejection_path(with("{tool: S1}")), "channels[0].egb.work");
  EXPECT_EQ(
      rejection_path(
          base + "channels: [{name: CH1, axes: [X1, Z1, C1, B1], spindles: [S1], cam: {master: "
                 "S1, slave: C1}, egb: {tool: S1, work: C1}}]\n",
          &what),
      "channels[0].egb.work");
  EXPECT_NE(what.find("cam"), std::string::npos) << what;
}

TEST(MachineConfig, EgbTakesParameter5320sBits) {
  const std::string base = R"(
machine: {name: m, cycle_us: 2000}
buses:
  - {name: b, uri: "socketcan:can0", sync_producer: X1}
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: C1, address: C, type: rotary, bus: b, node_id: 2}
  - {name: S1, type: spindle, bus: b, node_id: 3}
)";
  const auto with = [&](const std::string& egb) {
    return base + "channels: [{name: CH1, axes: [X1, C1], spindles: [S1], egb: " + egb + "}]\n";
  };
  const ChannelConfig plain = parse_machine_yaml(with("{tool: S1, work: C1}")).channels[0];
  EXPECT_FALSE(plain.egb_synchronous);  // follow mode, the deviation watched
  EXPECT_FALSE(plain.egb_no_wait);
  EXPECT_FALSE(plain.egb_reset_at_once);  // 5320.4 = 0: once the tool spindle stands
  EXPECT_FALSE(plain.egb_reverse);
  EXPECT_FALSE(plain.egb_helix_reverse);
  const ChannelConfig all =
      parse_machine_yaml(with("{tool: S1, work: C1, synchronous: true, no_wait: true, reset: "
                              "at_once, reverse: true, helix_reverse: true}"))
          .channels[0];
  EXPECT_TRUE(all.egb_synchronous);
  EXPECT_TRUE(all.egb_no_wait);
  EXPECT_TRUE(all.egb_reset_at_once);
  EXPECT_TRUE(all.egb_reverse);
  EXPECT_TRUE(all.egb_helix_reverse);
  std::string what;
  EXPECT_EQ(rejection_path(with("{tool: S1, work: C1, reset: later}"), &what),
            "channels[0].egb.reset");
  EXPECT_NE(what.find("5320.4"), std::string::npos) << what;
}

}  // namespace mcnc::config
