// The look-ahead behind the blocks: automatic corners (,C ,R E; GSK L D), angle programming (,A;
// GSK Q) and tool-nose radius compensation G40/G41/G42 as the interpreter emits them (spec
// dafeng §2.4, §2.8 L3670-3798; gsk A.6.10, A.6.11, A.6.22, D2-12, D2-13, D2-19).
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cmath>

namespace mcnc::interp::test {
namespace {

// Dafeng L1287-1300: from X40 Z150, G01 X110 Z120 ,C10 then G01 X120 Z30.
TEST(InterpCorners, ChamferSplitsTheCornerOnTheBlocksLine) {
  RunResult r = run_ok("G00 X40 Z150\nG01 X110 Z120 F500 ,C10 E200\nG01 X120 Z30\nM30\n");
  const auto lin = r.of(Op::linear);
  ASSERT_EQ(lin.size(), 3u);
  const double corner_z = 120.0;
  const double corner_x = 55.0;
  EXPECT_NEAR(std::hypot(lin[0].to[1] - corner_z, lin[0].to[0] - corner_x), 10.0, 1e-9);
  EXPECT_NEAR(std::hypot(lin[1].to[1] - corner_z, lin[1].to[0] - corner_x), 10.0, 1e-9);
  EXPECT_EQ(lin[1].line, 2);           // the chamfer belongs to the block that asked for it
  EXPECT_DOUBLE_EQ(lin[1].feed, 200);  // at the corner feed E
  EXPECT_DOUBLE_EQ(lin[2].feed, 500);
  EXPECT_AT(lin[2], 60, 30);
}

TEST(InterpCorners, RoundIsATangentArcAndChamferWins) {
  RunResult r = run_ok("G00 X0 Z0\nG01 Z-20 F100 ,R3\nG01 X40\nM30\n");
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_AT(arcs[0], 3, -20);  // tangent points 3 from the corner (gsk D2-12)
  EXPECT_AT(r.of(Op::linear)[0], 0, -17);
  RunResult both = run_ok("G00 X0 Z0\nG01 Z-20 F100 ,C2 ,R3\nG01 X40\nM30\n");
  EXPECT_TRUE(both.of(Op::arc).empty());
  EXPECT_AT(both.of(Op::linear)[0], 0, -18);
}

TEST(InterpCorners, GskLAndD) {
  RunResult r = run_ok("G00 X0 Z0\nG01 Z-20 F100 L2\nG01 X40\nM30\n", gsk());
  EXPECT_AT(r.of(Op::linear)[0], 0, -18);  // type II: 2 from the corner
  InterpreterConfig type1 = gsk();
  type1.chamfer_is_length = true;
  RunResult t = run_ok("G00 X0 Z0\nG01 Z-20 F100 L2\nG01 X40\nM30\n", type1);
  EXPECT_NEAR(t.of(Op::linear)[0].to[1], -20.0 + std::sqrt(2.0), 1e-9);
  RunResult d = run_ok("G00 X0 Z0\nG01 Z-20 F100 D3\nG01 X40\nM30\n", gsk());
  EXPECT_EQ(d.of(Op::arc).size(), 1u);
}

TEST(InterpCorners, CornerAlarms) {
  // No move after the corner, a rapid after it, a stop of the read-ahead before the next move,
  // a chamfer larger than the moves.
  run_alarm("G00 X0 Z0\nG01 Z-20 F100 ,C2\nM30\n", alarm::kCornerDoesNotFit, 3);
  run_alarm("G00 X0 Z0\nG01 Z-20 F100 ,C2\nG00 X40\nM30\n", alarm::kCornerDoesNotFit, 3);
  run_alarm("G00 X0 Z0\nG01 Z-20 F100 ,C2\nM00\nG01 X40\nM30\n", alarm::kCornerDoesNotFit, 3);
  run_alarm("G00 X0 Z0\nG01 Z-20 F100 ,C30\nG01 X40\nM30\n", alarm::kCornerDoesNotFit, 3);
  run_alarm("G00 X0 Z0\nG00 Z-20 ,C2\nM30\n", alarm::kWordNotAllowed, 2);
}

// Dafeng L1401-1416.
TEST(InterpAngles, OneCoordinateAndAnAngle) {
  RunResult r = run_ok("G00 X40 Z150\nG01 X120 F500 ,A135\nG01 X120 Z50\nM30\n");
  EXPECT_AT(r.of(Op::linear)[0], 60, 110);
  RunResult u = run_ok("G00 X40 Z150\nG01 U80 F500 ,A135\nM30\n");
  EXPECT_AT(u.of(Op::linear)[0], 60, 110);
}

TEST(InterpAngles, AnglePairMeetsAtTheIntersection) {
  RunResult r = run_ok("G00 X40 Z150\nG01 ,A135 F500\nG01 X50 Z80 ,A-120\nM30\n");
  const auto lin = r.of(Op::linear);
  ASSERT_EQ(lin.size(), 2u);
  EXPECT_EQ(lin[0].line, 2);
  EXPECT_NEAR(lin[0].to[1], 80.0 + 32.5 * (std::sqrt(3.0) - 1.0), 1e-9);
  EXPECT_NEAR(lin[0].to[0], 25.0 + 32.5 * (3.0 - std::sqrt(3.0)), 1e-9);
  EXPECT_AT(lin[1], 25, 80);
}

TEST(InterpAngles, AngleAlarms) {
  // gsk D2-13: X with an angle within 1 degree of the Z axis.
  run_alarm("G00 X40 Z150\nG01 X50 Q0 F100\nM30\n", alarm::kAngleProgramming, 2, -1, gsk());
  // The pair's second block must be absolute with its angle (gsk D1-2).
  run_alarm("G00 X40 Z150\nG01 ,A135 F500\nG01 U10 Z80 ,A-120\nM30\n", alarm::kAngleProgramming,
            3);
  run_alarm("G00 X40 Z150\nG01 ,A135 F500\nM30\n", alarm::kAngleProgramming, 3);
  // One block without motion may come between, two may not (gsk A.6.11 rule 7).
  run_ok("G00 X40 Z150\nG01 ,A135 F500\nM08\nG01 X50 Z80 ,A-120\nM30\n");
  run_alarm("G00 X40 Z150\nG01 ,A135 F500\nM08\nM09\nG01 X50 Z80 ,A-120\nM30\n",
            alarm::kAngleProgramming, 4);
  // GSK: both coordinates and Q: an ordinary line.
  RunResult g = run_ok("G00 X40 Z150\nG01 X50 Z-20 Q30000 F100\nM30\n", gsk());
  EXPECT_AT(g.of(Op::linear)[0], 25, -20);
}

InterpreterConfig with_nose(double radius, int tip, InterpreterConfig c = lathe()) {
  c.tool_geometry[1].radius = radius;
  c.tool_geometry[1].tip = tip;
  return c;
}

// An OD step under G42 with tip 3 and radius 0.8: the imaginary tip follows the contour on the
// straight parts, goes round the outside corner on an arc about the corner.
TEST(InterpCompensation, OdStepWithTip3) {
  RunResult r = run_ok(
      "T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\nG01 Z-20\nX40\nZ-40\nG40 G00 X60 Z5\nM30\n",
      with_nose(0.8, 3));
  const auto lin = r.of(Op::linear);
  ASSERT_EQ(lin.size(), 4u);
  EXPECT_AT(lin[0], 10, 1.2);   // start-up: to the offset start of the next element
  EXPECT_AT(lin[1], 10, -20);   // inside corner: the offsets meet
  EXPECT_AT(lin[2], 19.2, -20);
  EXPECT_AT(lin[3], 20, -40.8);  // the last move ends normal to itself before the cancel
  const auto arcs = r.of(Op::arc);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_AT(arcs[0], 20, -20.8);
  EXPECT_NEAR(arcs[0].center[0], -20.8, 1e-9);
  EXPECT_NEAR(arcs[0].center[1], 19.2, 1e-9);
  EXPECT_AT(r.at_line(7)[0], 30, 5);  // the cancel move goes to the programmed point
}

TEST(InterpCompensation, DafengDoesNotStartOnG00GskDoes) {
  const std::string program = "T0101\nG00 X20 Z5\nG42 G00 X20 Z2\nG01 Z-20 F100\nG40 X30\nM30\n";
  RunResult d = run_ok(program, with_nose(0.8, 3));
  EXPECT_AT(d.at_line(3)[0], 10, 2);  // not compensated: compensation starts with the G01
  RunResult g = run_ok(program, with_nose(0.8, 3, gsk()));
  EXPECT_AT(g.at_line(3)[0], 10, 1.2);
}

TEST(InterpCompensation, ATCodeCancelsIt) {
  RunResult r = run_ok(
      "T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\nG01 Z-20\nT0202\nG01 X40\nM30\n",
      with_nose(0.8, 3));
  EXPECT_AT(r.at_line(6).back(), 20, -20);  // after T the move is not offset any more
}

TEST(InterpCompensation, TooManyBlocksWithoutMotion) {
  run_alarm(
      "T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\nM08\nS100\nM09\nG04 X1\nG01 Z-20\nM30\n",
      alarm::kCompensationLookahead, 7, -1, with_nose(0.8, 3));
  run_ok("T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\nM08\nS100\nM09\nG01 Z-20\nG40 X30\nM30\n",
         with_nose(0.8, 3));
}

// gsk D2-19: six blocks without motion under G41/G42 are fine, the seventh is an alarm; G71
// entered under G42 roughs without compensation (gsk A.6.22 rule 6).
TEST(InterpCompensation, GskSevenBlocksAndG71WithoutCompensation) {
  const std::string six = "M08\nM09\nM08\nM09\nM08\nM09\n";
  run_ok("T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\n" + six + "G01 Z-20\nG40 X30\nM30\n",
         with_nose(0.8, 3, gsk()));
  run_alarm("T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\n" + six + "M08\nG01 Z-20\nM30\n",
            alarm::kCompensationLookahead, 10, -1, with_nose(0.8, 3, gsk()));
  const std::string g71 =
      "T0101\nG00 X102 Z2\nG42\nG71 U2 R1 F0.2\nG71 P40 Q60 U0 W0\nN40 G00 X80\nN50 G01 "
      "Z-30\nN60 X100\nG40 G00 X120\nM30\n";
  RunResult g = run_ok(g71, with_nose(0.8, 3, gsk()));
  RunResult d = run_ok(g71, with_nose(0.8, 3));
  // The semi-finishing pass's shoulder: on the contour in GSK, the nose-compensated tip path
  // (1.6 short on the diameter at the corner's end) in Dafeng.
  EXPECT_AT(g.at_line(5)[g.at_line(5).size() - 2], 50, -30);
  EXPECT_AT(d.at_line(5)[d.at_line(5).size() - 2], 49.2, -30);
}

TEST(InterpCompensation, ABarrierReleasesTheWaitingMove) {
  // M00 stops the read-ahead: the move before it ends normal to itself, in order before the stop.
  RunResult r = run_ok(
      "T0101\nG00 X20 Z5\nG42 G01 X20 Z2 F100\nG01 Z-20\nM00\nG01 X40\nG40 G00 X60\nM30\n",
      with_nose(0.8, 3));
  std::size_t stop = 0;
  for (std::size_t i = 0; i < r.commands.size(); ++i) {
    stop = r.commands[i].op == Op::stop ? i : stop;
  }
  ASSERT_GT(stop, 0u);
  EXPECT_AT(r.commands[stop - 1], 10, -20.8);
  EXPECT_EQ(r.commands[stop - 1].line, 4);
}

TEST(InterpCompensation, StartUpOnAnArcIsAnAlarm) {
  run_alarm("T0101\nG00 X20 Z5\nG42 G02 X30 Z0 R5 F100\nM30\n", alarm::kCompensationStart, 3, -1,
            with_nose(0.8, 3));
}

}  // namespace
}  // namespace mcnc::interp::test
