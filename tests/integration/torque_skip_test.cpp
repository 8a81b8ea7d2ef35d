// G160 through the runtime, in lockstep: small_lathe.yaml with a tailstock B1 (node 3 of can0)
// whose drive takes a torque limit (torque_skip: 0x6072 in its RPDO2, 0x6077 in its TPDO2) and
// whose load meets a centre at B-150 (the simulator's contact). The channel sends the limit with
// B1's setpoints, the axis node puts it on the bus, the drive's torque rises to it at the
// centre while the following error grows, the node latches the skip where B1 stands, and the
// channel stops the move and hands the position to the program (#5063). The limit stays while
// X and Z cut and through the retracting G160, until a G00 of B1 cancels it. G31 P98/P99 go
// the same way with B1's load ratio as the limit (decision 116), P99 also on Z1's touch probe.
// G10 L14 P9 limits B1's torque on the same bus, and G10 L14 P1 watches its reported load
// (decisions 120, 121). G10 L14 P10-P12 push B1 into the centre in torque mode (decision 152).
#include "bus_recorder.hpp"
#include "tests/integration/harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::test {
namespace {

constexpr std::uint8_t kTailstockNode = 3;
constexpr double kCentre = -150.0;

// Rewrites the machine file: each `what` replaced by its `with` (each must be there), then
// `more` appended.
void edit_machine(const TestMachine& machine,
                  const std::vector<std::pair<std::string, std::string>>& replacements,
                  const std::string& more = "") {
  std::ifstream in(machine.path());
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  for (const auto& [what, with] : replacements) {
    const std::size_t at = yaml.find(what);
    ASSERT_NE(at, std::string::npos) << what;
    yaml.replace(at, what.size(), with);
  }
  std::ofstream(machine.path()) << yaml << more;
}

// small_lathe.yaml with the tailstock B1, at a 2 ms cycle (three axes and B1's second PDOs keep
// the bus under 70 %).
void add_tailstock(const TestMachine& machine) {
  edit_machine(machine,
               {{"cycle_us: 1000", "cycle_us: 2000"}, {"axes: [X1, Z1]", "axes: [X1, Z1, B1]"}},
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
               "      contact: {at: -150, blocks: below}\n");
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

// add_tailstock's machine with Z1's touch probe on input 13, on where Z1 passes -12.5 (as
// integration.Skip's), and B1's load ratio of param 5511 at 50 %.
void add_probe_and_load_ratio(const TestMachine& machine) {
  add_tailstock(machine);
  edit_machine(machine,
               {{"  - name: Z1\n", "  - name: Z1\n    touch_probe: {input: 13}\n"},
                {"      max_velocity: 250     # mm/s\n",
                 "      max_velocity: 250     # mm/s\n      probe: {at: -12.5, on: below}\n"},
                {"    torque_skip: true\n", "    torque_skip: true\n    skip_load: 50\n"}});
}

std::int32_t signed16(const can::CanFrame& f) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8)));
}

// B1's 0x6072 values in the order they changed, and the lowest torque its TPDO2 reported while
// a limit stood (a move that cancels it starts with the command past the part: the drive's
// peak torque until the command backs off).
// What B1's frames on the bus say: each change of its torque limit (0x6072, RPDO2) in order,
// and the lowest torque it reported (TPDO2) while a limit stood.
struct BusLimits {
  std::vector<std::int32_t> limits;
  std::int32_t lowest_torque = 0;
};
BusLimits limits_on_the_bus(const std::vector<can::CanFrame>& frames) {
  BusLimits bus;
  for (const can::CanFrame& f : frames) {
    if (f.id == 0x300U + kTailstockNode && f.dlc == 2) {
      const std::int32_t v = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8));
      if (bus.limits.empty() || bus.limits.back() != v) {
        bus.limits.push_back(v);
      }
    } else if (f.id == 0x280U + kTailstockNode && f.dlc == 2 && !bus.limits.empty() &&
               bus.limits.back() < 10000) {
      bus.lowest_torque = std::min(bus.lowest_torque, signed16(f));
    }
  }
  return bus;
}

// No limit, 500 per mille while one block held B1 against the centre, none again; the torque
// there at -50 %.
void expect_held_at_half_torque_once(const std::vector<can::CanFrame>& frames) {
  const BusLimits bus = limits_on_the_bus(frames);
  EXPECT_EQ(bus.limits, (std::vector<std::int32_t>{10000, 500, 10000}));
  EXPECT_LE(bus.lowest_torque, -485);
  EXPECT_GE(bus.lowest_torque, -500);
}

