// G160 through the runtime, in lockstep: small_lathe.yaml with a tailstock B1 (node 3 of can0)
// whose drive takes a torque limit (torque_skip: 0x6072 in its RPDO2, 0x6077 in its TPDO2) and
// whose load meets a centre at B-150 (the simulator's contact). The channel sends the limit with
// B1's setpoints, the axis node puts it on the bus, the drive's torque rises to it at the
// centre while the following error grows, the node latches the skip where B1 stands, and the
// channel stops the move and hands the position to the program (#5063). The limit stays while
// X and Z cut and through the retracting G160, until a G00 of B1 cancels it.
#include "bus_recorder.hpp"
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mcnc::test {
namespace {

constexpr std::uint8_t kTailstockNode = 3;
constexpr double kCentre = -150.0;

// small_lathe.yaml with the tailstock B1, at a 2 ms cycle (three axes and B1's second PDOs keep
// the bus under 70 %).
void add_tailstock(const TestMachine& machine) {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto replace = [&](const std::string& what, const std::string& with) {
    const std::size_t at = yaml.find(what);
    ASSERT_NE(at, std::string::npos) << what;
    yaml.replace(at, what.size(), with);
  };
  replace("cycle_us: 1000", "cycle_us: 2000");
  replace("axes: [X1, Z1]", "axes: [X1, Z1, B1]");
  yaml +=
      "\n  - name: B1\n"
      "    address: B\n"
      "    type: linear\n"
      "    bus: can0\n"
      "    node_id: 3\n"
      "    counts_per_unit: 10000\n"
      "    rapid_rate: 6000\n"
      "    max_feed: 3000\n"
      "    acceleration: 1000\n"
      "    in_position: 0.0005\n"
      "    torque_skip: true\n"
      "    drive:\n"
      "      time_constant_s: 0.004\n"
      "      max_velocity: 150\n"
      "      quick_stop_decel: 5000\n"
      "      contact: {at: -150, blocks: below}\n";
  std::ofstream(machine.path()) << yaml;
}

// Where the channel's blocks left `axis`, in order.
std::vector<double> block_ends(const std::vector<nlohmann::json>& trace, const std::string& axis) {
  std::vector<double> ends;
  for (const auto& p : events(trace, "pos", "CH1")) {
    if (p["axis"] == axis) {
      ends.push_back(p["cmd"].get<double>());
    }
  }
  return ends;
}

std::int32_t signed16(const can::CanFrame& f) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8)));
}

TEST(TorqueSkip, TheTailstockPressesAgainstTheCentreWithTheLimitOnTheBus) {
  TestMachine machine("small_lathe.yaml", 108);
  add_tailstock(machine);
  std::vector<nlohmann::json> trace;
  std::vector<can::CanFrame> frames;
  {
    BusRecorder bus("udp:239.255.108.1:" + std::to_string(24000 + 108));
    trace = run_to_clean_end(machine, "tests/integration/programs/g160/tailstock.nc");
    frames = bus.frames();
  }
  EXPECT_TRUE(events(trace, "alarm").empty());
  // B1's block ends: G00 (line 3), G160 (4), G160 back (8), G00 to #5063 + 10 (9).
  const std::vector<double> b = block_ends(trace, "B1");
  ASSERT_GE(b.size(), 4U);
  const auto at = [&](double v) {
    return std::find_if(b.begin(), b.end(), [&](double x) { return std::abs(x - v) < 1e-6; }) !=
           b.end();
  };
  EXPECT_TRUE(at(-140.0));
  // The G160 stopped past the centre by Q (2 mm) and the reaction: the latch reaches the
  // channel a few 2 ms cycles later (0.02 mm each at 10 mm/s), then the braking (under 0.1 mm).
  const auto pressed = std::find_if(b.begin(), b.end(), [](double x) { return x < kCentre; });
  ASSERT_NE(pressed, b.end());
  EXPECT_LT(*pressed, kCentre - 2.0);
  EXPECT_GT(*pressed, kCentre - 2.3);
  // #5063 is where B1 stood at the latch, the centre; the last G00 went 10 above it.
  EXPECT_NEAR(b.back(), kCentre + 10.0, 1e-6);
  EXPECT_TRUE(at(0.0));  // the retract with the limit ran to its end

  // On the wire: B1's RPDO2 carries 0x6072, no limit (1000 %) before the G160, 500 per mille
  // from it through the retract, none again after the G00; its TPDO2 the torque at -50 %.
  std::vector<std::int32_t> limits;
  std::int32_t lowest_torque = 0;
  for (const can::CanFrame& f : frames) {
    if (f.id == 0x300U + kTailstockNode && f.dlc == 2) {
      const std::int32_t v = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8));
      if (limits.empty() || limits.back() != v) {
        limits.push_back(v);
      }
    } else if (f.id == 0x280U + kTailstockNode && f.dlc == 2) {
      lowest_torque = std::min(lowest_torque, signed16(f));
    }
  }
  EXPECT_EQ(limits, (std::vector<std::int32_t>{10000, 500, 10000}));
  EXPECT_LE(lowest_torque, -485);
  EXPECT_GE(lowest_torque, -500);
}

TEST(TorqueSkip, G160OfAnAxisWhoseDriveTakesNoLimitIsRefusedBeforeAnythingMoves) {
  TestMachine machine("small_lathe.yaml", 114);
  add_tailstock(machine);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("tests/integration/programs/g160/no_torque_limit.nc"),
                           "--trace", trace_file},
                          -1, std::chrono::seconds(180));
  // `mcnc run` checks the program against the machine before it starts a process: exit 2,
  // the alarm with the file, line and why, and no trace (nothing ran, nothing moved).
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no_torque_limit.nc:4:0: alarm 1157: G160: the drive of axis Z takes no "
                       "torque limit (torque_skip of the axis in the machine file)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(read_trace(trace_file).empty());
}

}  // namespace
}  // namespace mcnc::test
