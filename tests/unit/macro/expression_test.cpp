#include "channel/interp/macro/expression.hpp"
#include "channel/interp/macro/macro_alarms.hpp"
#include "tests/unit/macro/macro_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace mcnc::interp::macro {
namespace {

using test::assign;
using test::eval_text;

class Expr : public ::testing::Test {
 protected:
  double num(const std::string& text) {
    const EvalResult r = eval_text(text, store_);
    EXPECT_FALSE(r.alarm) << text << ": " << r.alarm.number << " col " << r.alarm.column << " "
                          << r.alarm.text();
    EXPECT_FALSE(r.value.is_null()) << text;
    return r.value.number();
  }
  bool is_null(const std::string& text) {
    const EvalResult r = eval_text(text, store_);
    EXPECT_FALSE(r.alarm) << text << ": " << r.alarm.text();
    return r.value.is_null();
  }
  void set(std::int64_t n, double x) { ASSERT_FALSE(store_.write(n, MacroValue::of(x))); }
  void run(const std::string& statement) {
    const MacroAlarm a = assign(statement, store_);
    ASSERT_FALSE(a) << statement << ": " << a.text();
  }
  MacroValue var(std::int64_t n) { return store_.read(n).value; }

  VariableStore store_;
};

// --- Spec examples -------------------------------------------------------------------------

// Dafeng L6895-6904 (§7.9 #73).
TEST_F(Expr, PrecedenceExamplesL6895) {
  EXPECT_EQ(num("3*20-10"), 50.0);
  EXPECT_EQ(num("3*[20-10]"), 30.0);
  EXPECT_EQ(num("10+2*10"), 30.0);
}

// Dafeng L6697-6705 (§7.9 #70).
TEST_F(Expr, AssignmentExampleL6697) {
  run("#101=3");
  run("#102=#101+1");
  run("#103=SQRT[#101*#101+#102*#102]");
  EXPECT_EQ(var(103), MacroValue::of(5.0));
}

// Dafeng L6437-6468 (§7.9 #69): null assignment, arithmetic and comparison.
TEST_F(Expr, NullExamplesL6437) {
  run("#1=#0");
  EXPECT_TRUE(var(1).is_null());
  run("#2=#0+1");
  EXPECT_EQ(var(2), MacroValue::of(1.0));
  run("#3=#0*3");
  EXPECT_EQ(var(3), MacroValue::of(0.0));
  EXPECT_EQ(num("#1==#0"), 1.0);
  EXPECT_EQ(num("#1==0"), 0.0);
  EXPECT_EQ(num("#1!=0"), 1.0);
  EXPECT_EQ(num("#1>=0"), 1.0);
  // `G00 X100 Y[#0]` is `G00 X100`: the bracketed reference stays null, so Y disappears.
  const ParseResult y = parse_expression("[#0]", 10, ParseMode::kOperandPrefix);
  ASSERT_FALSE(y.alarm);
  EXPECT_FALSE(as_word_value(evaluate(y.expression, store_).value).has_value());
}

// Dafeng L6418-6424: G[#101] X[#102*SIN[20]] F[#103], and L6668 X[100*COS[50]+20].
TEST_F(Expr, AddressExpressionsL6418) {
  set(101, 1);
  set(102, 100);
  EXPECT_EQ(num("[#101]"), 1.0);
  EXPECT_NEAR(num("[#102*SIN[20]]"), 34.20201433256687, 1e-12);
  EXPECT_NEAR(num("[100*COS[50]+20]"), 84.27876096865393, 1e-12);
  EXPECT_EQ(num("[-#101]"), -1.0);
}

// Dafeng L6427: #[#100+#102+2].
TEST_F(Expr, ComputedIndexL6427) {
  set(100, 100);
  set(102, 400);
  set(502, 12.5);
  EXPECT_EQ(num("#[#100+#102+2]"), 12.5);
}

// Dafeng L6878-6886 (§7.9 #72).
TEST_F(Expr, FupFixIntL6878) {
  set(1, 1.2);
  set(2, -1.2);
  EXPECT_EQ(num("FUP[#1]"), 2.0);
  EXPECT_EQ(num("FUP[#2]"), -2.0);
  EXPECT_EQ(num("FIX[#1]"), 1.0);
  EXPECT_EQ(num("FIX[#2]"), -1.0);
  set(1, 1.5);
  set(2, -1.5);
  EXPECT_EQ(num("INT[#1]"), 2.0);
  EXPECT_EQ(num("INT[#2]"), -2.0);
}

// Dafeng L7137-7167 (§7.9 #77): WHILE[#2 LE 10] sums 1..10 to 55.
TEST_F(Expr, WhileSumL7137) {
  run("#1=0");
  run("#2=1");
  const ParseResult cond = parse_expression("[#2 LE 10]", 6, ParseMode::kOperandPrefix);
  ASSERT_FALSE(cond.alarm);
  int passes = 0;
  while (evaluate(cond.expression, store_).value.number() != 0.0 && passes < 100) {
    run("#1=#1+#2");
    run("#2=#2+1");
    ++passes;
  }
  EXPECT_EQ(passes, 10);
  EXPECT_EQ(var(1), MacroValue::of(55.0));
}

// Dafeng L7036-7050 (§7.9 #75): X[#10*20] while #10<=5 gives X0, 20, ... 100.
TEST_F(Expr, IfLoopL7036) {
  run("#10=0");
  std::vector<double> xs;
  for (int guard = 0; guard < 100; ++guard) {
    xs.push_back(num("[#10*20]"));
    run("#10=#10+1");
    if (num("#10<=5") == 0.0) {
      break;
    }
  }
  EXPECT_EQ(xs, (std::vector<double>{0, 20, 40, 60, 80, 100}));
}

// gsk D3-2: `#[#1+1*2]=1` with #1 vacant sets #2.
TEST_F(Expr, GskComputedTargetD3_2) {
  run("#[#1+1*2]=1");
  EXPECT_EQ(var(2), MacroValue::of(1.0));
}

// gsk D3-6 (vacancy table) and D3-7 (numbers).
TEST_F(Expr, GskVacancyD3_6AndNumbersD3_7) {
  run("#2=#1");
  EXPECT_TRUE(var(2).is_null());
  run("#2=#1*5");
  EXPECT_EQ(var(2), MacroValue::of(0.0));
  run("#2=#1+#1");
  EXPECT_EQ(var(2), MacroValue::of(0.0));
  const MacroAlarm a = assign("#0=5", store_);
  EXPECT_EQ(a.number, alarm::kReadOnlyVariable);
  EXPECT_EQ(a.column, 1);
  run("#1=123");
  EXPECT_EQ(var(1), MacroValue::of(123.0));
  run("#1=12.3456");
  EXPECT_EQ(quantize_word_value(num("#1"), 3, WordRounding::kRound), 12.346);
  EXPECT_EQ(quantize_word_value(num("-#1"), 3, WordRounding::kRound), -12.346);
  set(2, 1);
  EXPECT_EQ(num("[#1+#2]"), 13.3456);
}

// gsk D3-9.
TEST_F(Expr, GskFunctionsD3_9) {
  EXPECT_EQ(num("ASIN[-0.5]"), -30.0);
  EXPECT_EQ(eval_text("ASIN[2]", store_).alarm.number, alarm::kOutOfRange);
  EXPECT_EQ(num("ACOS[-1]"), 180.0);
  EXPECT_EQ(eval_text("ACOS[1.5]", store_).alarm.number, alarm::kOutOfRange);
  EXPECT_NEAR(num("SIN[90.5]"), std::sin(90.5 * std::numbers::pi / 180.0), 1e-15);
  // A result beyond 10^47 is P/S 111 there, 3111 here.
  EXPECT_EQ(eval_text("EXP[200]", store_).alarm.number, alarm::kOutOfRange);
  EXPECT_EQ(eval_text("POW[10,47]*10", store_).alarm.number, alarm::kOutOfRange);
}

// --- Operators ------------------------------------------------------------------------------

TEST_F(Expr, Arithmetic) {
  EXPECT_EQ(num("1+2"), 3.0);
  EXPECT_EQ(num("1-2"), -1.0);
  EXPECT_EQ(num("3*4"), 12.0);
  EXPECT_EQ(num("1/4"), 0.25);
  EXPECT_EQ(num("7 MOD 3"), 1.0);
  EXPECT_EQ(num("-7 MOD 3"), -1.0);  // sign of the dividend
  EXPECT_EQ(num("7.5 MOD 2"), 1.5);
  EXPECT_EQ(num("7 mod 3"), 1.0);
  EXPECT_EQ(num("7MOD3"), 1.0);
}

TEST_F(Expr, Comparisons) {
  const char* ops[][2] = {{"==", "EQ"}, {"!=", "NE"}, {">", "GT"},
                          {">=", "GE"}, {"<", "LT"},  {"<=", "LE"}};
  const double expected[6][3] = {// 1 op 2, 2 op 2, 3 op 2
                                 {0, 1, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 1}, {1, 0, 0}, {1, 1, 0}};
  for (int i = 0; i < 6; ++i) {
    for (int a = 1; a <= 3; ++a) {
      for (const char* op : ops[i]) {
        EXPECT_EQ(num(std::to_string(a) + " " + op + " 2"), expected[i][a - 1]) << a << op;
        EXPECT_EQ(num(std::to_string(a) + op + "2"), expected[i][a - 1]) << a << op;
      }
    }
  }
  set(1, 5);
  set(2, 5);
  EXPECT_EQ(num("#1EQ#2"), 1.0);
  EXPECT_EQ(num("#1 ge #2"), 1.0);
}

TEST_F(Expr, ComparisonsWithNullFollowTheDialect) {
  // #1 null, #2 = 0.
  set(2, 0);
  EXPECT_EQ(num("#1 EQ #0"), 1.0);
  EXPECT_EQ(num("#2 EQ #0"), 0.0);
  EXPECT_EQ(num("#1 NE 0"), 1.0);
  EXPECT_EQ(num("#2 NE 0"), 0.0);
  EXPECT_EQ(num("#1 GE #0"), 1.0);
  EXPECT_EQ(num("#2 GE #0"), 1.0);  // Dafeng: null and 0 are equal for >=
  EXPECT_EQ(num("#1 GT #0"), 0.0);
  EXPECT_EQ(num("#1 LE 0"), 1.0);
  EXPECT_EQ(num("#1 LT 1"), 1.0);
  MacroDialect d;
  d.vacant_ordering = VacantOrdering::kLiteralGskTable;
  VariableStore g(d);
  ASSERT_FALSE(g.write(2, MacroValue::of(0)));
  EXPECT_EQ(eval_text("#2 GE #0", g).value.number(), 0.0);
  EXPECT_EQ(eval_text("#1 GE #0", g).value.number(), 1.0);
  EXPECT_EQ(eval_text("#2 LE #0", g).value.number(), 0.0);
}

TEST_F(Expr, LogicalOperators) {
  EXPECT_EQ(num("1 && 2"), 1.0);
  EXPECT_EQ(num("1 AND 0"), 0.0);
  EXPECT_EQ(num("0 || 0"), 0.0);
  EXPECT_EQ(num("0 OR 3"), 1.0);
  EXPECT_EQ(num("!0"), 1.0);
  EXPECT_EQ(num("!5"), 0.0);
  EXPECT_EQ(num("!#1"), 1.0);  // null counts as 0
  EXPECT_EQ(num("1 LT 2 AND 3 LT 4"), 1.0);
  EXPECT_EQ(num("1 GT 2 OR 3 LT 4"), 1.0);
}

TEST_F(Expr, BitwiseOperators) {
  EXPECT_EQ(num("5 | 3"), 7.0);
  EXPECT_EQ(num("5 & 3"), 1.0);
  EXPECT_EQ(num("5 ^ 3"), 6.0);
  EXPECT_EQ(num("5 XOR 3"), 6.0);
  EXPECT_EQ(num("~0"), -1.0);
  EXPECT_EQ(num("~5 & 7"), 2.0);
  EXPECT_EQ(num("-1 & 255"), 255.0);
  EXPECT_EQ(num("5.4 | 0"), 5.0);  // operands rounded half away from zero
  EXPECT_EQ(num("5.5 | 0"), 6.0);
  EXPECT_EQ(num("#1 | 4"), 4.0);
  EXPECT_EQ(eval_text("POW[2,60] | 1", store_).alarm.number, alarm::kOutOfRange);
  EXPECT_EQ(eval_text("~POW[2,60]", store_).alarm.number, alarm::kOutOfRange);
}

TEST_F(Expr, UnaryOperators) {
  EXPECT_EQ(num("-3"), -3.0);
  EXPECT_EQ(num("+3"), 3.0);
  EXPECT_EQ(num("- -3"), 3.0);
  EXPECT_EQ(num("--3"), 3.0);
  EXPECT_EQ(num("2*-3"), -6.0);
  EXPECT_EQ(num("2--3"), 5.0);
  EXPECT_EQ(num("-[2+3]"), -5.0);
  EXPECT_FALSE(std::signbit(num("-0")));
  EXPECT_FALSE(std::signbit(num("-#1")));
}

// Decision D18: unary tightest, MOD with * /, comparisons below + -, logical below
// comparisons, bitwise loosest; one level associates left to right.
TEST_F(Expr, PrecedenceLevels) {
  EXPECT_EQ(num("1+2*3"), 7.0);
  EXPECT_EQ(num("2*3+1"), 7.0);
  EXPECT_EQ(num("10-4-3"), 3.0);
  EXPECT_EQ(num("24/4/2"), 3.0);
  EXPECT_EQ(num("7 MOD 4 * 2"), 6.0);
  EXPECT_EQ(num("2*7 MOD 4"), 2.0);
  EXPECT_EQ(num("1+7 MOD 4"), 4.0);
  EXPECT_EQ(num("1+2 EQ 3"), 1.0);
  EXPECT_EQ(num("2 GT 1+2"), 0.0);
  EXPECT_EQ(num("1 < 2 < 3"), 1.0);     // [1<2]<3
  EXPECT_EQ(num("3 > 2 > 1"), 0.0);     // [3>2]>1 = 1>1
  EXPECT_EQ(num("1 AND 2 | 4"), 5.0);   // [1 AND 2] | 4
  EXPECT_EQ(num("6 & 3 == 2"), 0.0);    // 6 & [3==2]
  EXPECT_EQ(num("1 OR 0 AND 0"), 0.0);  // [1 OR 0] AND 0, not C's 1 OR [0 AND 0]
  EXPECT_EQ(num("0 AND 0 OR 1"), 1.0);
  EXPECT_EQ(num("1 | 2 ^ 3"), 0.0);  // [1|2]^3, not C's 1|[2^3]
  EXPECT_EQ(num("6 & 3 | 8"), 10.0);
  EXPECT_EQ(num("!0 + 1"), 2.0);
  EXPECT_EQ(num("-2*3"), -6.0);
  EXPECT_EQ(num("-7 MOD 4"), -3.0);
  EXPECT_EQ(num("[1+2]*[3+4]"), 21.0);
  EXPECT_EQ(num("[[[2]]]"), 2.0);
}

// --- Operands --------------------------------------------------------------------------------

TEST_F(Expr, NumbersUseTheCalculatorDecimalPoint) {
  EXPECT_EQ(num("123"), 123.0);  // gsk B.4 item 5: 123 is 123.000
  EXPECT_EQ(num("12."), 12.0);
  EXPECT_EQ(num(".5"), 0.5);
  EXPECT_EQ(num("007"), 7.0);
  EXPECT_EQ(num("0.1"), 0.1);
  EXPECT_EQ(num(" 1 +\t2 "), 3.0);
}

TEST_F(Expr, ConstantsPiAndChn) {
  EXPECT_EQ(num("PI"), std::numbers::pi);
  EXPECT_EQ(num("Pi"), std::numbers::pi);  // dafeng L6569
  EXPECT_EQ(num("2*pi"), 2 * std::numbers::pi);
  EXPECT_EQ(num("CHN"), 1.0);
  MacroDialect d;
  d.channel = 3;
  VariableStore s(d);
  EXPECT_EQ(eval_text("CHN==3", s).value.number(), 1.0);
}

TEST_F(Expr, EveryFunction) {
  EXPECT_EQ(num("SIN[30]"), 0.5);
  EXPECT_EQ(num("COS[60]"), 0.5);
  EXPECT_EQ(num("TAN[45]"), 1.0);
  EXPECT_EQ(num("ASIN[1]"), 90.0);
  EXPECT_EQ(num("ACOS[0]"), 90.0);
  EXPECT_EQ(num("ATAN[1]"), 45.0);
  EXPECT_EQ(num("ATAN[1,-1]"), 135.0);
  EXPECT_EQ(num("ATAN2[1,-1]"), 135.0);
  EXPECT_EQ(num("ATAN2 [-1, -1]"), -135.0);
  EXPECT_EQ(num("SQRT[16]"), 4.0);
  EXPECT_EQ(num("ABS[-3]"), 3.0);
  EXPECT_EQ(num("ROUND[1.23456]"), 1.235);
  EXPECT_EQ(num("ROUND2[1.23456,2]"), 1.23);
  EXPECT_EQ(num("INT[2.5]"), 3.0);
  EXPECT_EQ(num("FIX[2.7]"), 2.0);
  EXPECT_EQ(num("FUP[2.1]"), 3.0);
  EXPECT_NEAR(num("LN[EXP[2]]"), 2.0, 1e-15);
  EXPECT_EQ(num("EXP[0]"), 1.0);
  EXPECT_EQ(num("POW[2,10]"), 1024.0);
  EXPECT_EQ(num("BIN[4660]"), 1234.0);
  EXPECT_EQ(num("BCD[1234]"), 4660.0);
  EXPECT_EQ(num("sqrt[SQRT[16]]"), 2.0);
  EXPECT_EQ(num("ROUND2[#1+1.25,1+0]"), 1.3);
}

// Only a variable reference is null; any operator or function makes a number (null as 0).
TEST_F(Expr, NullThroughOperatorsAndFunctions) {
  EXPECT_TRUE(is_null("#1"));
  EXPECT_TRUE(is_null("[#1]"));
  EXPECT_TRUE(is_null("[[#1]]"));
  EXPECT_TRUE(is_null("#0"));
  EXPECT_TRUE(is_null("#[#1]"));  // #[null] is #0
  EXPECT_FALSE(is_null("-#1"));
  EXPECT_FALSE(is_null("+#1"));
  EXPECT_FALSE(is_null("#1+0"));
  EXPECT_FALSE(is_null("SIN[#1]"));
  EXPECT_EQ(num("COS[#1]"), 1.0);
  EXPECT_EQ(num("ABS[#1]"), 0.0);
  EXPECT_EQ(num("#1*3"), 0.0);
  EXPECT_EQ(num("#1-5"), -5.0);
  EXPECT_EQ(num("POW[#1,0]"), 1.0);
}

TEST_F(Expr, IndirectionChains) {
  set(1, 2);
  set(2, 3);
  set(3, 7);
  EXPECT_EQ(num("#[#1]"), 3.0);
  EXPECT_EQ(num("#[#[#1]]"), 7.0);
  EXPECT_TRUE(is_null("#[#[#[#1]]]"));  // #7 is null
  EXPECT_EQ(num("#[ 1 + 1 ]"), 3.0);
  set(100, 42);
  EXPECT_EQ(num("#[#1+98]"), 42.0);
  EXPECT_EQ(num("#[2.0000000000001]"), 3.0);  // within the snap tolerance
  run("#[#[#1]]=9");
  EXPECT_EQ(var(3), MacroValue::of(9.0));
}

TEST_F(Expr, LocalsFollowTheCallLevel) {
  run("#1=5");
  const ParseResult p = parse_expression("#1*2+#100");
  ASSERT_FALSE(p.alarm);
  run("#100=1");
  EXPECT_EQ(evaluate(p.expression, store_).value.number(), 11.0);
  ASSERT_FALSE(store_.push_level());
  EXPECT_EQ(evaluate(p.expression, store_).value.number(), 1.0);
  run("#1=7");
  EXPECT_EQ(evaluate(p.expression, store_).value.number(), 15.0);
  ASSERT_FALSE(store_.pop_level());
  EXPECT_EQ(evaluate(p.expression, store_).value.number(), 11.0);
}

// --- Prefix modes (how the interpreter takes an expression out of a block) -------------------

TEST(ExpressionPrefix, OperandAfterAnAddress) {
  struct Case {
    const char* text;
    std::size_t end;
  } cases[] = {{"#1Z#2", 2},     {"-#101 Z5", 5}, {"[#1 EQ 2] GOTO 10", 9},
               {"SIN[30]X1", 7}, {"12.5F3", 4},   {"#[#1+2]=5", 7},
               {"[#1]", 4},      {"#1+#2", 2}};
  for (const Case& c : cases) {
    const ParseResult p = parse_expression(c.text, 1, ParseMode::kOperandPrefix);
    EXPECT_FALSE(p.alarm) << c.text << ": " << p.alarm.text();
    EXPECT_EQ(p.end, c.end) << c.text;
  }
}

TEST(ExpressionPrefix, LongestExpression) {
  const ParseResult p = parse_expression("#1 + 2 THEN #3=1", 1, ParseMode::kExpressionPrefix);
  ASSERT_FALSE(p.alarm);
  EXPECT_EQ(p.end, 6u);
  const ParseResult q = parse_expression("1+2]", 1, ParseMode::kExpressionPrefix);
  ASSERT_FALSE(q.alarm);
  EXPECT_EQ(q.end, 3u);
  const ParseResult r = parse_expression("1+ GOTO", 1, ParseMode::kExpressionPrefix);
  EXPECT_EQ(r.alarm.number, alarm::kUnknownWord);  // an operand must follow '+'
  EXPECT_EQ(r.alarm.column, 4);
}

TEST(ExpressionPrefix, ParsedOnceEvaluatedManyTimes) {
  VariableStore s;
  const ParseResult p = parse_expression("#1*#1");
  ASSERT_FALSE(p.alarm);
  EXPECT_EQ(p.expression.code().size(), 3u);
  EXPECT_EQ(p.expression.stack_depth(), 2);
  for (int i = 0; i < 10; ++i) {
    ASSERT_FALSE(s.write(1, MacroValue::of(i)));
    EXPECT_EQ(evaluate(p.expression, s).value.number(), i * i);
  }
}

// --- Alarms ----------------------------------------------------------------------------------

struct AlarmCase {
  const char* text;
  int number;
  int column;
};

TEST(ExpressionAlarms, ParseAlarmsWithNumberAndColumn) {
  const AlarmCase cases[] = {
      {"[1+2", alarm::kBracketNotClosed, 1},
      {"SIN[1+2", alarm::kBracketNotClosed, 4},
      {"#[1", alarm::kBracketNotClosed, 2},
      {"1+2]", alarm::kUnexpectedBracket, 4},
      {"1+", alarm::kMissingOperand, 3},
      {"[]", alarm::kMissingOperand, 2},
      {"*2", alarm::kMissingOperand, 1},
      {"1+*2", alarm::kMissingOperand, 3},
      {"1 EQ", alarm::kMissingOperand, 5},
      {"EQ 1", alarm::kMissingOperand, 1},
      {"", alarm::kMissingOperand, 1},
      {"SIN[1,]", alarm::kMissingOperand, 7},
      {"FOO[1]", alarm::kUnknownWord, 1},
      {"1+SINE[1]", alarm::kUnknownWord, 3},
      {"#1 THEN", alarm::kUnknownWord, 4},
      {"1e5", alarm::kUnknownWord, 2},
      {"#-1", alarm::kBadVariableSyntax, 2},
      {"#+1", alarm::kBadVariableSyntax, 2},
      {"#A", alarm::kBadVariableSyntax, 2},
      {"#", alarm::kBadVariableSyntax, 1},
      {"##1", alarm::kBadVariableSyntax, 2},
      {"#1.5", alarm::kBadVariableSyntax, 2},
      {"1 2", alarm::kOperatorExpected, 3},
      {"#1=2", alarm::kOperatorExpected, 3},
      {"1$", alarm::kOperatorExpected, 2},
      {"SIN[1],2", alarm::kOperatorExpected, 7},
      {"[1]SIN[2]", alarm::kOperatorExpected, 4},
      {"SIN 30", alarm::kBracketExpected, 1},
      {"1+PI[2]", alarm::kOperatorExpected, 5},
      {"ATAN2[1]", alarm::kArgumentCount, 1},
      {"SIN[1,2]", alarm::kArgumentCount, 1},
      {"2*ATAN[1,2,3]", alarm::kArgumentCount, 3},
      {"1.2.3", alarm::kMalformedNumber, 1},
      {".", alarm::kMalformedNumber, 1},
      {"1000000000000000000000000000000000000000000000000", alarm::kMalformedNumber, 1},
      {"#1234567890123456", alarm::kUndefinedVariable, 2},
  };
  for (const AlarmCase& c : cases) {
    const ParseResult p = parse_expression(c.text);
    EXPECT_EQ(p.alarm.number, c.number) << c.text << ": " << p.alarm.text();
    EXPECT_EQ(p.alarm.column, c.column) << c.text << ": " << p.alarm.text();
    EXPECT_FALSE(p.alarm.text().empty()) << c.text;
  }
}

TEST(ExpressionAlarms, TextsNameTheProblem) {
  EXPECT_EQ(parse_expression("[1+2").alarm.text(), "'[' at column 1 is not closed");
  EXPECT_EQ(parse_expression("#-1").alarm.text(), "a variable number cannot be negative");
  EXPECT_EQ(parse_expression("FOO[1]").alarm.text(), "unknown function or word 'FOO'");
  EXPECT_EQ(parse_expression("ATAN2[1]").alarm.text(), "ATAN2 takes 2 arguments");
  EXPECT_EQ(parse_expression("ATAN[1,2,3]").alarm.text(), "ATAN takes 1 or 2 arguments");
  EXPECT_EQ(parse_expression("1 2").alarm.text(), "operator expected before '2'");
  EXPECT_EQ(parse_expression("1+").alarm.text(), "operand missing at the end of the expression");
}

TEST(ExpressionAlarms, ColumnsAreThoseOfTheLine) {
  // The text starts at column 10 of its line, e.g. after `N10 G01 X`.
  const ParseResult p = parse_expression("[1+2", 10);
  EXPECT_EQ(p.alarm.column, 10);
  const ParseResult q = parse_expression("1/0", 10);
  ASSERT_FALSE(q.alarm);
  EXPECT_EQ(evaluate(q.expression, VariableStore()).alarm.column, 11);
}

TEST(ExpressionAlarms, NestingLimit) {
  std::string ok;
  std::string deep;
  for (int i = 0; i < 20; ++i) {
    ok += "[";
  }
  ok += "1";
  for (int i = 0; i < 20; ++i) {
    ok += "]";
  }
  EXPECT_FALSE(parse_expression(ok).alarm);  // the spec wants at least 10
  deep = "[" + ok + "]";
  const ParseResult p = parse_expression(deep);
  EXPECT_EQ(p.alarm.number, alarm::kTooComplex);
  EXPECT_EQ(p.alarm.column, 21);
  EXPECT_FALSE(parse_expression(deep, 1, ParseMode::kWhole, ParseLimits{30}).alarm);
  const ParseResult f = parse_expression("SIN[" + ok + "]");
  EXPECT_EQ(f.alarm.number, alarm::kTooComplex);
  std::string signs(40, '-');
  EXPECT_EQ(parse_expression(signs + "1").alarm.number, alarm::kTooComplex);
}

TEST(ExpressionAlarms, StackLimit) {
  std::string text;
  for (int i = 0; i < kMaxEvalStack + 5; ++i) {
    text += "1+[";
  }
  text += "1";
  text += std::string(kMaxEvalStack + 5, ']');
  const ParseResult p = parse_expression(text, 1, ParseMode::kWhole, ParseLimits{1000});
  EXPECT_EQ(p.alarm.number, alarm::kTooComplex);
  EXPECT_EQ(p.alarm.text(), "expression too complex (more than 128 pending operands)");
}

TEST(ExpressionAlarms, EvaluationAlarmsWithNumberAndColumn) {
  MacroDialect d;
  d.local_last = 33;
  VariableStore s(d);
  const AlarmCase cases[] = {
      {"1/0", alarm::kDivisionByZero, 2},
      {"1+1/#0", alarm::kDivisionByZero, 4},  // null counts as 0
      {"5 MOD 0", alarm::kDivisionByZero, 3},
      {"SQRT[-1]", alarm::kOutOfRange, 1},
      {"2+ASIN[2]", alarm::kOutOfRange, 3},
      {"ACOS[1.5]", alarm::kOutOfRange, 1},
      {"LN[0]", alarm::kOutOfRange, 1},
      {"TAN[90]", alarm::kOutOfRange, 1},
      {"ATAN2[0,0]", alarm::kOutOfRange, 1},
      {"ROUND2[1,-1]", alarm::kOutOfRange, 1},
      {"POW[-8,0.5]", alarm::kOutOfRange, 1},
      {"BIN[10]", alarm::kOutOfRange, 1},
      {"BCD[-1]", alarm::kOutOfRange, 1},
      {"EXP[200]", alarm::kOutOfRange, 1},
      {"1+POW[10,40]*POW[10,40]", alarm::kOutOfRange, 13},
      {"~POW[2,60]", alarm::kOutOfRange, 1},
      {"#[1.5]", alarm::kVariableNumberNotInteger, 1},
      {"1+#[-1]", alarm::kUndefinedVariable, 3},
      {"#[0-1]", alarm::kUndefinedVariable, 1},
      {"1+#1234", alarm::kUndefinedVariable, 3},
      {"#34", alarm::kUndefinedVariable, 1},  // GSK-style locals end at #33
      {"#[POW[10,20]]", alarm::kUndefinedVariable, 1},
  };
  for (const AlarmCase& c : cases) {
    const ParseResult p = parse_expression(c.text);
    ASSERT_FALSE(p.alarm) << c.text << ": " << p.alarm.text();
    const EvalResult r = evaluate(p.expression, s);
    EXPECT_EQ(r.alarm.number, c.number) << c.text << ": " << r.alarm.text();
    EXPECT_EQ(r.alarm.column, c.column) << c.text << ": " << r.alarm.text();
    EXPECT_FALSE(r.alarm.text().empty()) << c.text;
  }
  EXPECT_EQ(eval_text("SQRT[-1]", s).alarm.text(), "SQRT of a negative value");
  EXPECT_EQ(eval_text("1/0", s).alarm.text(), "division by zero");
  EXPECT_EQ(eval_text("#[1.5]", s).alarm.text(), "variable number 1.5 is not an integer");
}

TEST(AssignmentAlarms, NumbersAndColumns) {
  VariableStore s;
  const AlarmCase parse_cases[] = {
      {"#1 5", alarm::kAssignmentExpected, 4},  {"#1", alarm::kAssignmentExpected, 3},
      {"#1==5", alarm::kAssignmentExpected, 3}, {"X=5", alarm::kAssignmentExpected, 1},
      {"", alarm::kAssignmentExpected, 1},      {"#1=", alarm::kMissingOperand, 4},
      {"#1=2)", alarm::kOperatorExpected, 5},   {"#-1=2", alarm::kBadVariableSyntax, 2},
      {"#[1=2", alarm::kOperatorExpected, 4},   {"  #1 = 2 3", alarm::kOperatorExpected, 10},
  };
  for (const AlarmCase& c : parse_cases) {
    const AssignmentParse p = parse_assignment(c.text);
    EXPECT_EQ(p.alarm.number, c.number) << c.text << ": " << p.alarm.text();
    EXPECT_EQ(p.alarm.column, c.column) << c.text << ": " << p.alarm.text();
  }
  const AlarmCase exec_cases[] = {
      {"#0=5", alarm::kReadOnlyVariable, 1},
      {"  #[#1]=5", alarm::kReadOnlyVariable, 3},  // #1 null: #[0]
      {"#1000=5", alarm::kUndefinedVariable, 1},
      {"#[-2]=5", alarm::kUndefinedVariable, 1},
      {"#[0.5]=5", alarm::kVariableNumberNotInteger, 1},
      {"#1=1/0", alarm::kDivisionByZero, 5},
      {"#[1/0]=1", alarm::kDivisionByZero, 4},
  };
  for (const AlarmCase& c : exec_cases) {
    const AssignmentParse p = parse_assignment(c.text);
    ASSERT_FALSE(p.alarm) << c.text << ": " << p.alarm.text();
    const MacroAlarm a = execute(p.assignment, s);
    EXPECT_EQ(a.number, c.number) << c.text << ": " << a.text();
    EXPECT_EQ(a.column, c.column) << c.text << ": " << a.text();
  }
  // A failed statement writes nothing.
  EXPECT_TRUE(s.read(1).value.is_null());
}

TEST(Assignment, FormsAndNull) {
  VariableStore s;
  ASSERT_FALSE(assign("#1 = 2.5", s));
  ASSERT_FALSE(assign("#[#1*2]=#1", s));  // #5 = 2.5
  EXPECT_EQ(s.read(5).value, MacroValue::of(2.5));
  ASSERT_FALSE(assign("#5=[#7]", s));  // bracketed null stays null
  EXPECT_TRUE(s.read(5).value.is_null());
  ASSERT_FALSE(assign("#500=#1", s));
  EXPECT_EQ(s.read(500).value, MacroValue::of(2.5));
  const AssignmentParse p = parse_assignment("#101=3", 12);
  ASSERT_FALSE(p.alarm);
  EXPECT_EQ(p.assignment.target, 101);
  EXPECT_EQ(p.assignment.target_column, 12);
}

}  // namespace
}  // namespace mcnc::interp::macro