// A run to its clean end, with every frame of the bus (that of the machine's domain).
struct Recorded {
  std::vector<nlohmann::json> trace;
  std::vector<can::CanFrame> frames;
};
Recorded run_recording_the_bus(const TestMachine& machine, int domain, const std::string& program,
                               const std::vector<std::string>& extra = {}) {
  Recorded r;
  BusRecorder bus("udp:239.255." + std::to_string(domain) + ".1:" + std::to_string(24000 + domain));
  r.trace = run_to_clean_end(machine, program, extra);
  r.frames = bus.frames();
  return r;
}

TEST(TorqueSkip, TheTailstockPressesAgainstTheCentreWithTheLimitOnTheBus) {
  TestMachine machine("small_lathe.yaml", 108);
  add_tailstock(machine);
  const Recorded r =
      run_recording_the_bus(machine, 108, "tests/integration/programs/g160/tailstock.nc");
  const std::vector<nlohmann::json>& trace = r.trace;
  const std::vector<can::CanFrame>& frames = r.frames;
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
  expect_held_at_half_torque_once(frames);
}

TEST(TorqueSkip, G31P98StopsWhereTheTailstockIsHeldBackAtTheLoadRatioOfG10L14P6) {
  TestMachine machine("small_lathe.yaml", 113);
  add_tailstock(machine);
  const Recorded r =
      run_recording_the_bus(machine, 113, "tests/integration/programs/g160/load_skip.nc");
  const std::vector<nlohmann::json>& trace = r.trace;
  const std::vector<can::CanFrame>& frames = r.frames;
  EXPECT_TRUE(events(trace, "alarm").empty());
  // Every block end gives each axis's position; B1's first below the centre is the G31's.
  const std::vector<double> b = block_ends(trace, "B1");
  const auto pressed = std::find_if(b.begin(), b.end(), [](double v) { return v < kCentre; });
  ASSERT_NE(pressed, b.end());
  // Stopped past the centre by the reaction (the latch reaches the channel a few 2 ms cycles
  // later, 0.01 mm each at 5 mm/s) and the braking, with no following error to wait for.
  EXPECT_GT(*pressed, kCentre - 0.25);
  // #5063 is where B1 stood at the latch, the centre: the last G00 went 10 above it.
  EXPECT_NEAR(b.back(), kCentre + 10.0, 0.005);
  // R100 = 1: X went to 30 (the trace gives the slide's radius).
  const std::vector<double> x = block_ends(trace, "X1");
  ASSERT_FALSE(x.empty());
  EXPECT_NEAR(x.back(), 15.0, 1e-6);
  // On the wire: no limit before the G31, G10 L14 P6's 50 % (500 per mille) from it until the
  // G00 of B1, none after; the torque at the centre at -50 %.
  expect_held_at_half_torque_once(frames);
}

