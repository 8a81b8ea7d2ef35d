// Inclined-axis control in the interpreter (spec dafeng §2.9, L4653-4767; params 5680.1,
// 5690-5692): the program and #5001 in Cartesian coordinates, the moves and #5021 in the
// machine's inclined ones, G53 and the reference points not inclined.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mcnc::interp::test {
namespace {

constexpr std::size_t kX = 0;
constexpr std::size_t kZ = 1;
const double kTan = std::tan(-30.0 * std::numbers::pi / 180.0);
const double kCos = std::cos(-30.0 * std::numbers::pi / 180.0);

// The spec's example (L4701-4765): X (axis 1, a diameter) inclined at -30 degrees, Z (axis 2)
// the orthogonal axis; offset 2 is X5.1 Z2.5.
InterpreterConfig inclined_lathe() {
  InterpreterConfig c;
  c.axes[kX].id = 1;
  c.axes[kZ].id = 2;
  c.axes[kX].exchange = 1;
  c.inclined_axis = 'X';
  c.inclined_orthogonal = 'Z';
  c.inclined_degrees = -30.0;
  c.tool_geometry[2] = {5.1, 2.5};
  return c;
}

// Program X (radius) and Z of machine X (radius) and Z: the inverse of the spec's formulas.
std::array<double, 2> cartesian(const AxisVector& m) {
  const double x = m[kX] * kCos;
  return {x, m[kZ] - x * kTan};
}

struct TableRow {
  const char* block;
  double shown_x, shown_z;      // the absolute position shown (X a diameter)
  double machine_x, machine_z;  // the machine position shown (X a diameter)
};

// Each row of the table: after the block's move, #5001 and the machine position.
TEST(InterpInclinedAxis, TheSpecsWorkedTable) {
  const TableRow rows[] = {
      {"G53 X0 Z0", 0.0, 0.0, 0.0, 0.0},
      {"G53 X-100 Z-50", -86.603, -75.0, -100.0, -50.0},
      {"T0001 G00 X10 Z0", 10.0, 0.0, 11.547, -2.887},
      {"G00 X-10 Z5", -10.0, 5.0, -11.547, 7.887},
      {"T0002 G00 X10 Z0", 10.0, 0.0, 17.436, -1.859},
      {"G00 X-10 Z5", -10.0, 5.0, -5.658, 8.9145},
  };
  std::string program;
  for (const TableRow& row : rows) {
    program += std::string(row.block) + "\n";
  }
  program += "M30\n";
  Interpreter in(inclined_lathe());
  ASSERT_FALSE(in.start(program, "test.nc"));
  int row = 0;
  while (auto x = in.next()) {
    ASSERT_TRUE(std::holds_alternative<Command>(*x)) << std::get<ProgramAlarm>(*x).text;
    const Command& c = std::get<Command>(*x);
    if (c.op != Op::rapid) {
      continue;
    }
    ASSERT_LT(row, 6);
    const TableRow& want = rows[row++];
    // The table gives three decimals (four in its last row).
    EXPECT_NEAR(c.to[kX] * 2.0, want.machine_x, 6e-4) << want.block;
    EXPECT_NEAR(c.to[kZ], want.machine_z, 6e-4) << want.block;
    EXPECT_NEAR(in.machine_position()[kX] * 2.0, want.machine_x, 6e-4) << want.block;
    EXPECT_NEAR(in.program_position(0), want.shown_x, 6e-4) << want.block;
    EXPECT_NEAR(in.program_position(1), want.shown_z, 6e-4) << want.block;
  }
  EXPECT_EQ(row, 6);
}

TEST(InterpInclinedAxis, MachinePositionVariableIsInclinedAndTheWorkpieceOneCartesian) {
  Interpreter in(inclined_lathe());
  ASSERT_FALSE(in.start("T0002 G00 X10 Z0\n#101=#5001\n#102=#5002\n#103=#5021\n#104=#5022\nM30\n",
                        "test.nc"));
  ASSERT_FALSE(drain(in).alarm);
  auto value = [&](int n) { return in.variables().read(n).value.number(); };
  // The table's row (L4747-4751): shown X10 Z0, machine X17.436 Z-1.859.
  EXPECT_NEAR(value(101), 10.0, 1e-9);
  EXPECT_NEAR(value(102), 0.0, 1e-9);
  EXPECT_NEAR(value(103), (10.0 + 5.1) / kCos, 1e-9);
  EXPECT_NEAR(value(104), (10.0 + 5.1) / 2.0 * kTan + 2.5, 1e-9);
}

TEST(InterpInclinedAxis, ALineTakesTheTimeOfTheProgrammedLine) {
  RunResult r = run_ok("G00 X0 Z0\nG01 X40 Z-30 F200\nM30\n", inclined_lathe());
  const std::vector<Command> m = r.of(Op::linear);
  ASSERT_EQ(m.size(), 1u);
  const double programmed = std::hypot(20.0, 30.0);
  const double machine = std::hypot(m[0].to[kX], m[0].to[kZ]);
  EXPECT_NEAR(m[0].to[kX], 20.0 / kCos, 1e-9);
  EXPECT_NEAR(m[0].to[kZ], -30.0 + 20.0 * kTan, 1e-9);
  EXPECT_NEAR(machine / m[0].feed, programmed / 200.0, 1e-12);
}

TEST(InterpInclinedAxis, AnArcLeavesAsChordsOnTheProgrammedCircle) {
  InterpreterConfig c = inclined_lathe();
  RunResult r = run_ok("G00 X20 Z0\nG03 X60 Z-20 I0 K-20 F100\nM30\n", c);
  const std::vector<Command> chords = r.at_line(2);
  ASSERT_GT(chords.size(), 10u);
  // Centre (X radius 10, Z -20): a quarter circle from (10, 0) to (30, -20).
  std::array<double, 2> from = {10.0, 0.0};
  double seconds = 0.0;
  AxisVector machine_from{};
  machine_from[kX] = 10.0 / kCos;
  machine_from[kZ] = 10.0 * kTan;
  for (const Command& chord : chords) {
    ASSERT_EQ(chord.op, Op::linear);
    const std::array<double, 2> to = cartesian(chord.to);
    EXPECT_NEAR(std::hypot(to[0] - 10.0, to[1] + 20.0), 20.0, 1e-9);
    // Its middle within the tolerance (1 um) of the circle: the tool tip is Cartesian.
    const double mid = std::hypot((from[0] + to[0]) / 2.0 - 10.0, (from[1] + to[1]) / 2.0 + 20.0);
    EXPECT_LE(20.0 - mid, c.polar_tolerance + 1e-12);
    seconds +=
        std::hypot(chord.to[kX] - machine_from[kX], chord.to[kZ] - machine_from[kZ]) / chord.feed;
    from = to;
    machine_from = chord.to;
  }
  EXPECT_NEAR(from[0], 30.0, 1e-9);
  EXPECT_NEAR(from[1], -20.0, 1e-9);
  // A quarter circle of radius 20 at F100 takes as long.
  EXPECT_NEAR(seconds, 20.0 * std::numbers::pi / 2.0 / 100.0, 1e-9);
}

TEST(InterpInclinedAxis, AThreadKeepsItsRevolutions) {
  RunResult r = run_ok("G00 X20 Z5\nG32 X30 Z-40 F2\nM30\n", inclined_lathe());
  const std::vector<Command> t = r.of(Op::thread);
  ASSERT_EQ(t.size(), 1u);
  // 45 mm of Z at 2 mm a revolution: 22.5 revolutions along the machine's longest travel.
  const double dx = t[0].to[kX] - 10.0 / kCos;
  const double dz = t[0].to[kZ] - (5.0 + 10.0 * kTan);
  EXPECT_NEAR(std::max(std::fabs(dx), std::fabs(dz)) / t[0].lead, 22.5, 1e-9);
}

TEST(InterpInclinedAxis, ReferenceReturnEndsOnTheMachinesReferencePoint) {
  InterpreterConfig c = inclined_lathe();
  c.axes[kX].reference[0] = 100.0;  // machine, radius
  c.axes[kZ].reference[0] = 50.0;
  RunResult r = run_ok("G00 X20 Z0\nG28 U0\nG28 W0\nM30\n", c);
  const std::vector<Command> m = r.of(Op::rapid);
  ASSERT_EQ(m.size(), 5u);
  // G28 U0: X to its reference on the machine, Z stays where it is on the machine.
  EXPECT_NEAR(m[2].to[kX], 100.0, 1e-9);
  EXPECT_NEAR(m[2].to[kZ], 10.0 * kTan, 1e-9);
  EXPECT_NEAR(m[4].to[kX], 100.0, 1e-9);
  EXPECT_NEAR(m[4].to[kZ], 50.0, 1e-9);
}

TEST(InterpInclinedAxis, ThePositionTheChannelGivesIsInclined) {
  Interpreter in(inclined_lathe());
  ASSERT_FALSE(in.start("G01 W-10 F100\nM30\n", "test.nc"));
  AxisVector at{};
  at[kX] = -50.0;  // the table's G53 X-100 Z-50
  at[kZ] = -50.0;
  in.set_machine_position(at);
  RunResult r = drain(in);
  ASSERT_FALSE(r.alarm);
  const std::vector<Command> m = r.of(Op::linear);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0].to[kX], -50.0, 1e-9);  // W moves Z alone, on the machine too
  EXPECT_NEAR(m[0].to[kZ], -60.0, 1e-9);
  EXPECT_NEAR(in.program_position(0), -86.603, 6e-4);
  EXPECT_NEAR(in.program_position(1), -85.0, 6e-4);
}

