// G68.1/G69.1 coordinate rotation (spec dafeng L4502-4652) and G51.1/G50.1 programmable mirror
// (L4233-4278): positions, arcs, offsets after the turn, the restrictions and their alarms.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>
#include <random>
#include <sstream>

namespace mcnc::interp::test {
namespace {

const double kCos60 = 0.5;
const double kSin60 = std::sqrt(3.0) / 2.0;

// ---- G51.1 / G50.1

TEST(InterpMirror, SpecExampleMirrorsTheSecondPassAboutX0) {
  // Spec dafeng L4254-4276: the pass at X100/X90 runs again at X-100/X-90.
  RunResult r = run_ok(
      "G50.1 X0\nM98 Q100\nG51.1 X0\nM98 Q100\nG50.1 X0\nM30\n"
      "N100 G00 X100.0 Z0\nG01 Z-10 F200\nG01 X90 Z-20 F300\nG0 Z0\nM99\n");
  const std::vector<Command> starts = r.at_line(7);
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_AT(starts[0], 50, 0);
  EXPECT_AT(starts[1], -50, 0);
  const std::vector<Command> moves = r.at_line(9);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_AT(moves[0], 45, -20);
  EXPECT_AT(moves[1], -45, -20);
}

TEST(InterpMirror, MirrorsAboutTheGivenPositionAndFlipsArcs) {
  RunResult r =
      run_ok("G00 X0 Z0\nG51.1 X10\nG00 X20 Z0\nG02 X40 Z-10 R10 F100\nG50.1\nG00 X20 Z0\nM30\n");
  const std::vector<Command> rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 3u);
  EXPECT_AT(rapids[1], 0, 0);  // X20 about X10 (diameters): X0
  const std::vector<Command> arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_AT(arcs[0], -10, -10);
  EXPECT_EQ(arcs[0].direction, ArcDirection::ccw);  // G02 mirrored on one plane axis
  EXPECT_NEAR(arcs[0].center[0], 0.0, 1e-9);        // centre Z0 ...
  EXPECT_NEAR(arcs[0].center[1], -10.0, 1e-9);      // ... X20 mirrored about X5 (radii)
  EXPECT_AT(rapids[2], 10, 0);                      // G50.1 alone ends the mirror
}

TEST(InterpMirror, BothAxesMirroredKeepTheArcSense) {
  RunResult r = run_ok("G51.1 X0 Z0\nG00 X0 Z0\nG02 X20 Z-10 R10 F100\nM30\n");
  const std::vector<Command> arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_AT(arcs[0], -10, 10);
  EXPECT_EQ(arcs[0].direction, ArcDirection::cw);
}

TEST(InterpMirror, G501CancelsTheNamedAxisOnlyAndModalReadsIt) {
  RunResult r = run_ok(
      "G51.1 X0 Z0\nIF[#4022 NE 51.1] #3000=1 (group 22)\nG50.1 X0\n"
      "IF[#4022 NE 51.1] #3000=2 (still Z)\nG00 X20 Z5\nG50.1 Z0\n"
      "IF[#4022 NE 50.1] #3000=3 (off)\nM30\n");
  ASSERT_EQ(r.of(Op::rapid).size(), 1u);
  EXPECT_AT(r.of(Op::rapid)[0], 10, -5);
}

// ---- G68.1 / G69.1

TEST(InterpRotation, SpecExampleTurnsTheHolePositions) {
  // Spec dafeng L4619-4650 without its drilling: X210 Z20 in the frame turned 60 degrees about
  // X100 Z0; G69.1 returns to the unturned frame.
  RunResult r = run_ok(
      "G00 X400 Z150\nG68.1 X100 Z0 R60\nG00 X210 Z20\nG00 X340\nG69.1\nG00 X400 Z150\nM30\n");
  const std::vector<Command> rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 4u);
  // (Z20, X105) is (20, 55) from the centre (Z0, X50).
  EXPECT_AT(rapids[1], 50 + 20 * kSin60 + 55 * kCos60, 20 * kCos60 - 55 * kSin60);
  EXPECT_AT(rapids[2], 50 + 20 * kSin60 + 120 * kCos60, 20 * kCos60 - 120 * kSin60);
  EXPECT_AT(rapids[3], 200, 150);
}

TEST(InterpRotation, OmittedCentreIsTheCurrentPositionAndIncrementsAreTurned) {
  RunResult r = run_ok("G00 X20 Z10\nG68.1 R90\nG00 W10\nG00 U10\nM30\n");
  const std::vector<Command> rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 3u);
  EXPECT_AT(rapids[1], 20, 10);  // +Z turned 90 degrees towards +X
  EXPECT_AT(rapids[2], 20, 5);   // +X (5 as a radius) turned towards -Z
}