TEST(TorqueSkip, G31P99StopsAtTheLoadOrAtTheTouchProbeWhicheverComesFirst) {
  TestMachine machine("small_lathe.yaml", 115);
  add_probe_and_load_ratio(machine);
  const Recorded r =
      run_recording_the_bus(machine, 115, "tests/integration/programs/g160/probe_or_load.nc");
  const std::vector<nlohmann::json>& trace = r.trace;
  const std::vector<can::CanFrame>& frames = r.frames;
  EXPECT_TRUE(events(trace, "alarm").empty());
  // Every block end gives each axis's position. The first G31 (line 4): B1 held back at the
  // centre at 50 %, halfway, Z1 at -1, short of the probe.
  const std::vector<double> b = block_ends(trace, "B1");
  const std::vector<double> z = block_ends(trace, "Z1");
  ASSERT_EQ(b.size(), z.size());
  const auto pressed = std::find_if(b.begin(), b.end(), [](double v) { return v < kCentre; });
  ASSERT_NE(pressed, b.end());
  const auto i = static_cast<std::size_t>(pressed - b.begin());
  ASSERT_GE(b.size(), i + 4);
  EXPECT_GT(b[i], kCentre - 0.25);
  EXPECT_NEAR(z[i], -1.0, 0.02);
  EXPECT_NEAR(b[i + 1], kCentre + 10.0, 0.005);  // #5063: the centre
  // The second (line 7), Z1 from -1 to -21 with B1 from -140 to -146: Z1's probe at -12.5
  // comes first, at 57.5 % of the way (B1 at -143.45), long before B1 could reach the centre.
  EXPECT_LT(z[i + 2], -12.5);
  EXPECT_GT(z[i + 2], -12.5 - 0.25);
  EXPECT_NEAR(b[i + 2], -143.45, 0.05);
  EXPECT_NEAR(z.back(), -10.5, 0.005);  // #5062: the probe's latch
  // B1's limit on the wire: param 5511's 50 % from the first G31 to the G00, again from the
  // second G31 to the end (a limit stands until a move of its axis).
  const BusLimits bus = limits_on_the_bus(frames);
  // (Its last change, back to none after M30, is not this test's: nothing moves B1 then.)
  ASSERT_GE(bus.limits.size(), 4U);
  EXPECT_EQ(std::vector<std::int32_t>(bus.limits.begin(), bus.limits.begin() + 4),
            (std::vector<std::int32_t>{10000, 500, 10000, 500}));
  EXPECT_LE(bus.lowest_torque, -485);
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

// G10 L14 P9 (decision 120): B1 pressed into the centre by less than its in-position width, so
// that the blocks end in position; its position loop then asks for ever more torque. Under
// the limit the drive gives 30 % and no more; once P9 B0 lifts it, the torque rises past that.
TEST(TorqueLimit, P9LimitsTheTailstocksTorqueAgainstTheCentreUntilCancelled) {
  TestMachine machine("small_lathe.yaml", 193);
  add_tailstock(machine);
  const Recorded r =
      run_recording_the_bus(machine, 193, "tests/integration/programs/g10_l14/torque_limit.nc");
  EXPECT_TRUE(events(r.trace, "alarm").empty());
  // On the wire: no limit, 300 per mille from line 3 to line 6, none again.
  const BusLimits bus = limits_on_the_bus(r.frames);
  EXPECT_EQ(bus.limits, (std::vector<std::int32_t>{10000, 300, 10000}));
  EXPECT_LE(bus.lowest_torque, -290);  // pressed at the limit, the way B1 moved
  EXPECT_GE(bus.lowest_torque, -300);  // and never beyond it
  // Without the limit the same press takes more.
  std::int32_t unlimited = 0;
  int changes = 0;  // of the limit: 2 once P9 B0 lifted it
  std::int32_t limit = -1;
  for (const can::CanFrame& f : r.frames) {
    if (f.id == 0x300U + kTailstockNode && f.dlc == 2) {
      const std::int32_t v = f.data[0] | (f.data[1] << 8);
      changes += v != limit && limit != -1 ? 1 : 0;
      limit = v;
    } else if (changes == 2 && f.id == 0x280U + kTailstockNode && f.dlc == 2) {
      unlimited = std::min(unlimited, signed16(f));
    }
  }
  EXPECT_LT(unlimited, -400);
  // B1 stood at the centre, then went back to -140.
  const std::vector<double> b = block_ends(r.trace, "B1");
  ASSERT_FALSE(b.empty());
  EXPECT_NEAR(b.back(), -140.0, 1e-6);
}

// G10 L14 P1 (decision 121): B1's load, as its drive reports it, watched in its G01 moves at
// 80 %. The feed to B-149.5 takes little; the one into the centre at B-150 presses until the
// load passes 80 %: alarm 1280 at its line, and nothing moves from then on (B1 stays at the
// centre, X never goes to 40).
TEST(TorqueLimit, P1OverloadIsAnAlarmAtTheG01AndNothingMovesAfter) {
  TestMachine machine("small_lathe.yaml", 194);
  add_tailstock(machine);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run(
      {bin("mcnc"), "run", machine.path(), "--program",
       "CH1=" + source("tests/integration/programs/g10_l14/overload.nc"), "--trace", trace_file},
      -1, std::chrono::seconds(180));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<nlohmann::json> trace = read_trace(trace_file);
  const std::vector<nlohmann::json> alarms = events(trace, "alarm");
  ASSERT_EQ(alarms.size(), 1U);
  const nlohmann::json& a = alarms.front();
  EXPECT_EQ(a["number"], 1280);
  EXPECT_EQ(a["line"], 6);  // the G01 into the centre
  EXPECT_EQ(a["text"].get<std::string>().substr(0, 30), "G10 L14 P1: the load of axis B") << a;
  // Raised once B1 stood at the centre: its command had passed it by less than the travel of
  // the cycles the load needs to rise (5 mm/s: 0.01 mm per 2 ms cycle).
  const auto alarm_cycle = a["cycle"].get<std::uint64_t>();
  double b_cmd_then = 0.0;
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "B1" && p["cycle"].get<std::uint64_t>() <= alarm_cycle) {
      b_cmd_then = p["cmd"].get<double>();
    }
  }
  EXPECT_LT(b_cmd_then, -149.9);
  EXPECT_GT(b_cmd_then, -150.2);
  // After it, neither B1 nor X1 moves: every sample of their nodes stands where the first after
  // the alarm stood.
  for (const std::string axis : {"B1", "X1"}) {
    std::optional<double> stood;
    for (const nlohmann::json& p : events(trace, "pos")) {
      if (p["axis"] != axis || p["src"] == "CH1" ||
          p["cycle"].get<std::uint64_t>() <= alarm_cycle + 4) {
        continue;
      }
      stood = stood.value_or(p["cmd"].get<double>());
      EXPECT_NEAR(p["cmd"].get<double>(), *stood, 1e-9) << axis << " " << p;
    }
    ASSERT_TRUE(stood.has_value()) << axis;
  }
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "X1") {
      EXPECT_LT(p["cmd"].get<double>(), 10.0 + 1e-6) << p;  // X20 (a radius of 10): never X40
    }
  }
}

