// Coordinates: absolute/incremental, diameter X, work offsets, G50, G52, G53, G28/G30, G68,
// G10 L2, system B G90/G91, #5001/#5021 (spec dafeng §1.5, §2.9).
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

TEST(InterpCoordinates, DiameterXIsHalvedAndIncrementalUIsDiameter) {
  RunResult r = run_ok("G00 X100 Z10\nG00 U-20 W5\nG01 U10 F100\nM30\n");
  ASSERT_EQ(r.commands.size(), 4u);
  EXPECT_AT(r.commands[0], 50, 10);
  EXPECT_AT(r.commands[1], 40, 15);
  EXPECT_AT(r.commands[2], 45, 15);
}

TEST(InterpCoordinates, RadiusAxisIsNotHalved) {
  InterpreterConfig c = lathe();
  c.axes[0].diameter = false;
  RunResult r = run_ok("G00 X100 Z10\nG00 U-20\nM30\n", c);
  EXPECT_AT(r.commands[0], 100, 10);
  EXPECT_AT(r.commands[1], 80, 10);
}

TEST(InterpCoordinates, AbsoluteAndIncrementalOfOneAxisIsAnAlarm) {
  run_alarm("G00 X10\nG00 X20 U5\nM30\n", alarm::kAbsoluteAndIncremental, 2);
}

TEST(InterpCoordinates, StartPositionFromConfig) {
  InterpreterConfig c = lathe();
  c.axes[0].start = 30;  // physical radius
  c.axes[1].start = 40;
  RunResult r = run_ok("G00 W-10\nG00 U10\nM30\n", c);
  EXPECT_AT(r.commands[0], 30, 30);
  EXPECT_AT(r.commands[1], 35, 30);
}

