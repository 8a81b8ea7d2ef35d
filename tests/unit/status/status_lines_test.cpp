// `mcnc status` lines: what an operator without a browser reads from a live machine.
#include "tools/status/status_lines.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mcnc::status {
namespace {

config::MachineConfig two_channels() {
  return config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes:
  - {name: X1, address: X, bus: b, node_id: 1}
  - {name: A1, address: A, type: rotary, bus: b, node_id: 2, exchange: 14}
  - {name: S1, type: spindle, bus: b, node_id: 3}
  - {name: X2, address: X, bus: b, node_id: 4}
channels:
  - {name: CH1, axes: [X1, A1], spindles: [S1]}
  - {name: CH2, axes: [X2], exchange_axes: [A1]}
)");
}

TEST(StatusLines, OneLinePerChannelAndAxisSayingWhatTheOperatorAsks) {
  const config::MachineConfig m = two_channels();
  StatusSnapshot s;
  ChannelView ch1;
  ch1.state = ChannelState::waiting;
  ch1.block = 5;
  ch1.block_total = 11;
  ch1.line = 7;
  ch1.sync_p = 10;
  ch1.sync_waiting_for = 0b10;  // CH2
  s.channels[1] = ch1;
  ChannelView ch2;
  ch2.state = ChannelState::alarm;
  ch2.alarms = 1;
  ch2.call_caller = 1;
  s.channels[2] = ch2;
  AxisView x1;
  x1.cmd = 12.5;
  x1.act = 12.4998;
  x1.following_error = 0.0002;
  x1.enabled = true;
  x1.owner = 1;
  s.axes[1] = x1;
  AxisView a1;
  a1.owner = 2;
  a1.released_by = 1;
  a1.enabled = true;
  s.axes[2] = a1;
  AxisView s1;
  s1.vel = 600.0;  // degrees per second
  s1.mode_display = 9;
  s1.enabled = true;
  s1.owner = 1;
  s.axes[3] = s1;
  const std::vector<std::string> lines = status_lines(m, s);
  ASSERT_EQ(lines.size(), 6U);
  EXPECT_EQ(lines[0], "CH1  waiting  block 5/11  line 7  waits at G04.1 P10 for CH2");
  EXPECT_EQ(lines[1], "CH2  alarm    block 0/0  line 0  runs a call of CH1  1 alarm");
  EXPECT_EQ(lines[2], "X1   CH1       cmd 12.5000  act 12.4998  error 0.0002");
  EXPECT_EQ(lines[3], "A1   CH2 (from CH1)  cmd 0.0000  act 0.0000  error 0.0000");
  EXPECT_EQ(lines[4], "S1   CH1       100.0 rpm  speed (CSV)");
  EXPECT_EQ(lines[5], "X2   no feedback");
  EXPECT_EQ(missing(m, s), std::vector<std::string>{"X2"});
}

TEST(StatusLines, ADisabledAxisAnAlarmAndAFollowingSpindleShow) {
  const config::MachineConfig m = two_channels();
  StatusSnapshot s;
  AxisView x1;
  x1.alarm = true;
  s.axes[1] = x1;
  AxisView x2;
  x2.owner = 2;
  s.axes[4] = x2;
  AxisView s1;
  s1.owner = 1;
  s1.enabled = true;
  s1.mode_display = 8;
  s1.coupled_to = 1;
  s1.coupling_locked = true;
  s.axes[3] = s1;
  const std::vector<std::string> lines = status_lines(m, s);
  EXPECT_EQ(lines[0], "CH1  no status");
  EXPECT_NE(lines[2].find("ALARM"), std::string::npos) << lines[2];
  EXPECT_NE(lines[2].find("released"), std::string::npos) << lines[2];
  EXPECT_NE(lines[4].find("position (CSP)  follows X1 (in phase)"), std::string::npos) << lines[4];
  EXPECT_NE(lines[5].find("disabled"), std::string::npos) << lines[5];
  EXPECT_EQ(missing(m, s), (std::vector<std::string>{"CH1", "CH2", "A1"}));
}

TEST(StatusLines, AMachineOfSeveralHostsHasEachHostsClock) {
  config::MachineConfig m = two_channels();
  m.hosts = {config::HostConfig{"ncu1", "", {"CH1", "X1", "A1", "S1", "b"}},
             config::HostConfig{"ncu2", "", {"CH2", "X2"}}, config::HostConfig{"ncu3", "", {}}};
  StatusSnapshot s;
  s.host_clocks["ncu1"] = HostClockView{0, 0, 0};
  s.host_clocks["ncu2"] = HostClockView{3'022'800, 65'700, 9};
  const std::vector<std::string> lines = status_lines(m, s);
  ASSERT_EQ(lines.size(), 9U);
  EXPECT_EQ(lines[6], "host ncu1  clock: machine time (coordinator)");
  EXPECT_EQ(lines[7], "host ncu2  clock +3022.8 us +- 65.7 us (9 exchanges)");
  EXPECT_EQ(lines[8], "host ncu3  no clock announced");
}

}  // namespace
}  // namespace mcnc::status