TEST(InterpRotation, AnglesCountModulo360) {
  RunResult a = run_ok("G00 X0 Z0\nG68.1 X0 Z0 R400\nG00 Z10\nM30\n");
  RunResult b = run_ok("G00 X0 Z0\nG68.1 X0 Z0 R40\nG00 Z10\nM30\n");
  ASSERT_EQ(a.of(Op::rapid).size(), 2u);
  ASSERT_EQ(b.of(Op::rapid).size(), 2u);
  EXPECT_AT(a.of(Op::rapid)[1], b.of(Op::rapid)[1].to[0], b.of(Op::rapid)[1].to[1]);
  EXPECT_NEAR(b.of(Op::rapid)[1].to[0], 10 * std::sin(40 * M_PI / 180), 1e-9);
}

TEST(InterpRotation, OffsetsApplyAfterTheTurn) {
  InterpreterConfig c = lathe();
  c.work_offsets[1] = {0, 100};  // G54: Z100
  c.tool_geometry[1] = {4, 1};   // X4 (diameter), Z1
  c.tool_geometry[2] = {10, 3};
  RunResult r = run_ok("T0101\nG00 X0 Z0\nG68.1 X0 Z0 R90\nG00 Z10\nT0102\nG00 X0 Z10\nM30\n", c);
  const std::vector<Command> rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 3u);
  EXPECT_AT(rapids[0], 2, 101);
  EXPECT_AT(rapids[1], 12, 101);  // (Z10, X0) turned to (Z0, X10), then the offsets
  EXPECT_AT(rapids[2], 15, 103);  // the new tool's offset is not turned
}

TEST(InterpRotation, ArcsKeepTheirSenseAndTurnTheirCentre) {
  RunResult r = run_ok("G00 X0 Z0\nG68.1 X0 Z0 R90\nG03 X0 Z-20 R10 F100\nM30\n");
  const std::vector<Command> arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_AT(arcs[0], -20, 0);  // Z-20 turned 90 degrees: X-20 (radius)
  EXPECT_EQ(arcs[0].direction, ArcDirection::ccw);
  EXPECT_NEAR(arcs[0].center[0], 0.0, 1e-9);    // Z
  EXPECT_NEAR(arcs[0].center[1], -10.0, 1e-9);  // X
}

// A cycle in the turned frame is the unturned cycle turned: G71's contour is read in the frame.
TEST(InterpRotation, CyclesRunInTheTurnedFrame) {
  const std::string cycle =
      "G00 X100 Z10\nG71 U2 R1\nG71 P10 Q20 U0.5 W0.2 F100\nN10 G00 X40\nG01 Z-20\nX60 Z-30\n"
      "N20 X100\nM30\n";
  RunResult plain = run_ok(cycle);
  RunResult turned = run_ok("G68.1 X0 Z0 R90\n" + cycle);
  ASSERT_EQ(plain.commands.size(), turned.commands.size());
  ASSERT_GT(plain.commands.size(), 5u);
  for (std::size_t k = 0; k < plain.commands.size(); ++k) {
    // 90 degrees counter-clockwise in the Z-X plane: (z, x) -> (-x, z).
    EXPECT_NEAR(turned.commands[k].to[0], plain.commands[k].to[1], 1e-9) << k;
    EXPECT_NEAR(turned.commands[k].to[1], -plain.commands[k].to[0], 1e-9) << k;
  }
}

TEST(InterpRotation, G53IsNotTurned) {
  RunResult r = run_ok("G00 X0 Z0\nG68.1 X0 Z0 R30\nG53 X100 Z50\nG00 Z0\nM30\n");
  const std::vector<Command> rapids = r.of(Op::rapid);
  ASSERT_EQ(rapids.size(), 3u);
  EXPECT_AT(rapids[1], 50, 50);
}

TEST(InterpRotation, DisplayShowsTheUnturnedProgramPosition) {
  Interpreter in(lathe());
  ASSERT_FALSE(in.start("G68.1 X100 Z0 R60\nG00 X210 Z20\nM00\nM30\n", "test.nc"));
  bool seen = false;
  while (auto x = in.next()) {
    const Command* c = std::get_if<Command>(&*x);
    ASSERT_NE(c, nullptr);
    if (c->op == Op::stop) {
      seen = true;
      break;
    }
  }
  ASSERT_TRUE(seen);
  EXPECT_NEAR(in.program_position(0), 210, 1e-9);
  EXPECT_NEAR(in.program_position(1), 20, 1e-9);
  EXPECT_NEAR(in.machine_position()[0], 50 + 20 * kSin60 + 55 * kCos60, 1e-9);
}

