// The run report's pictures say what ran: a lane per channel with its blocks, waits and sync
// points, the axis that changed owner, and a toolpath per channel through the sampled points.
#include "tools/report/run_report.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::report {
namespace {

config::MachineConfig two_turrets() {
  return config::parse_machine_yaml(R"(
machine: {name: twins, cycle_us: 2000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: A1, address: A, type: rotary, bus: b, node_id: 3, exchange: 14}
  - {name: X2, address: X, bus: b, node_id: 4}
channels:
  - {name: CH1, axes: [X1, Z1, A1]}
  - {name: CH2, axes: [X2], exchange_axes: [A1]}
)");
}

nlohmann::json ev(std::uint64_t cycle, const std::string& src, const std::string& kind,
                  nlohmann::json fields) {
  fields["cycle"] = cycle;
  fields["src"] = src;
  fields["ev"] = kind;
  return fields;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

Trace a_run() {
  Trace t;
  t.push_back(ev(0, "CH1", "state", {{"ch", "CH1"}, {"state", "running"}}));
  t.push_back(ev(0, "CH2", "state", {{"ch", "CH2"}, {"state", "running"}}));
  t.push_back(ev(0, "A1", "owner", {{"axis", "A1"}, {"owner", "CH1"}}));
  t.push_back(
      ev(1, "CH1", "block", {{"ch", "CH1"}, {"prog", "a.nc"}, {"line", 1}, {"text", "G00 X10"}}));
  t.push_back(
      ev(1, "CH2", "block", {{"ch", "CH2"}, {"prog", "b.nc"}, {"line", 1}, {"text", "G04.1 P10"}}));
  t.push_back(ev(2, "CH2", "state", {{"ch", "CH2"}, {"state", "waiting"}}));
  t.push_back(ev(40, "CH1", "block",
                 {{"ch", "CH1"}, {"prog", "a.nc"}, {"line", 2}, {"text", "G04.1 P10"}}));
  t.push_back(ev(41, "CH1", "sync_release", {{"ch", "CH1"}, {"p", 10}, {"gen", 1}}));
  t.push_back(ev(42, "CH2", "sync_release", {{"ch", "CH2"}, {"p", 10}, {"gen", 1}}));
  t.push_back(ev(42, "CH2", "state", {{"ch", "CH2"}, {"state", "running"}}));
  t.push_back(
      ev(42, "CH1", "block", {{"ch", "CH1"}, {"prog", "a.nc"}, {"line", 3}, {"text", "G140 A14"}}));
  t.push_back(ev(50, "A1", "owner",
                 {{"axis", "A1"}, {"owner", "CH2"}, {"previous", "CH1"}, {"forced", false}}));
  t.push_back(ev(60, "CH1", "end", {{"ch", "CH1"}, {"code", 30}}));
  t.push_back(ev(60, "CH1", "state", {{"ch", "CH1"}, {"state", "idle"}}));
  // X1 and Z1 sampled every 10 cycles: from (X 0, Z 0) to (X 5, Z -10), where it stays.
  for (std::uint64_t c = 0; c <= 60; c += 10) {
    const double f = std::min(1.0, static_cast<double>(c) / 40.0);
    t.push_back(ev(c, "X1", "pos", {{"axis", "X1"}, {"cmd", 5.0 * f}, {"act", 5.0 * f}}));
    t.push_back(ev(c, "Z1", "pos", {{"axis", "Z1"}, {"cmd", -10.0 * f}, {"act", -10.0 * f}}));
  }
  t.push_back(ev(60, "CH1", "pos", {{"axis", "X1"}, {"cmd", 5.0}, {"act", 5.0}}));  // a block end
  t.push_back(ev(70, "launch", "summary",
                 {{"ok", true},
                  {"cycles", 70},
                  {"channels", {{"CH1", {{"end", 30}, {"alarms", 0}, {"cycle_time_s", 0.12}}}}}}));
  return t;
}

TEST(RunReport, TheTimelineHasALanePerChannelWithBlocksWaitsSyncPointsAndOwnerChanges) {
  const std::string svg = timeline_svg(two_turrets(), a_run());
  EXPECT_EQ(count(svg, "<g data-channel=\"CH1\">"), 1U);
  EXPECT_EQ(count(svg, "<g data-channel=\"CH2\">"), 1U);
  const std::string ch1 =
      svg.substr(svg.find("data-channel=\"CH1\""),
                 svg.find("data-channel=\"CH2\"") - svg.find("data-channel=\"CH1\""));
  const std::string ch2 = svg.substr(svg.find("data-channel=\"CH2\""));
  EXPECT_EQ(count(ch1, "class=\"block\""), 3U);
  EXPECT_EQ(count(ch2, "class=\"block\""), 1U);
  EXPECT_EQ(count(ch1, "class=\"sync\" data-p=\"10\""), 1U);
  EXPECT_EQ(count(ch2, "class=\"sync\" data-p=\"10\""), 1U);
  EXPECT_EQ(count(ch2, "class=\"wait\""), 1U);
  EXPECT_EQ(count(ch1, "class=\"wait\""), 0U);
  // The exchange shows once, on the lane of the channel that took A1 (not at start).
  EXPECT_EQ(count(svg, "class=\"owner\""), 1U);
  EXPECT_EQ(count(ch2, "class=\"owner\" data-axis=\"A1\""), 1U);
  EXPECT_NE(ch1.find("a.nc:3 G140 A14"), std::string::npos);  // the block's text as its title
}

TEST(RunReport, TheToolpathGoesThroughTheSampledPointsWithTheSyncPointOnIt) {
  const std::string svg = toolpath_svg(two_turrets(), a_run(), "CH1");
  EXPECT_EQ(count(svg, "<path class=\"toolpath\""), 1U);
  // Seven samples; Z from -10 (left edge, 20) to 0 (right edge, 460), X (radius) 0 at the
  // bottom (460) to 5: one scale for both, so 5 mm is a quarter of the 440 of 10 mm.
  EXPECT_NE(svg.find("d=\"M460.00 460.00 L350.00 405.00"), std::string::npos) << svg;
  EXPECT_EQ(count(svg, " L"), 6U);
  EXPECT_NE(svg.find("L20.00 240.00\""), std::string::npos) << svg;
  // P10 released at cycle 41: the sample at 40, the end point.
  EXPECT_NE(svg.find("class=\"sync\" data-p=\"10\" cx=\"20.00\" cy=\"240.00\""), std::string::npos)
      << svg;
  EXPECT_TRUE(toolpath_svg(two_turrets(), a_run(), "CH2").empty());  // CH2 has no Z
}

TEST(RunReport, ThePageHasTheResultTheCycleTimesAndBothPictures) {
  const std::string html = report_html(two_turrets(), a_run());
  EXPECT_NE(html.find("Run report: twins"), std::string::npos);
  EXPECT_NE(html.find("<td>CH1</td><td>M30</td><td>0.12</td><td>0</td>"), std::string::npos)
      << html;
  EXPECT_NE(html.find("<td>CH2</td><td>no program</td>"), std::string::npos);
  EXPECT_EQ(count(html, "<svg"), 2U);  // the timeline and CH1's toolpath
  EXPECT_NE(html.find("<li>none</li>"), std::string::npos);
}

}  // namespace
}  // namespace mcnc::report
