// `hosts:` in a machine file (docs/configuration.md "Hosts"): which host runs which process, and
// the rejections, each at its key path.
#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::config {
namespace {

// Two hosts: a runs CH1 and can0's axes, b runs CH2 and can1's. `cycle` is the machine's
// cycle_us line (or none), `runs_a` and `runs_b` what the hosts run.
std::string two_hosts(const std::string& runs_a, const std::string& runs_b,
                      const std::string& cycle = "") {
  return R"(
machine: {name: m)" +
         cycle +
         R"(}
buses:
  - {name: can0, uri: "udp:239.255.42.1:29000", sync_producer: X1}
  - {name: can1, uri: "udp:239.255.42.1:29001", sync_producer: X2}
channels:
  - {name: CH1, axes: [X1], spindles: [S1]}
  - {name: CH2, axes: [X2]}
axes:
  - {name: X1, address: X, bus: can0, node_id: 1}
  - {name: S1, type: spindle, bus: can0, node_id: 3, c_axis: {name: C1, address: C}}
  - {name: X2, address: X, bus: can1, node_id: 1}
hosts:
  - {name: a, address: 10.77.0.1, runs: [)" +
         runs_a + R"(]}
  - {name: b, runs: [)" +
         runs_b + R"(]}
)";
}

// The key path and the reason of a rejection; "<accepted>" when there is none.
std::string rejection(const std::string& text) {
  try {
    (void)parse_machine_yaml(text);
  } catch (const ConfigError& error) {
    return error.key_path() + ": " + error.what();
  }
  return "<accepted>";
}

TEST(Hosts, EachProcessRunsOnTheHostThatNamesItAndTheHmiOnTheFirstUnlessNamed) {
  const MachineConfig m = parse_machine_yaml(two_hosts("CH1, X1, S1, can0", "CH2, X2, can1"));
  ASSERT_EQ(m.hosts.size(), 2U);
  EXPECT_EQ(m.hosts[0].address, "10.77.0.1");
  EXPECT_EQ(m.hosts[1].address, "");
  EXPECT_EQ(m.host_of("CH1")->name, "a");
  EXPECT_EQ(m.host_of("X2")->name, "b");
  EXPECT_EQ(m.host_of("can1")->name, "b");
  EXPECT_EQ(m.host_of("hmi")->name, "a");
  EXPECT_EQ(m.host_of("C1"), nullptr) << "a C axis is no process of its own";
  EXPECT_EQ(m.cycle_us, 1000) << "no channel commands an axis on another host";
  const MachineConfig hmi_on_b =
      parse_machine_yaml(two_hosts("CH1, X1, S1, can0", "CH2, X2, can1, hmi"));
  EXPECT_EQ(hmi_on_b.host_of("hmi")->name, "b");
  // Without hosts: one host, no placement.
  EXPECT_EQ(parse_machine_yaml(R"(
machine: {name: m}
buses: [{name: can0, uri: "udp:239.255.42.1:29000", sync_producer: X1}]
channels: [{name: CH1, axes: [X1]}]
axes: [{name: X1, address: X, bus: can0, node_id: 1}]
)")
                .host_of("CH1"),
            nullptr);
}

TEST(Hosts, AChannelThatCommandsAnAxisOnAnotherHostRunsAtTheLinksCycle) {
  // CH2 on host a commands X2 on host b.
  const MachineConfig m = parse_machine_yaml(two_hosts("CH1, CH2, X1, S1, can0", "X2, can1"));
  EXPECT_EQ(m.cycle_us, kDefaultLinkCycleUs);
  EXPECT_EQ(m.buses[0].sync_offset_us, kDefaultLinkCycleUs / 2) << "the SYNC from that cycle";
  EXPECT_EQ(
      parse_machine_yaml(two_hosts("CH1, CH2, X1, S1, can0", "X2, can1", ", cycle_us: 4000"))
          .cycle_us,
      4000);
  EXPECT_EQ(parse_machine_yaml(two_hosts("CH1, CH2, X1, S1, can0", "X2, can1",
                                         ", cycle_us: 1000, link_cycle_us: 1000"))
                .cycle_us,
            1000);
  EXPECT_EQ(rejection(two_hosts("CH1, CH2, X1, S1, can0", "X2, can1", ", cycle_us: 1000")),
            "machine.cycle_us: machine.cycle_us: 1000 us is below the 2000 us the hosts' link "
            "allows, and channel CH2 (host a) commands X2 on host b (link_cycle_us sets the "
            "link's cycle) (line 2, column 30)");
}

TEST(Hosts, EveryProcessRunsOnExactlyOneHostAndEachAxisWhereItsBusIs) {
  auto path_of = [](const std::string& text) {
    const std::string r = rejection(text);
    return r.substr(0, r.find(':'));
  };
  auto reason_has = [](const std::string& text, const std::string& part) {
    const std::string r = rejection(text);
    EXPECT_NE(r.find(part), std::string::npos) << r;
  };
  const std::string unknown = two_hosts("CH1, X1, S1, can0, X9", "CH2, X2, can1");
  EXPECT_EQ(path_of(unknown), "hosts[0].runs[4]");
  reason_has(unknown, "no channel, axis, bus or hmi of this machine is called 'X9'");

  const std::string twice = two_hosts("CH1, X1, S1, can0", "CH2, X2, can1, CH1");
  EXPECT_EQ(path_of(twice), "hosts[1].runs[3]");
  reason_has(twice, "channel CH1 already runs on host a");

  const std::string nowhere = two_hosts("CH1, X1, S1, can0", "CH2, can1");
  EXPECT_EQ(path_of(nowhere), "hosts");
  reason_has(nowhere, "axis X2 runs on no host");

  const std::string off_bus = two_hosts("CH1, X1, can0", "CH2, X2, can1, S1");
  EXPECT_EQ(path_of(off_bus), "hosts[1].runs[3]");
  reason_has(off_bus, "axis S1 is on bus can0, which host a runs");

  const std::string c_axis = two_hosts("CH1, X1, S1, can0, C1", "CH2, X2, can1");
  EXPECT_EQ(path_of(c_axis), "hosts[0].runs[4]");
  reason_has(c_axis, "C1 is spindle S1's C axis: it runs where its spindle runs");

  std::string same_name = two_hosts("CH1, X1, S1, can0", "CH2, X2, can1");
  same_name.replace(same_name.find("{name: b,"), 9, "{name: a,");
  EXPECT_EQ(path_of(same_name), "hosts[1].name");
  reason_has(same_name, "duplicate host name a");

  std::string no_runs = two_hosts("CH1, X1, S1, can0", "CH2, X2, can1");
  no_runs.replace(no_runs.find(", runs: [CH2"), 6, ", run: ");
  EXPECT_EQ(path_of(no_runs), "hosts[1].run");
}

}  // namespace
}  // namespace mcnc::config
