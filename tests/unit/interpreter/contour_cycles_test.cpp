// The contour cycles G70-G73 in the interpreter: the P..Q contour, its rules and alarms (spec
// dafeng §2.5 L1421-1708, gsk A.6.30 and D2-24..D2-26). The roughing geometry itself is tested
// in tests/unit/cycles/.
#include "tests/unit/interpreter/interp_test_support.hpp"

#include <cstdio>

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

// Spec dafeng §2.5 syntax ② of G71/G72/G73: F, S and T on the P block are the roughing's. The
// cycle's P is its contour's first N, never the `S_ Paab` spindle address, whatever N it names
// (read as an address, P10 was spindle 0, P12 spindle 2 and P100 channel 10).
TEST(InterpContour, SpeedOnTheCycleBlockIsTheRoughingSpeed) {
  struct Cycle {
    const char* first;
    const char* code;
    const char* contour;  // its first and last N are filled in
  };
  const Cycle cycles[] = {
      {"G71 U1 R0.5", "G71", "G00 X40\nG01 Z-20 F0.1\nN%d G01 X60\n"},
      {"G72 W1 R0.5", "G72", "G00 Z-20\nG01 X60 F0.1\nN%d G01 Z0\n"},
      {"G73 U2 W1 R2", "G73", "G00 X40\nG01 Z-20 F0.1\nN%d G01 X60\n"},
  };
  for (const Cycle& c : cycles) {
    for (int n : {10, 11, 12, 100}) {
      char contour[96];
      std::snprintf(contour, sizeof contour, c.contour, n + 10);
      const std::string program = "M03 S500\nG00 X100 Z10\n" + std::string(c.first) + "\n" +
                                  c.code + " P" + std::to_string(n) + " Q" +
                                  std::to_string(n + 10) + " U0.4 W0.1 F0.3 S1200\nN" +
                                  std::to_string(n) + " " + contour + "M30\n";
      RunResult r = run_ok(program);
      const auto spindles = r.of(Op::spindle);
      ASSERT_EQ(spindles.size(), 2u) << program;
      EXPECT_EQ(spindles[1].spindle, 1) << program;
      EXPECT_EQ(spindles[1].channel, 0) << program;
      EXPECT_DOUBLE_EQ(spindles[1].rpm, 1200.0) << program;
      EXPECT_EQ(spindles[1].line, 4) << program;
      EXPECT_GT(r.at_line(4).size(), 2u) << program;  // the roughing ran
    }
  }
}

// An M code and a T word beside them on the P block, as CAM posts write it.
TEST(InterpContour, SpindleCodeAndToolOnTheCycleBlock) {
  RunResult r = run_ok(
      "G00 X100 Z10\nG71 U1 R0.5\nG71 P12 Q22 U0.4 W0.1 F0.3 M03 S900 T0202\n"
      "N12 G00 X40\nG01 Z-20 F0.1\nN22 G01 X60\nM30\n");
  const auto spindles = r.of(Op::spindle);
  ASSERT_EQ(spindles.size(), 1u);
  EXPECT_EQ(spindles[0].spindle, 1);
  EXPECT_EQ(spindles[0].spindle_direction, SpindleDirection::cw);
  EXPECT_DOUBLE_EQ(spindles[0].rpm, 900.0);
  EXPECT_EQ(spindles[0].line, 3);
  EXPECT_EQ(r.of(Op::tool).size(), 1u);
}

}  // namespace
}  // namespace mcnc::interp::test
