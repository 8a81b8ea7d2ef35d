// G81.4 / G80.4 electronic gear box through the runtime, in lockstep (spec dafeng §2.6.11): on
// egb_lathe.yaml the channel asks C1's axis node to turn the work at L/T of the hob's spindle
// S1, in phase R, plus the helical angle of Z1's travel; the node lays that over the channel's
// setpoint every cycle from S1's feedback and Z1's command. G80.4 stops C1 within the stop time
// and the channel commands it from where it stopped. A G81.4 the channel cannot run moves
// nothing, and C1 off the gear's ratio too long is an alarm that stops it.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

using namespace std::chrono_literals;

constexpr double kCycleS = 0.002;  // egb_lathe.yaml's cycle

// How far `degrees` is from the nearest multiple of `period`.
double off_period(double degrees, double period) {
  return std::fabs(degrees - period * std::round(degrees / period));
}

// A run that must end in an alarm of CH1: its trace.
std::vector<nlohmann::json> run_to_alarm(const TestMachine& machine, const std::string& program) {
  const std::string trace_path = machine.file("trace.jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + source(program), "--trace",
           trace_path, "--trace-pos-every", "1"},
          -1, 180s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the run ends in the alarm
  return read_trace(trace_path);
}

// CH1's alarms numbered `number`.
std::vector<nlohmann::json> alarms(const std::vector<nlohmann::json>& trace, int number) {
  std::vector<nlohmann::json> found;
  for (const auto& a : events(trace, "alarm", "CH1")) {
    if (a["number"] == number) {
      found.push_back(a);
    }
  }
  return found;
}

TEST(ElectronicGearBox, CTurnsAtLOverTOfTheHobWithRAndTheHelixThenG804StopsItAndTheChannelGoesOn) {
  TestMachine machine("egb_lathe.yaml", 210);
  const auto trace =
      run_to_clean_end(machine, "launch/programs/egb_hob.nc", {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "C1");
  ASSERT_EQ(couples.size(), 1U);
  EXPECT_EQ(couples[0]["kind"], "egb");
  EXPECT_EQ(couples[0]["master"], "S1");
  EXPECT_EQ(couples[0]["refused"], false);
  const auto decouples = events(trace, "decouple", "C1");
  ASSERT_EQ(decouples.size(), 1U);
  EXPECT_EQ(decouples[0]["kind"], "egb");
  EXPECT_EQ(decouples[0]["why"], "G80.4");
  ASSERT_EQ(events(trace, "absorb", "C1").size(), 1U);

  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto z1 = axis_positions(trace, "Z1", "cmd");
  const auto c1 = axis_positions(trace, "C1", "cmd");
  // From the hob's infeed (line 5: G81.4 ended once C1 was locked) to G80.4 (line 8): C1's
  // node commands, for cycle c, S1's angle and Z1's position extrapolated from their samples of
  // c - 1 and c - 2, as 1/20 of S1 plus Z's travel from 5 x sin 15 deg / (pi 20 2) x 360, in the
  // phase R0: on one of the 18-degree periods (360 |L| / T) of the tooth.
  const double helix =
      std::sin(15.0 * std::numbers::pi / 180.0) / (std::numbers::pi * 40.0) * 360.0;
  const std::uint64_t locked = block.at(5);
  const std::uint64_t g804 = block.at(8);
  ASSERT_GT(g804, locked + 1000);
  for (std::uint64_t c = locked; c < g804; ++c) {
    const double hob = 2.0 * s1.at(c - 1) - s1.at(c - 2);
    const double z = 2.0 * z1.at(c - 1) - z1.at(c - 2);
    ASSERT_LT(off_period(c1.at(c) - hob / 20.0 - (z - 5.0) * helix, 18.0), 2e-3) << "cycle " << c;
  }
  // The hob turns at 300 rpm, C1 at 15 rpm while Z stands (the infeed, line 5).
  const std::uint64_t along = block.at(6);
  EXPECT_NEAR((s1.at(along - 1) - s1.at(locked)) / ((along - 1 - locked) * kCycleS), 1800.0, 1.0);
  EXPECT_NEAR((c1.at(along - 1) - c1.at(locked)) / ((along - 1 - locked) * kCycleS), 90.0, 0.1);
  // Z's 25 mm along the face (line 6) added its helical angle: C1 turned that much less than
  // 1/20 of S1 over the line.
  const std::uint64_t out = block.at(7);
  EXPECT_NEAR(z1.at(out - 1), -20.0, 1e-6);
  EXPECT_NEAR((c1.at(out - 1) - c1.at(along)) - (s1.at(out - 2) - s1.at(along - 1)) / 20.0,
              -25.0 * helix, 0.05);

  // G80.4 stops C1 within its 0.4 s from 15 rpm (egb stop_time), and the program goes on once
  // it stands: C1's node keeps it where it reached until the channel commands that angle.
  const std::uint64_t stopped = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_GT(stopped, g804);
  EXPECT_LE(stopped, g804 + static_cast<std::uint64_t>(0.4 / kCycleS) + 3);
  const std::uint64_t index = block.at(9);  // G91 G00 C90
  EXPECT_GE(index, stopped);
  const double reached = c1.at(stopped);
  // The channel commanded C at 0 all along: where C1 stands is the gear box's offset.
  EXPECT_NEAR(reached, decouples[0]["offset"].get<double>(), 1e-5);
  for (std::uint64_t c = stopped; c < index; ++c) {
    ASSERT_NEAR(c1.at(c), reached, 1e-9) << "cycle " << c;
  }
  // From there C moves on by 90 degrees, never faster than its rapid rate: nothing jumps.
  for (auto it = c1.lower_bound(g804); it != c1.end(); ++it) {
    const auto prev = c1.find(it->first - 1);
    ASSERT_LE(std::fabs(it->second - prev->second), 36000.0 / 60.0 * kCycleS + 1e-6)
        << "cycle " << it->first;
  }
  EXPECT_NEAR(c1.rbegin()->second, reached + 90.0, 1e-5);
  EXPECT_NEAR(axis_positions(trace, "C1", "act").rbegin()->second, reached + 90.0, 0.002);
}

TEST(ElectronicGearBox, AG814OnAChannelWithoutAGearBoxMovesNothing) {
  TestMachine machine("cam_lathe.yaml", 211);
  const auto trace = run_to_alarm(machine, "tests/integration/programs/egb/no_egb.nc");
  const auto refused = alarms(trace, 1254);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0]["line"], 4);
  EXPECT_NE(refused[0]["text"].get<std::string>().find("no electronic gear box"), std::string::npos)
      << refused[0]["text"];
  EXPECT_TRUE(events(trace, "couple").empty());
  // X stayed at the G00's 55 (27.5 in radius): nothing after G81.4 ran.
  const auto x1 = axis_positions(trace, "X1", "cmd");
  ASSERT_FALSE(x1.empty());
  EXPECT_NEAR(x1.rbegin()->second, 27.5, 1e-6);
}

