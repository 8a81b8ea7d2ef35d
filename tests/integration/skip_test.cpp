// G31 through the runtime: the small lathe's Z1 drive (the simulator) has a touch probe on skip
// input 13 whose input goes on where Z passes -12.5. The channel arms it, the drive latches the
// edge (0x60B9/0x60BA), the axis node reports it in its feedback, and the channel stops the
// move there and hands the position to the program (#5062), all in lockstep. G31.8: the same
// probe passing teeth, every edge latched and stored.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

// small_lathe.yaml with Z1's probe, at a 2 ms cycle (its three full PDOs keep the bus under
// 70 %).
std::string machine_text(const TestMachine& machine) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Where the channel's blocks left Z1, in order.
std::vector<double> z_block_ends(const std::vector<nlohmann::json>& trace) {
  std::vector<double> z_ends;
  for (const auto& p : events(trace, "pos", "CH1")) {
    if (p["axis"] == "Z1") {
      z_ends.push_back(p["cmd"].get<double>());
    }
  }
  return z_ends;
}

// `probe`: the simulated drive's probe input (drive.probe in the machine file).
void add_probe(const TestMachine& machine, const std::string& probe = "{at: -12.5, on: below}") {
  std::string yaml = machine_text(machine);
  const auto replace = [&](const std::string& what, const std::string& with) {
    const std::size_t at = yaml.find(what);
    ASSERT_NE(at, std::string::npos) << what;
    yaml.replace(at, what.size(), with);
  };
  replace("cycle_us: 1000", "cycle_us: 2000");
  replace("  - name: Z1\n", "  - name: Z1\n    touch_probe: {input: 13}\n");
  replace("      max_velocity: 250     # mm/s\n",
          "      max_velocity: 250     # mm/s\n      probe: " + probe + "\n");
  std::ofstream(machine.path()) << yaml;
}

// Runs `program` (Z probes down from 0 to a face at -12.5, goes 1 up, then to 2 above the skip
// position it read, #5062 + 2 with R's 1) and checks where the blocks left Z: the G31 stopped
// past the face within `reaction` mm, far from its programmed end at -50; W1 went on from
// there; #5062 was past the face by at most `reading_error` mm, before Z stopped.
void expect_probed_face(const TestMachine& machine, const std::string& program, double reaction,
                        double reading_error) {
  const auto trace = run_to_clean_end(machine, program);
  EXPECT_TRUE(events(trace, "alarm").empty());
  // The channel's block ends, in order: G00 (line 2), G31 (3), G00 W1 (5), G00 Z (6).
  const std::vector<double> z_ends = z_block_ends(trace);
  ASSERT_GE(z_ends.size(), 4U);
  const double stop = z_ends[1];
  EXPECT_LT(stop, -12.5);
  EXPECT_GT(stop, -12.5 - reaction);
  EXPECT_NEAR(z_ends[2], stop + 1.0, 1e-6);
  EXPECT_LE(z_ends[3], -10.5 + 1e-6);
  EXPECT_GE(z_ends[3], -10.5 - reading_error - 1e-6);
  EXPECT_GT(z_ends[3] - 2.0, stop);
}

TEST(Skip, G31StopsAtTheDrivesTouchProbeAndTheProgramReadsTheLatchedPosition) {
  TestMachine machine("small_lathe.yaml", 147);
  add_probe(machine);
  // The reaction: the latch reaches the channel three or four 2 ms cycles later (under 0.08 mm
  // at 10 mm/s), then the jerk-limited braking (v^2/2a + v a/2j at 1500 mm/s^2 and
  // 75000 mm/s^3: 0.13 mm). #5062 is the drive's latch: -12.5 exactly.
  expect_probed_face(machine, "tests/integration/programs/g31/probe.nc", 0.25, 0.0);
}

// small_lathe.yaml with a PLC whose input `touch` is skip signal 2 (G0014.1) and comes on where
// Z1's feedback passes -12.5 (a sensor of the simulated machine).
void add_plc_skip_signal(const TestMachine& machine) {
  std::string yaml = machine_text(machine);
  yaml +=
      "\nplc:\n"
      "  signals:\n"
      "    - {name: touch, type: input, skip: 2, position: {axis: Z1, at: -12.5, on: below}}\n";
  std::ofstream(machine.path()) << yaml;
}