TEST(InterpInclinedAxis, TheInclinedAndOrthogonalAxesAreNotExchanged) {
  RunResult r = run_alarm("G00 X20 Z0\nG140 X1\nM30\n", alarm::kInclinedAxisRestriction, 2, -1,
                          inclined_lathe());
  EXPECT_NE(r.alarm->text.find("cannot be exchanged"), std::string::npos) << r.alarm->text;
}

TEST(InterpInclinedAxis, NeitherAxisIsAG514Slave) {
  run_alarm("G51.4 P1 Q2\nM30\n", alarm::kInclinedAxisRestriction, 1, -1, inclined_lathe());
  InterpreterConfig c = inclined_lathe();
  c.axes.push_back(AxisConfig{'Y', false});
  c.axes.back().id = 3;
  c.axes.back().may_follow = true;
  run_ok("G51.4 P1 Q3\nG50.4 Q3\nM30\n", c);  // the inclined axis may be the master
}

TEST(InterpInclinedAxis, AnArcThreadIsRefused) {
  run_alarm("G00 X20 Z0\nG32.2 X60 Z-20 R20 F2\nM30\n", alarm::kInclinedAxisRestriction, 2, -1,
            inclined_lathe());
}

TEST(InterpInclinedAxis, AnArcOfTooManyChordsIsAnAlarm) {
  // A full circle of radius 500 m within 1 um: about 1.6 million chords.
  InterpreterConfig c = inclined_lathe();
  c.polar_tolerance = 1e-6;
  run_alarm("G00 X0 Z0\nG02 X0 Z0 K-500000 F100\nM30\n", alarm::kInclinedAxisRestriction, 2, -1, c);
  run_ok("G00 X0 Z0\nG02 X0 Z0 K-50 F100\nM30\n", c);
}

