// Inch input (G20) with IS-B increments: 0.0001 inch for lengths, 0.001 degree for rotary axes.
// A literal keeps its digits; a variable's value is cut to the increment (Dafeng L6671-6676:
// truncated; GSK: rounded); a number without a point counts in increments where it does in mm.
#include "tests/unit/interpreter/interp_test_support.hpp"

namespace mcnc::interp::test {
namespace {

constexpr double kInch = 25.4;

TEST(InterpInch, VariableValueIsCutToATenThousandthOfAnInch) {
  RunResult r = run_ok("#1=1.23456\n#2=0.61728\nG20 G00 X#1 Z#2\nG01 X[#1+1] Z-#2 F10\nM30\n");
  const auto rapid = r.of(Op::rapid);
  ASSERT_EQ(rapid.size(), 1u);
  EXPECT_AT(rapid[0], 1.2345 * kInch / 2, 0.6172 * kInch);
  const auto cut = r.of(Op::linear);
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_AT(cut[0], 2.2345 * kInch / 2, -0.6172 * kInch);
}

TEST(InterpInch, GskRoundsTheVariableValue) {
  RunResult r = run_ok("#1=1.23456\nG20 G00 X#1 Z#1\nM30\n", gsk());
  EXPECT_AT(r.of(Op::rapid).at(0), 1.2346 * kInch / 2, 1.2346 * kInch);
}

TEST(InterpInch, LiteralKeepsItsDigits) {
  RunResult r = run_ok("G20 G00 X1.23456 Z0.61728\nM30\n");
  EXPECT_AT(r.of(Op::rapid).at(0), 1.23456 * kInch / 2, 0.61728 * kInch);
}

TEST(InterpInch, MetricIncrementIsUnchanged) {
  RunResult r = run_ok("#1=1.23456\nG21 G00 X#1 Z#1\nM30\n");
  EXPECT_AT(r.of(Op::rapid).at(0), 1.234 / 2, 1.234);
}

TEST(InterpInch, NumbersWithoutAPointCountInInchIncrements) {
  InterpreterConfig c = lathe();
  c.decimal_point = DecimalPoint::increment;
  RunResult r = run_ok("G20 G00 X12345 Z-5000\nM30\n", c);
  EXPECT_AT(r.of(Op::rapid).at(0), 1.2345 * kInch / 2, -0.5 * kInch);
}

TEST(InterpInch, RotaryAxisKeepsItsDegreeIncrement) {
  InterpreterConfig c = lathe();
  c.axes.push_back(AxisConfig{'C', false, true});
  RunResult r = run_ok("#1=12.34567\nG20 G00 C#1\nM30\n", c);
  EXPECT_NEAR(r.of(Op::rapid).at(0).to[2], 12.345, 1e-9);
}

// G76's height P and first depth Q without a point are increments: P1200 = 0.12 inch and
// Q400 = 0.04 inch (not 1.2 and 0.4).
TEST(InterpInch, CycleAmountsCountInInchIncrements) {
  RunResult r = run_ok("G20\nG00 X1.4 Z0.2\nG76 P010060 R0\nG76 X1.1 Z-1 P1200 Q400 F0.1\nM30\n");
  const auto threads = r.of(Op::thread);
  ASSERT_GE(threads.size(), 2u);
  EXPECT_NEAR(threads.back().to[0], 1.1 * kInch / 2, 1e-9);           // the root
  EXPECT_NEAR(threads[0].to[0], (0.55 + 0.12 - 0.04) * kInch, 1e-9);  // crest less Q
}

}  // namespace
}  // namespace mcnc::interp::test
