// Inclined-axis control through the runtime (spec dafeng L4653-4767): the small lathe with X1
// inclined at -30 degrees to Z1 runs the spec's worked table in lockstep. The channel's start
// position comes from the axes' feedback (inclined), the axis nodes are commanded the inclined
// positions of the table's machine column, and #5002 reads the Cartesian Z.
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

void add_inclined_axis(const TestMachine& machine) {
  ASSERT_TRUE(insert_in_machine_file(machine, "    axes: [X1, Z1]\n",
                                     "    inclined: {axis: X, orthogonal: Z, angle: -30}\n"));
}

TEST(InclinedAxis, TheAxesAreCommandedTheSpecsMachineColumn) {
  TestMachine machine("small_lathe.yaml", 111);
  add_inclined_axis(machine);
  const auto trace = run_to_clean_end(machine, "tests/integration/programs/inclined/table.nc");
  EXPECT_TRUE(events(trace, "alarm").empty());
  // Each block end's commanded X1 (the slide's radius) and Z1, in order.
  std::vector<std::array<double, 2>> ends;
  for (const auto& p : events(trace, "pos", "CH1")) {
    if (p["axis"] == "X1") {
      ends.push_back({p["cmd"].get<double>(), 0.0});
    } else if (p["axis"] == "Z1" && !ends.empty()) {
      ends.back()[1] = p["cmd"].get<double>();
    }
  }
  const double tan30 = std::tan(-30.0 * M_PI / 180.0);
  const double cos30 = std::cos(-30.0 * M_PI / 180.0);
  // The table's machine column (X as a radius here), then G01 X20 Z-10 and G00 Z[#5002+5]:
  // #5002 is the Cartesian -10, so Z-5 at X radius 10.
  const std::vector<std::array<double, 2>> expected = {
      {0.0, 0.0},
      {-50.0, -50.0},
      {5.0 / cos30, 5.0 * tan30},
      {-5.0 / cos30, 5.0 - 5.0 * tan30},
      {10.0 / cos30, -10.0 + 10.0 * tan30},
      {10.0 / cos30, -5.0 + 10.0 * tan30},
      {0.0, 0.0},
  };
  // The moving blocks' ends in the program's order (a block that does not move may end too).
  std::size_t found = 0;
  for (const auto& e : ends) {
    if (found < expected.size() && std::fabs(e[0] - expected[found][0]) < 2e-6 &&
        std::fabs(e[1] - expected[found][1]) < 2e-6) {
      ++found;
    }
  }
  EXPECT_EQ(found, expected.size())
      << "found " << found << " of the table's positions in " << ends.size() << " block ends";
}

}  // namespace
}  // namespace mcnc::test
