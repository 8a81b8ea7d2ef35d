#include "launch/ephemeral_ports.hpp"

#include <gtest/gtest.h>

using namespace mcnc::launch;

TEST(EphemeralPorts, ReadsTheKernelsRangeAndList) {
  EXPECT_EQ(parse_port_range("32768\t60999\n"), (PortRange{32768, 60999}));
  EXPECT_FALSE(parse_port_range("60999\t32768\n"));
  EXPECT_FALSE(parse_port_range("32768\n"));
  EXPECT_FALSE(parse_port_range("32768 x"));
  EXPECT_EQ(parse_port_list("\n"), std::vector<PortRange>{});
  EXPECT_EQ(parse_port_list("7410-7430,8000\n"),
            (std::vector<PortRange>{{7410, 7430}, {8000, 8000}}));
  EXPECT_FALSE(parse_port_list("7410-"));
  EXPECT_FALSE(parse_port_list("7430-7410"));
  EXPECT_FALSE(parse_port_list("7410,"));
  EXPECT_FALSE(parse_port_list("70000"));
}

TEST(EphemeralPorts, ExposedAreTheWantedPortsInTheRangeThatAreNotReserved) {
  const PortRange linux_default{32768, 60999};
  // Domain 101's ports of a 15-process machine lie below the range: none exposed.
  EXPECT_TRUE(exposed_ports({32660, 32689}, linux_default, {}).empty());
  // Across its lower end: the part inside.
  EXPECT_EQ(exposed_ports({32750, 32800}, linux_default, {}),
            (std::vector<PortRange>{{32768, 32800}}));
  // Reserved ports are not exposed; the rest is, range by range.
  EXPECT_EQ(exposed_ports({59160, 59190}, linux_default, {{59165, 59170}, {59180, 59180}}),
            (std::vector<PortRange>{{59160, 59164}, {59171, 59179}, {59181, 59190}}));
  EXPECT_TRUE(exposed_ports({59160, 59190}, linux_default, {{59000, 59500}}).empty());
}

TEST(EphemeralPorts, WritesTheListAsTheKernelReadsIt) {
  EXPECT_EQ(port_list({}), "");
  EXPECT_EQ(port_list({{59160, 59164}, {59171, 59171}}), "59160-59164,59171");
  EXPECT_EQ(parse_port_list(port_list({{1, 2}, {5, 5}})), (std::vector<PortRange>{{1, 2}, {5, 5}}));
}