// G31 P2 (decision 92): the channel stops the move where the PLC's status shows the signal on,
// and #5062 is where Z's feedback stood then.
TEST(Skip, G31PStopsWhereThePlcsSkipSignalComesOn) {
  TestMachine machine("small_lathe.yaml", 197);
  add_plc_skip_signal(machine);
  // The reaction: the signal's way (Z's feedback to the PLC, its status to the channel: two or
  // three 1 ms cycles, 0.03 mm at 10 mm/s), the drive's following error (v tau: 0.04 mm) and
  // the braking (0.13 mm). #5062 is Z's actual position when the channel saw the signal: past
  // the face by the signal's way, at most five cycles' travel (0.05 mm).
  expect_probed_face(machine, "tests/integration/programs/g31/plc_signal.nc", 0.25, 0.05);
}

// Z1's probe passing three 1 mm teeth below -10, 2 mm apart: on at -10, -12 and -14 going down.
const std::string kTeeth = "{at: -10, on: below, teeth: {pitch: 2, width: 1, count: 3}}";

// G31.8 through the runtime (decision 123): the channel asks the drive's continuous latching
// (0x60B8 bit 1), the drive latches every edge and counts it (0x60B9 bits 6-7), the axis node
// reports the count and the last position in its feedback, and the channel stores each
// position in #P.. and their count in #R.
// Runs `program` on a small lathe with kTeeth on `domain`: where its blocks left Z1, in order,
// none after an alarm.
std::vector<double> z_ends_passing_teeth(int domain, const std::string& program) {
  TestMachine machine("small_lathe.yaml", domain);
  add_probe(machine, kTeeth);
  const auto trace = run_to_clean_end(machine, program);
  EXPECT_TRUE(events(trace, "alarm").empty());
  return z_block_ends(trace);
}

TEST(MultiSkip, G318StoresTheDrivesLatchAtEveryToothAndRunsToItsEnd) {
  const std::vector<double> z_ends =
      z_ends_passing_teeth(157, "tests/integration/programs/g318/teeth.nc");
  // Block ends: G00 (line 2), G31.8 (3), G00 Z[#500] .. Z[#502] (4-6), G00 Z[-#1] (7), M30.
  ASSERT_GE(z_ends.size(), 6U) << ::testing::PrintToString(z_ends);
  EXPECT_NEAR(z_ends[1], -20.0, 1e-6);  // three teeth of Q5: on to its end point
  // The drive's latches, exactly where its input switched.
  EXPECT_NEAR(z_ends[2], -10.0, 1e-6);
  EXPECT_NEAR(z_ends[3], -12.0, 1e-6);
  EXPECT_NEAR(z_ends[4], -14.0, 1e-6);
  EXPECT_NEAR(z_ends[5], -3.0, 1e-6);  // #1 = 3
}

TEST(MultiSkip, G318QStopsTheMoveAtItsLastTooth) {
  const std::vector<double> z_ends =
      z_ends_passing_teeth(158, "tests/integration/programs/g318/two_teeth.nc");
  // Block ends: G00 (line 2), G31.8 (3), G00 W1 (5), G00 Z[#511-#1] (6), M30.
  ASSERT_GE(z_ends.size(), 4U) << ::testing::PrintToString(z_ends);
  // Stopped past the second tooth within the latch's way to the channel (three or four 2 ms
  // cycles, under 0.08 mm at 10 mm/s) and the braking (0.13 mm), before the third at -14.
  const double stop = z_ends[1];
  EXPECT_LT(stop, -12.0);
  EXPECT_GT(stop, -12.25);
  EXPECT_NEAR(z_ends[2], stop + 1.0, 1e-6);
  EXPECT_NEAR(z_ends[3], -14.0, 1e-6);  // #511 = -12 exactly, #1 = 2
}

}  // namespace
}  // namespace mcnc::test