TEST(InterpCoordinates, WorkOffsetsG54ToG59AndExtended) {
  InterpreterConfig c = lathe();
  c.work_offsets[1] = {10, 1};   // G54 (physical radius for X)
  c.work_offsets[2] = {20, 2};   // G55
  c.work_offsets[6] = {60, 6};   // G59
  c.work_offsets[7] = {70, 7};   // G54.1 P1
  c.work_offsets[0] = {1, 100};  // EXT applies to all
  RunResult r = run_ok("G00 X0 Z0\nG55 G00 X0 Z0\nG59 X0 Z0\nG54.1 P1 X0 Z0\nG54 X2 Z0\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 6u);
  EXPECT_AT(r.commands[0], 11, 101);
  EXPECT_AT(r.commands[1], 21, 102);
  EXPECT_AT(r.commands[2], 61, 106);
  EXPECT_AT(r.commands[3], 71, 107);
  EXPECT_AT(r.commands[4], 12, 101);
}

TEST(InterpCoordinates, G10L2WritesWorkOffsetAbsoluteAndIncremental) {
  // G10 L2 P1 X/Z set (X as a diameter), U/W add.
  RunResult r = run_ok("G10 L2 P1 X20 Z5\nG00 X0 Z0\nG10 L2 P1 U10 W-1\nG00 X0 Z0\nM30\n");
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_AT(r.commands[0], 10, 5);
  EXPECT_AT(r.commands[1], 15, 4);
}

TEST(InterpCoordinates, G10L20WritesExtendedOffsets) {
  RunResult r = run_ok("G10 L20 P2 Z30\nG54.1 P2 G00 Z0\nM30\n");
  EXPECT_AT(r.commands[0], 0, 30);
}

TEST(InterpCoordinates, G50SetsCurrentPositionWithoutMotion) {
  RunResult r = run_ok("G00 X100 Z50\nG50 X0 Z0\nG00 X10 Z10\nM30\n");
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_AT(r.commands[1], 55, 60);
}

TEST(InterpCoordinates, G50UWShiftsReading) {
  InterpreterConfig c = lathe();
  c.axes[0].start = 30;  // X60 dia
  c.axes[1].start = 200;
  Interpreter in(c);
  ASSERT_FALSE(in.start("G50 U-14 W-20\nG4I0\nM30\n", "t.nc"));
  auto x = in.next();
  ASSERT_TRUE(x && std::holds_alternative<Command>(*x));
  EXPECT_EQ(std::get<Command>(*x).op, Op::sync);
  EXPECT_NEAR(in.program_position(0), 46, 1e-9);
  EXPECT_NEAR(in.program_position(1), 180, 1e-9);
  EXPECT_NEAR(in.machine_position()[0], 30, 1e-9);
}

TEST(InterpCoordinates, G52LocalSystemAndCancel) {
  RunResult r = run_ok("G52 X10 Z20\nG00 X0 Z0\nG00 X10\nG52 X0 Z0\nG00 X0 Z0\nM30\n");
  ASSERT_EQ(r.commands.size(), 4u);
  EXPECT_AT(r.commands[0], 5, 20);
  EXPECT_AT(r.commands[1], 10, 20);
  EXPECT_AT(r.commands[2], 0, 0);
}

TEST(InterpCoordinates, G52IsKeptPerWorkSystem) {
  InterpreterConfig c = lathe();
  c.work_offsets[2] = {0, 100};
  RunResult r = run_ok("G52 Z20\nG55 G00 Z0\nG54 G00 Z0\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_AT(r.commands[0], 0, 100);  // G55 has no local system
  EXPECT_AT(r.commands[1], 0, 20);   // G54 still has it
}

TEST(InterpCoordinates, G50_3RestoresTheOriginAndNamesItsCodePerSystem) {
  RunResult r = run_ok("G52 X10 Z20\nG50.3 X0 Z0\nG00 X0 Z0\nM30\n");
  EXPECT_AT(r.commands[0], 0, 0);
  RunResult a = run_alarm("G50.3 Z5\nM30\n", alarm::kBadWordValue, 1);
  EXPECT_NE(a.alarm->text.find("G50.3"), std::string::npos) << a.alarm->text;
  InterpreterConfig c = lathe();
  c.system = GCodeSystem::b;
  RunResult b = run_alarm("G92.1 Z5\nM30\n", alarm::kBadWordValue, 1, -1, c);
  EXPECT_NE(b.alarm->text.find("G92.1"), std::string::npos) << b.alarm->text;
}

TEST(InterpCoordinates, G53IsMachineAndOneShot) {
  InterpreterConfig c = lathe();
  c.work_offsets[1] = {50, 50};
  RunResult r = run_ok("G53 X20 Z10\nG00 Z0\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_EQ(r.commands[0].op, Op::rapid);
  EXPECT_TRUE(r.commands[0].barrier);
  EXPECT_AT(r.commands[0], 10, 10);
  EXPECT_AT(r.commands[1], 10, 50);
}

TEST(InterpCoordinates, G53WithIncrementalIsAnAlarm) {
  RunResult r = run("G00 X10\nG53 W10\nM30\n");
  ASSERT_TRUE(r.alarm.has_value());
  EXPECT_EQ(r.alarm->line, 2);
  for (const Command& c : r.commands) {
    EXPECT_NE(c.line, 2);
  }
}

TEST(InterpCoordinates, G28MovesOnlyNamedAxesViaIntermediatePoint) {
  InterpreterConfig c = lathe();
  c.axes[0].reference = {200, 150, 100, 50};
  c.axes[1].reference = {500, 400, 300, 200};
  RunResult r = run_ok("G00 X10 Z10\nG28 U20\nG28 Z30\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 6u);
  EXPECT_AT(r.commands[1], 15, 10);
  EXPECT_AT(r.commands[2], 200, 10);
  EXPECT_AT(r.commands[3], 200, 30);
  EXPECT_AT(r.commands[4], 200, 500);
}

TEST(InterpCoordinates, G30SelectsReferencePoint) {
  InterpreterConfig c = lathe();
  c.axes[0].reference = {200, 150, 100, 50};
  c.axes[1].reference = {500, 400, 300, 200};
  RunResult r = run_ok("G30 P4 U0 W0\nG30 U0 W0\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 5u);
  EXPECT_AT(r.commands[1], 50, 200);
  EXPECT_AT(r.commands[3], 150, 400);
}

TEST(InterpCoordinates, G68MirrorsXAndG69Cancels) {
  RunResult r = run_ok("G68\nG00 X20 Z5\nG69\nG00 X20 Z5\nM30\n");
  ASSERT_EQ(r.commands.size(), 3u);
  EXPECT_AT(r.commands[0], -10, 5);
  EXPECT_AT(r.commands[1], 10, 5);
}

TEST(InterpCoordinates, G53IsNotMirroredByG68) {
  RunResult r = run_ok("G68\nG53 X20\nM30\n");
  EXPECT_AT(r.commands[0], 10, 0);
}

TEST(InterpCoordinates, SystemBG90G91) {
  InterpreterConfig c = lathe();
  c.system = GCodeSystem::b;
  RunResult r = run_ok("G90 G00 X20 Z5\nG91 X10 Z-1\nZ-1\nG90 Z0\nM30\n", c);
  ASSERT_EQ(r.commands.size(), 5u);
  EXPECT_AT(r.commands[0], 10, 5);
  EXPECT_AT(r.commands[1], 15, 4);
  EXPECT_AT(r.commands[2], 15, 3);
  EXPECT_AT(r.commands[3], 15, 0);
}

TEST(InterpCoordinates, PositionVariables) {
  InterpreterConfig c = lathe();
  c.work_offsets[1] = {10, 20};  // physical
  // #5001 = workpiece (X as a diameter), #5021 = machine.
  RunResult r = run_ok(
      "G00 X30 Z5\nG4I0\n"
      "IF[#5001 NE 30] #3000=1(5001)\n"
      "IF[#5002 NE 5] #3000=2(5002)\n"
      "IF[#5021 NE 50] #3000=3(5021)\n"
      "IF[#5022 NE 25] #3000=4(5022)\n"
      "M30\n",
      c);
  EXPECT_EQ(r.commands.size(), 3u);
}

TEST(InterpCoordinates, AddressValuesAreTruncatedToTheIncrement) {
  RunResult r = run_ok("#1=1.2349\nG00 Z#1\nG00 Z-#1\nM30\n");
  EXPECT_AT(r.commands[0], 0, 1.234);
  EXPECT_AT(r.commands[1], 0, -1.234);
}

TEST(InterpCoordinates, GskRoundsAddressValues) {
  RunResult r = run_ok("#1=1.2346\nG00 Z#1\nG00 Z-#1\nM30\n", gsk());
  EXPECT_AT(r.commands[0], 0, 1.235);
  EXPECT_AT(r.commands[1], 0, -1.235);
}

TEST(InterpCoordinates, IncrementDecimalPointMode) {
  InterpreterConfig c = lathe();
  c.decimal_point = DecimalPoint::increment;
  RunResult r = run_ok("G00 Z1000\nG00 Z2.5\nM30\n", c);
  EXPECT_AT(r.commands[0], 0, 1.0);
  EXPECT_AT(r.commands[1], 0, 2.5);
}

}  // namespace
}  // namespace mcnc::interp::test