TEST(InterpInclinedAxis, TheStrokeCheckLimitsAreOnTheMachine) {
  // Z's + limit 0 on the machine: at X20 (radius 10) the Cartesian Z0 is machine Z -5.77, so Z5
  // is machine -0.77, inside; Z6 is machine 0.23, beyond it.
  InterpreterConfig c = inclined_lathe();
  c.axes[kZ].stroke_plus = 0.0;
  c.axes[kZ].stroke_minus = -1000.0;
  c.axes[kX].stroke_plus = 1000.0;
  c.axes[kX].stroke_minus = -1000.0;
  c.stroke_inside_forbidden = false;
  run_ok("G00 X20 Z-10\nG22\nG00 Z5\nM30\n", c);
  run_alarm("G00 X20 Z-10\nG22\nG00 Z6\nM30\n", alarm::kStrokeLimit, 3, -1, c);
}

TEST(InterpInclinedAxis, WithoutItTheMovesAreCartesian) {
  InterpreterConfig c = inclined_lathe();
  c.inclined_axis = 0;
  RunResult r = run_ok("T0002 G00 X10 Z0\nM30\n", c);
  EXPECT_AT(r.of(Op::rapid)[0], (10.0 + 5.1) / 2.0, 2.5);
}

}  // namespace
}  // namespace mcnc::interp::test