// G10 L14 P4/P5 and P41/P51 (L4770-4849, decision 141): B1 fed into the centre by G31 P98
// (skipping at its 50 % ratio) with timer 4 counting its load above 20 % and timer 5 above
// 900 %. The checks run once the blocks before them ended: #100 gets B's bit (the third axis:
// 4, as the spec's example reads Z), #101 nothing, so X goes to 20 + 4 * 10 = 60.
TEST(LoadTimers, TheChecksHandTheAxesBitsToTheProgramAtTheirBlock) {
  TestMachine machine("small_lathe.yaml", 212);
  add_tailstock(machine);
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--program",
                           "CH1=" + source("tests/integration/programs/g10_l14/load_timers.nc"),
                           "--trace", trace_file},
                          -1, std::chrono::seconds(180));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::vector<nlohmann::json> trace = read_trace(trace_file);
  EXPECT_TRUE(events(trace, "alarm").empty());
  // B1 stopped at the centre (the skip), then went back; X1 went to 60 (a radius of 30) only
  // after the checks: its last block end.
  const std::vector<double> x = block_ends(trace, "X1");
  ASSERT_FALSE(x.empty());
  EXPECT_NEAR(x.back(), 30.0, 1e-6);
  double b_min = 0.0;
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "B1" && p["src"] != "CH1") {
      b_min = std::min(b_min, p["act"].get<double>());
    }
  }
  EXPECT_GT(b_min, -150.01);  // held at the centre
  EXPECT_LT(b_min, -149.9);
}

// add_tailstock's machine with B1's torque mode, at 30 rpm where no P11 sets one (param 5521).
void add_torque_mode_tailstock(const TestMachine& machine) {
  add_tailstock(machine);
  edit_machine(machine, {{"    torque_skip: true\n",
                          "    torque_skip: true\n    torque_mode: true\n"
                          "    torque_mode_speed: 30\n"}});
}

