// The contour cycles G70-G73 in the interpreter: the P..Q contour, its rules and alarms (spec
// dafeng §2.5 L1421-1708, gsk A.6.30 and D2-24..D2-26). The roughing geometry itself is tested
// in tests/unit/cycles/.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

// Dafeng L1456-1473: G70 runs any block range, also one after M30, L times, and returns to
// its start point.
TEST(InterpContour, G70RunsTheRangeLTimesAndReturns) {
  RunResult r = run_ok(
      "G00 X100 Z10\nG70 P100 Q200 L2\nM30\n"
      "N100 G01 X50 F200\nN200 G01 Z0\n");
  const auto moves = r.at_line(4);
  ASSERT_EQ(moves.size(), 2u);  // X50 twice
  EXPECT_AT(moves[0], 25, 10);
  const auto back = r.at_line(2);
  ASSERT_EQ(back.size(), 2u);  // the return to X100 Z10 after each pass
  EXPECT_AT(back[0], 50, 10);
  EXPECT_EQ(r.commands.back().op, Op::end);
  EXPECT_EQ(r.commands.size(), 1u + 2u * 3u + 1u);
}

TEST(InterpContour, G70UsesTheContoursFeedAndSpeed) {
  RunResult r = run_ok(
      "G00 X100 Z10\nM03 S500\nG70 P10 Q20\nM30\n"
      "N10 G00 X40 S1000\nN20 G01 Z-10 F80\n");
  const auto spindles = r.of(Op::spindle);
  ASSERT_EQ(spindles.size(), 2u);
  EXPECT_DOUBLE_EQ(spindles[1].rpm, 1000.0);
  EXPECT_DOUBLE_EQ(r.of(Op::linear)[0].feed, 80.0);
}

TEST(InterpContour, ContourRules) {
  // gsk D2-25: no M98 inside the contour; nor a stop of the read-ahead, nor the program end.
  run_alarm("G00 X100 Z10\nG70 P10 Q20\nM30\nN10 G00 X40\nM98 P100\nN20 G01 Z0 F1\n",
            alarm::kContourForbidden, 5);
  run_alarm("G00 X100 Z10\nG70 P10 Q20\nM30\nN10 G00 X40\nM00\nN20 G01 Z0 F1\n",
            alarm::kContourForbidden, 5);
  run_alarm("G00 X100 Z10\nG70 P10 Q20\nN10 G00 X40\nM30\nN20 G01 Z0 F1\n",
            alarm::kContourForbidden, 4);
  run_alarm("G00 X100 Z10\nG70 P10 Q20\nM30\nN10 G00 X40\nG65 P100\nN20 G01 Z0 F1\n",
            alarm::kContourForbidden, 5);
}

TEST(InterpContour, ContourRangeAlarms) {
  run_alarm("G00 X100 Z10\nG70 P10\nM30\nN10 G00 X40\n", alarm::kContourMissing, 2);
  run_alarm("G00 X100 Z10\nG70 P10 Q30\nM30\nN10 G00 X40\nN20 G01 Z0 F1\n",
            alarm::kSequenceNotFound, 2);
  // Q before P: the range is empty.
  run_alarm("G00 X100 Z10\nG70 P20 Q10\nM30\nN10 G00 X40\nN20 G01 Z0 F1\n",
            alarm::kSequenceNotFound, 2);
  // gsk A.6.30 rule 6: the contour's first N must be unique.
  run_alarm("G00 X100 Z10\nG70 P10 Q20\nM30\nN10 G00 X40\nN20 G01 Z0 F1\nN10 X1\n",
            alarm::kContourMissing, 2);
}

TEST(InterpContour, MacroStatementsInsideTheContourRun) {
  RunResult r = run_ok(
      "#1=30\nG00 X100 Z10\nG70 P10 Q20\nM30\n"
      "N10 G00 X[#1]\n#1=#1+10\nN20 G01 X[#1] F1\n");
  const auto lin = r.of(Op::linear);
  ASSERT_EQ(lin.size(), 1u);
  EXPECT_AT(lin[0], 20, 10);
}

}  // namespace
}  // namespace mcnc::interp::test
