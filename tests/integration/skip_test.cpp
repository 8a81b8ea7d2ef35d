// G31 through the runtime: the small lathe's Z1 drive (the simulator) has a touch probe on skip
// input 13 whose input goes on where Z passes -12.5. The channel arms it, the drive latches the
// edge (0x60B9/0x60BA), the axis node reports it in its feedback, and the channel stops the
// move there and hands the position to the program (#5062), all in lockstep.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace mcnc::test {
namespace {

// small_lathe.yaml with Z1's probe, at a 2 ms cycle (its three full PDOs keep the bus under
// 70 %).
void add_probe(const TestMachine& machine) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::string yaml = text.str();
  const auto replace = [&](const std::string& what, const std::string& with) {
    const std::size_t at = yaml.find(what);
    ASSERT_NE(at, std::string::npos) << what;
    yaml.replace(at, what.size(), with);
  };
  replace("cycle_us: 1000", "cycle_us: 2000");
  replace("  - name: Z1\n", "  - name: Z1\n    touch_probe: {input: 13}\n");
  replace("      max_velocity: 250     # mm/s\n",
          "      max_velocity: 250     # mm/s\n      probe: {at: -12.5, on: below}\n");
  std::ofstream(machine.path()) << yaml;
}

TEST(Skip, G31StopsAtTheDrivesTouchProbeAndTheProgramReadsTheLatchedPosition) {
  TestMachine machine("small_lathe.yaml", 147);
  add_probe(machine);
  const auto trace = run_to_clean_end(machine, "tests/integration/programs/g31/probe.nc");
  EXPECT_TRUE(events(trace, "alarm").empty());
  // The channel's block ends, in order: G00 (line 2), G31 (3), G00 W1 (5), G00 Z (6).
  std::vector<double> z_ends;
  for (const auto& p : events(trace, "pos", "CH1")) {
    if (p["axis"] == "Z1") {
      z_ends.push_back(p["cmd"].get<double>());
    }
  }
  ASSERT_GE(z_ends.size(), 4U);
  // G31 stopped past the face within the reaction (the latch reaches the channel three or four
  // 2 ms cycles later: under 0.08 mm at 10 mm/s) and the jerk-limited braking (v^2/2a + v a/2j
  // at 1500 mm/s^2 and 75000 mm/s^3: 0.13 mm), far from its programmed end at -50.
  const double stop = z_ends[1];
  EXPECT_LT(stop, -12.5);
  EXPECT_GT(stop, -12.75);
  // W1 went on from where it stopped.
  EXPECT_NEAR(z_ends[2], stop + 1.0, 1e-6);
  // #5062 = -12.5 (the drive's latch) and #100 = 1: Z[#101+#100*2] = -10.5.
  EXPECT_NEAR(z_ends[3], -10.5, 1e-6);
}

}  // namespace
}  // namespace mcnc::test