// G10 L14 P10-P12 (decision 152): B1 with torque mode (its drive's CST: the target torque 0x6071
// and the speed limit 0x6080 in its RPDO2 after 0x6072) pushed from B-148 into the centre at
// -50 % and 30 rpm (param 5521: 5 mm/s at 10 mm a revolution). Its drive's torque (TPDO2) holds
// at the set torque against the centre, nothing moves B1 while X cuts, and P12 takes it back to
// position control where it stands: its command never jumps, and the G00 retracts from there.
TEST(TorqueMode, TheTailstockHoldsItsSetTorqueAgainstTheCentreAndP12TakesItBackWhereItStands) {
  constexpr int kDomain = 217;
  TestMachine machine("small_lathe.yaml", kDomain);
  add_torque_mode_tailstock(machine);
  const Recorded r =
      run_recording_the_bus(machine, kDomain, "tests/integration/programs/g10_l14/torque_mode.nc",
                            {"--trace-pos-every", "1"});
  EXPECT_TRUE(events(r.trace, "alarm").empty());
  // On the wire: B1's RPDO2 (8 bytes: 0x6072, 0x6071, 0x6080) carries -500 per mille and 30 rpm
  // from P10 to P12, 0 before and after; its TPDO2 the drive's torque.
  std::vector<std::int32_t> targets;  // each change of 0x6071
  std::vector<std::int32_t> held;     // the torque reported while -500 was set
  for (const can::CanFrame& f : r.frames) {
    if (f.id == 0x300U + kTailstockNode && f.dlc == 8) {
      const std::int32_t target =
          static_cast<std::int16_t>(static_cast<std::uint16_t>(f.data[2] | (f.data[3] << 8)));
      const std::uint32_t speed = static_cast<std::uint32_t>(f.data[4]) |
                                  (static_cast<std::uint32_t>(f.data[5]) << 8) |
                                  (static_cast<std::uint32_t>(f.data[6]) << 16) |
                                  (static_cast<std::uint32_t>(f.data[7]) << 24);
      if (targets.empty() || targets.back() != target) {
        targets.push_back(target);
      }
      EXPECT_EQ(speed, target != 0 ? 30U : 0U);
    } else if (f.id == 0x280U + kTailstockNode && f.dlc == 2 && !targets.empty() &&
               targets.back() == -500) {
      held.push_back(signed16(f));
    }
  }
  EXPECT_EQ(targets, (std::vector<std::int32_t>{0, -500, 0}));
  // Held against the centre for the last half of the push (the dwell and the cut): at the set
  // torque, within 3 %.
  ASSERT_GT(held.size(), 400U);
  for (std::size_t i = held.size() / 2; i < held.size(); ++i) {
    EXPECT_NEAR(held[i], -500, 15) << i;
  }
  // B1's node, every cycle: at the centre, never past it; no step of its command larger than a
  // cycle of its rapid (100 mm/s: 0.2 mm per 2 ms): no jump back to -148 at P12.
  std::optional<double> last;
  double b_min = 0.0;
  for (const nlohmann::json& p : events(r.trace, "pos")) {
    if (p["axis"] != "B1" || p["src"] == "CH1") {
      continue;
    }
    const double cmd = p["cmd"].get<double>();
    b_min = std::min(b_min, p["act"].get<double>());
    if (last) {
      EXPECT_LT(std::abs(cmd - *last), 0.21) << p;
    }
    last = cmd;
  }
  EXPECT_GT(b_min, -150.01);
  EXPECT_LT(b_min, -149.9);
  // Block ends: B1 stood at the centre while X cut (line 6), then the G00 went to -140; X1 at
  // a radius of 5.
  const std::vector<double> b = block_ends(r.trace, "B1");
  ASSERT_FALSE(b.empty());
  EXPECT_NEAR(b.back(), -140.0, 1e-6);
  const std::vector<double> x = block_ends(r.trace, "X1");
  ASSERT_FALSE(x.empty());
  EXPECT_NEAR(x.back(), 5.0, 1e-6);
}

// A block that moves B1 while it is in torque mode: alarm 1263 at its line before it moves
// anything; B1 keeps pushing.
TEST(TorqueMode, ABlockThatMovesTheTailstockInTorqueModeIsAnAlarmAtItsLine) {
  constexpr int kDomain = 217;
  TestMachine machine("small_lathe.yaml", kDomain);
  add_torque_mode_tailstock(machine);
  const std::string program = machine.file("moves_b.nc");
  std::ofstream(program) << "G98 G00 X20 Z0\nG00 B-148\nG10 L14 P10 B-50\nG04 X1\n"
                            "G00 X30 B-140\nM30\n";
  const std::string trace_file = machine.file("trace.jsonl");
  const RunResult r = run(
      {bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program, "--trace", trace_file},
      -1, std::chrono::seconds(180));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<nlohmann::json> trace = read_trace(trace_file);
  const std::vector<nlohmann::json> alarms = events(trace, "alarm");
  ASSERT_EQ(alarms.size(), 1U);
  EXPECT_EQ(alarms.front()["number"], 1263);
  EXPECT_EQ(alarms.front()["line"], 5);
  bool b_pushed = false;  // B1 reached -148 (line 2): from then on it never goes back up
  for (const nlohmann::json& p : events(trace, "pos")) {
    if (p["axis"] == "X1") {
      EXPECT_LT(p["cmd"].get<double>(), 10.0 + 1e-6) << p;  // X20 (radius 10): never X30
    }
    if (p["axis"] == "B1") {
      const double cmd = p["cmd"].get<double>();
      EXPECT_TRUE(!b_pushed || cmd < -147.99) << p;
      b_pushed = b_pushed || cmd < -147.99;
    }
  }
  EXPECT_TRUE(b_pushed);
}

}  // namespace
}  // namespace mcnc::test