TEST(ElectronicGearBox, AG814WhileTheGearBoxIsOnIsRefusedAndNeverReachesTheWorkAxis) {
  TestMachine machine("egb_lathe.yaml", 211);
  const auto trace = run_to_alarm(machine, "tests/integration/programs/egb/twice.nc");
  const auto refused = alarms(trace, 1254);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0]["line"], 6);
  EXPECT_NE(refused[0]["text"].get<std::string>().find("on already"), std::string::npos)
      << refused[0]["text"];
  // The first gear is the only one C1's node heard of, and it was never let go.
  EXPECT_EQ(events(trace, "couple", "C1").size(), 1U);
  EXPECT_TRUE(events(trace, "decouple", "C1").empty());
  // X never went in (line 7 did not run), and C1 turned at 1/20 of S1 (not 1/10) from the
  // dwell (G81.4 ended locked) until the alarm stopped the hob.
  EXPECT_NEAR(axis_positions(trace, "X1", "cmd").rbegin()->second, 30.0, 1e-9);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto c1 = axis_positions(trace, "C1", "cmd");
  std::uint64_t hob_stop = 0;
  for (const auto& e : events(trace, "spindle", "CH1")) {
    hob_stop = e["rpm"].get<double>() == 0.0 ? e["cycle"].get<std::uint64_t>() : hob_stop;
  }
  const std::uint64_t dwell = block_starts(trace).at(5);
  ASSERT_GT(hob_stop, dwell + 200);
  EXPECT_GE(hob_stop, refused[0]["cycle"].get<std::uint64_t>());
  for (std::uint64_t c = dwell; c <= hob_stop; ++c) {
    ASSERT_LT(off_period(c1.at(c) - (2.0 * s1.at(c - 1) - s1.at(c - 2)) / 20.0, 18.0), 2e-3)
        << "cycle " << c;
  }
}

TEST(ElectronicGearBox, AG814WithoutRWhileTheHobTurnsMovesNothing) {
  TestMachine machine("egb_lathe.yaml", 211);
  const auto trace = run_to_alarm(machine, "tests/integration/programs/egb/no_phase_turning.nc");
  const auto refused = alarms(trace, 1254);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0]["line"], 4);
  EXPECT_NE(refused[0]["text"].get<std::string>().find("without R"), std::string::npos)
      << refused[0]["text"];
  EXPECT_TRUE(events(trace, "couple").empty());
  for (const auto& [cycle, cmd] : axis_positions(trace, "C1", "cmd")) {
    ASSERT_EQ(cmd, 0.0) << "cycle " << cycle;
  }
  EXPECT_NEAR(axis_positions(trace, "X1", "cmd").rbegin()->second, 30.0, 1e-9);
}

TEST(ElectronicGearBox, CFallingOffTheRatioIsAnAlarmAndStopsItWithinTheStopTime) {
  // T1 L1: C1 (3600 deg/s^2) would have to turn as S1 does, which starts at 7200 deg/s^2.
  TestMachine machine("egb_lathe.yaml", 211);
  const auto trace = run_to_alarm(machine, "tests/integration/programs/egb/off_ratio.nc");
  const auto lost = alarms(trace, 1254);
  ASSERT_EQ(lost.size(), 1U);
  EXPECT_NE(lost[0]["text"].get<std::string>().find("off the gear's ratio"), std::string::npos)
      << lost[0]["text"];
  const auto decouples = events(trace, "decouple", "C1");
  ASSERT_EQ(decouples.size(), 1U);
  EXPECT_EQ(decouples[0]["why"], "deviation");
  const auto block = block_starts(trace);
  EXPECT_EQ(block.count(6), 0U) << "the infeed after the dwell never ran";
  // From the spindle's start C1 fell behind for 0.1 s (egb deviation_time), then stopped within
  // 0.4 s from what it turned at, and stands there.
  const std::uint64_t start = block.at(4);
  const std::uint64_t stopped = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_LE(stopped, start + static_cast<std::uint64_t>(0.55 / kCycleS));
  const auto c1 = axis_positions(trace, "C1", "cmd");
  for (auto it = c1.lower_bound(stopped); it != c1.end(); ++it) {
    ASSERT_NEAR(it->second, c1.at(stopped), 1e-9) << "cycle " << it->first;
  }
  EXPECT_TRUE(events(trace, "absorb").empty());
}

}  // namespace
}  // namespace mcnc::test
