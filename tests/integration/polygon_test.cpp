// G51.2 / G50.2 polygon turning through the runtime, in lockstep (spec dafeng §2.6.6): on
// polygon_lathe.yaml the channel asks T1's axis node to follow S1, T1's node turns the disc at
// Q/P times the spindle's position from its feedback, and the channel goes on once the disc is
// in phase; G50.2 brings it to rest. A G51.2 the polygon axis cannot take moves nothing.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

using namespace std::chrono_literals;

double wrap(double degrees) {
  double a = std::fmod(degrees, 360.0);
  a += a <= -180.0 ? 360.0 : a > 180.0 ? -360.0 : 0.0;
  return a;
}

TEST(PolygonTurning, TheDiscTurnsTwiceTheSpindleInPhaseUntilG502) {
  TestMachine machine("polygon_lathe.yaml", 117);
  const auto trace =
      run_to_clean_end(machine, "launch/programs/polygon_turn.nc", {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "T1");
  ASSERT_EQ(couples.size(), 1U);
  EXPECT_EQ(couples[0]["kind"], "polygon");
  EXPECT_EQ(couples[0]["master"], "S1");
  EXPECT_EQ(couples[0]["p"], 1);
  EXPECT_EQ(couples[0]["q"], 2);
  EXPECT_EQ(couples[0]["r"].get<double>(), 0.0);
  const auto decouples = events(trace, "decouple", "T1");
  ASSERT_EQ(decouples.size(), 1U);
  EXPECT_EQ(decouples[0]["kind"], "polygon");

  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto t1_cmd = axis_positions(trace, "T1", "cmd");
  const auto t1_act = axis_positions(trace, "T1", "act");
  // N40-N70 cut while the disc is locked (G51.2 ended only then), up to M05's stop (its
  // setpoint goes out before N80's block event: the spindle's command is the channel's, M05
  // is no read-ahead stop).
  const std::uint64_t locked = block.at(6);
  std::uint64_t stop = 0;
  for (const auto& s : events(trace, "spindle", "CH1")) {
    stop = s["rpm"].get<double>() == 0.0 ? s["cycle"].get<std::uint64_t>() : stop;
  }
  ASSERT_GT(stop, locked + 1000);
  int compared = 0;
  for (std::uint64_t c = locked; c < stop; ++c) {
    // T1's node commands, for cycle c, S1's position extrapolated from its feedback of c - 1
    // (at constant speed, its position at c) times Q/P: within a hundredth of a degree. (When
    // the spindle's drive stops it within a few cycles after M05, the extrapolation is off by
    // degrees for those cycles: the disc's node knows the spindle one cycle late.)
    ASSERT_NEAR(wrap(2.0 * s1.at(c) - t1_cmd.at(c)), 0.0, 0.01) << "cycle " << c;
    ++compared;
  }
  EXPECT_GT(compared, 1000);
  // The disc really turns at 1000 rpm while the spindle turns at 500 (spec L2958).
  const std::uint64_t a = locked + 100;
  const std::uint64_t b = stop - 10;
  const double s1_speed = (s1.at(b) - s1.at(a)) / ((b - a) * 0.002);
  const double t1_speed = (t1_act.at(b) - t1_act.at(a)) / ((b - a) * 0.002);
  EXPECT_NEAR(s1_speed, 3000.0, 3.0);
  EXPECT_NEAR(t1_speed / s1_speed, 2.0, 1e-4);
  // M05 stops the spindle and the disc with it, G50.2 lets the disc go once it stands, and
  // it stays there to the end: its drive, back in velocity control at 0, settles within half a
  // degree (the CSP lag of the abrupt stop it followed) and then stands still.
  const std::uint64_t released = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_GE(released, block.at(11));
  const double rest = t1_act.rbegin()->second;
  for (auto it = t1_act.lower_bound(released); it != t1_act.end(); ++it) {
    ASSERT_NEAR(it->second, rest, it->first < released + 20 ? 0.5 : 1e-9) << "cycle " << it->first;
  }
}

TEST(PolygonTurning, G502SlowsTheTurningDiscToRestBeforeTheProgramGoesOn) {
  TestMachine machine("polygon_lathe.yaml", 118);
  const auto trace = run_to_clean_end(
      machine, "tests/integration/programs/polygon/release_turning.nc", {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "T1");
  const auto decouples = events(trace, "decouple", "T1");
  ASSERT_EQ(couples.size(), 2U);
  ASSERT_EQ(decouples.size(), 2U);
  EXPECT_EQ(couples[0]["p"], 2);
  EXPECT_EQ(couples[0]["q"], -3);
  EXPECT_EQ(couples[0]["r"].get<double>(), 45.0);
  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto t1 = axis_positions(trace, "T1", "cmd");
  // In the dwell of N30 the disc turns -3/2 times the spindle, at its zero where S1 is at 45.
  for (std::uint64_t c = block.at(5); c < block.at(6); ++c) {
    ASSERT_NEAR(wrap(-1.5 * (s1.at(c) - 45.0) - t1.at(c)), 0.0, 0.01) << "cycle " << c;
  }
  // G50.2 (N40, wait): the disc slows down within its 7200 deg/s^2 and the dwell of N50 starts
  // only once it stands free.
  const std::uint64_t first_free = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_GT(first_free, block.at(6));
  EXPECT_GE(block.at(7), first_free);
  // From 2700 deg/s (1.5 x 300 rpm) to rest at 7200 deg/s^2: 0.375 s.
  EXPECT_NEAR((first_free - block.at(6)) * 0.002, 2700.0 / 7200.0, 0.02);
  double last_speed = 2700.0;
  for (std::uint64_t c = block.at(6) + 1; c <= first_free; ++c) {
    const double speed = std::fabs(t1.at(c) - t1.at(c - 1)) / 0.002;
    // Never faster again (the trace's positions have 0.001 deg: 0.5 deg/s per cycle).
    EXPECT_LE(speed, last_speed + 1.0) << "cycle " << c;
    last_speed = speed;
  }
  // G50.2 P0 (N70): the program goes on while the disc slows down.
  const std::uint64_t second_free = decouples[1]["cycle"].get<std::uint64_t>();
  EXPECT_LT(block.at(10), second_free);
}

TEST(PolygonTurning, ARefusedG512MovesNothing) {
  TestMachine machine("polygon_lathe.yaml", 122);
  const std::string trace_path = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("tests/integration/programs/polygon/too_fast.nc"),
                           "--trace", trace_path, "--trace-pos-every", "1"},
                          -1, 180s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the run ends in the alarm
  const auto trace = read_trace(trace_path);
  bool refused = false;
  for (const auto& a : events(trace, "alarm", "CH1")) {
    if (a["number"] == 1252) {
      refused = true;
      EXPECT_EQ(a["line"], 6);
      EXPECT_NE(a["text"].get<std::string>().find("3500 rpm, above its 3000 rpm"),
                std::string::npos)
          << a["text"];
    }
  }
  EXPECT_TRUE(refused);
  EXPECT_TRUE(events(trace, "couple").empty());
  // The disc never turned, and X stayed at the G00's 50 (25 in radius): N50 never ran.
  const auto t1 = axis_positions(trace, "T1", "cmd");
  ASSERT_FALSE(t1.empty());
  for (const auto& [cycle, cmd] : t1) {
    ASSERT_EQ(cmd, t1.begin()->second) << "cycle " << cycle;
  }
  const auto x1 = axis_positions(trace, "X1", "cmd");
  ASSERT_FALSE(x1.empty());
  for (const auto& [cycle, cmd] : x1) {
    ASSERT_LE(std::fabs(cmd), 25.0 + 1e-9) << "cycle " << cycle;
  }
  EXPECT_NEAR(x1.rbegin()->second, 25.0, 1e-6);
}

// Param 5311 naming a rotary servo axis (decision 157): on polygon_servo_lathe.yaml C1 turns
// twice S1 while its node follows S1, whatever the channel sent it before, and after G50.2 the
// channel commands it where it stood: N80's H90 positions it 90 degrees on from there.
TEST(PolygonTurning, AServoDiscFollowsTheSpindleAndIsPositionedFromWhereItStood) {
  TestMachine machine("polygon_servo_lathe.yaml", 219);
  const auto trace = run_to_clean_end(machine, "launch/programs/polygon_servo_turn.nc",
                                      {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "C1");
  ASSERT_EQ(couples.size(), 1U);
  EXPECT_EQ(couples[0]["kind"], "polygon");
  EXPECT_EQ(couples[0]["master"], "S1");
  const auto decouples = events(trace, "decouple", "C1");
  ASSERT_EQ(decouples.size(), 1U);

  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto c1 = axis_positions(trace, "C1", "cmd");
  // N40-N60 cut while the disc is locked (G51.2 ended only then), up to G50.2 (N70).
  int compared = 0;
  for (std::uint64_t c = block.at(6); c < block.at(9); ++c) {
    ASSERT_NEAR(wrap(2.0 * s1.at(c) - c1.at(c)), 0.0, 0.01) << "cycle " << c;
    ++compared;
  }
  EXPECT_GT(compared, 500);
  // G50.2 slows the disc from 3600 deg/s to rest within its 7200 deg/s^2 (0.5 s), and N80 starts
  // only then. From there C1 moves only as N80's rapid moves it (100 rpm: 1.2 deg a cycle), and
  // ends 90 degrees on from where it stood: the channel took it over there, without a jump.
  const std::uint64_t free = decouples[0]["cycle"].get<std::uint64_t>();
  EXPECT_NEAR((free - block.at(9)) * 0.002, 0.5, 0.03);
  EXPECT_GE(block.at(10), free);
  const double stood = c1.at(free);
  EXPECT_GT(stood, 3000.0);
  for (auto it = c1.upper_bound(free); it != c1.end(); ++it) {
    ASSERT_LE(std::fabs(it->second - std::prev(it)->second), 1.2 + 1e-6) << "cycle " << it->first;
  }
  EXPECT_NEAR(c1.rbegin()->second, stood + 90.0, 1e-3);
  for (const auto& p : events(trace, "pos", "CH1")) {
    if (p["axis"] == "C1" && p["cycle"].get<std::uint64_t>() > block.at(10)) {
      EXPECT_NEAR(p["cmd"].get<double>(), stood + 90.0, 1e-3) << p;
    }
  }
}

// Param 5300.5 = 1 (decision 159): G51.2 (N30, with S1 at speed) ends at once, N40's rapid runs
// while the servo disc catches up, and N50's cut starts only once the disc is in phase.
TEST(PolygonTurning, WithoutWaitTheRapidRunsWhileTheDiscCatchesUpAndTheCutWaits) {
  TestMachine machine("polygon_servo_lathe.yaml", 223);
  const std::string yaml = slurp(machine.path());
  std::ofstream(machine.path()) << std::regex_replace(yaml, std::regex("max_rpm: 1500\\}"),
                                                      "max_rpm: 1500, no_wait: true}");
  const auto trace = run_to_clean_end(
      machine, "tests/integration/programs/polygon/servo_no_wait.nc", {"--trace-pos-every", "1"});
  ASSERT_FALSE(trace.empty());
  EXPECT_TRUE(events(trace, "alarm").empty());
  const auto couples = events(trace, "couple", "C1");
  ASSERT_EQ(couples.size(), 1U);
  const auto block = block_starts(trace);
  const auto s1 = axis_positions(trace, "S1", "act");
  const auto c1 = axis_positions(trace, "C1", "cmd");
  // The disc is in phase (within its node's 0.05 degrees) from `locked` to G50.2 (N60).
  const std::uint64_t coupled = couples[0]["cycle"].get<std::uint64_t>();
  std::uint64_t locked = coupled;
  for (std::uint64_t c = coupled; c < block.at(8); ++c) {
    locked = std::fabs(wrap(2.0 * s1.at(c) - c1.at(c))) > 0.05 ? c + 1 : locked;
  }
  // From rest to 3600 deg/s within 7200 deg/s^2 takes half a second at least.
  EXPECT_GT(locked, coupled + 250);
  EXPECT_LT(block.at(6), coupled + 10);  // the rapid did not wait
  EXPECT_GE(block.at(7), locked);        // the cut did, and starts as the channel sees the lock
  EXPECT_LT(block.at(7), locked + 10);
  std::uint64_t z_there = 0;  // N40's Z1 at its end point
  for (const auto& [c, z] : axis_positions(trace, "Z1", "cmd")) {
    z_there = z_there == 0 && std::fabs(z - 1.0) < 1e-9 ? c : z_there;
  }
  ASSERT_GT(z_there, 0U);
  EXPECT_LT(z_there, locked - 100);  // the rapid ended long before: the cut waited for the disc
  for (std::uint64_t c = block.at(7); c < block.at(8); ++c) {
    ASSERT_NEAR(wrap(2.0 * s1.at(c) - c1.at(c)), 0.0, 0.01) << "cycle " << c;
  }
}

}  // namespace
}  // namespace mcnc::test