TEST(InterpRotation, ModalGroup17ReadsTheRotation) {
  run_ok(
      "IF[#4017 NE 69.1] #3000=1 (power-on)\nG68.1 X0 Z0 R10\n"
      "IF[#4017 NE 68.1] #3000=2 (on)\nG69.1\nIF[#4017 NE 69.1] #3000=3 (off)\nM30\n");
}

// Misuse of G68.1 and G51.1, and what their modes forbid (alarms 1103, 1121, 1152, 1153).
TEST(InterpFrame, MisuseIsAnAlarm) {
  const ExpectedAlarm cases[] = {
      {"G51.1 X0\nG00 X20 Z0\nG00 W-5\nG00 U10\nM30\n", alarm::kFrameRestriction, 4, 5},
      {"G00 X0\nG51.1\nM30\n", alarm::kCycleWordMissing, 2, -1},
      {"G51.1 X0\nG52 X10\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G51.1 X0\nG28 U0\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G51.1 X0\nG55\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G51.1 X0\nG68\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68\nG51.1 X0\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68\nG68.1 X0 Z0 R10\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68.1 X0 Z0 R10\nG17\nM30\n", alarm::kFrameRestriction, 2, 1},
      {"G68.1 X0 Z0 R10\nG50 X0\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68.1 X0 Z0 R10\nG50.3 X0\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68.1 X0 Z0 R10\nG30 U0\nM30\n", alarm::kFrameRestriction, 2, -1},
      {"G68.1 X0 Z0\nM30\n", alarm::kCycleWordMissing, 1, -1},
      {"G68.1 U10 R5\nM30\n", alarm::kWordNotAllowed, 1, 7},
      {"G68.1 X0 Z0 R10 G04 P100\nM30\n", alarm::kGroupConflict, 1, -1},
  };
  expect_alarms(cases);
  // The plane it was given in, G18 again, and the spindle clamp G50 S are allowed.
  run_ok("G68.1 X0 Z0 R10\nG18\nG50 S2000\nM30\n");
}

// Seeded random rotations and mirrors with offsets: the machine keeps the distances of the
// program, and program -> machine -> program (the display after the machine position is set
// back) reads the programmed point within 1e-9.
TEST(InterpRotation, RandomFramesReadTheProgrammedPointBack) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  std::uniform_real_distribution<double> angle(-720.0, 720.0);
  std::bernoulli_distribution coin(0.5);
  auto fixed = [](double v) {
    std::ostringstream s;
    s.precision(3);
    s << std::fixed << v;
    return s.str();
  };
  for (int trial = 0; trial < 200; ++trial) {
    InterpreterConfig c = lathe();
    c.work_offsets[1] = {coordinate(rng), coordinate(rng)};
    c.tool_geometry[1] = {coordinate(rng) / 10, coordinate(rng) / 10};
    const double x0 = coordinate(rng);
    const double z0 = coordinate(rng);
    const double x = coordinate(rng);
    const double z = coordinate(rng);
    std::string text = "T0101\n";
    if (coin(rng)) {
      text += "G51.1 X" + fixed(coordinate(rng)) +
              (coin(rng) ? " Z" + fixed(coordinate(rng)) : "") + "\n";
    }
    text += "G68.1 X" + fixed(coordinate(rng)) + " Z" + fixed(coordinate(rng)) + " R" +
            fixed(angle(rng)) + "\n";
    text += "G00 X" + fixed(x0) + " Z" + fixed(z0) + "\nG00 X" + fixed(x) + " Z" + fixed(z) +
            "\nM00\nM30\n";
    Interpreter in(c);
    ASSERT_FALSE(in.start(text, "test.nc"));
    std::vector<AxisVector> ends;
    while (auto r = in.next()) {
      const Command* cmd = std::get_if<Command>(&*r);
      ASSERT_NE(cmd, nullptr) << text;
      if (cmd->op == Op::rapid) {
        ends.push_back(cmd->to);
      }
      if (cmd->op == Op::stop) {
        break;
      }
    }
    ASSERT_EQ(ends.size(), 2u) << text;
    const double programmed = std::hypot((std::stod(fixed(x)) - std::stod(fixed(x0))) / 2,
                                         std::stod(fixed(z)) - std::stod(fixed(z0)));
    EXPECT_NEAR(std::hypot(ends[1][0] - ends[0][0], ends[1][1] - ends[0][1]), programmed, 1e-9)
        << text;
    in.set_machine_position(in.machine_position());
    EXPECT_NEAR(in.program_position(0), std::stod(fixed(x)), 1e-9) << text;
    EXPECT_NEAR(in.program_position(1), std::stod(fixed(z)), 1e-9) << text;
  }
}

}  // namespace
}  // namespace mcnc::interp::test
