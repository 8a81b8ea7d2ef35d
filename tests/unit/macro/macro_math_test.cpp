#include "channel/interp/macro/macro_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mcnc::interp::macro {
namespace {

double call(Function f, double a) {
  const MathResult r = apply_function(f, &a, 1);
  EXPECT_TRUE(r.ok()) << function_info(f).name << ": " << (r.error ? r.error : "");
  return r.value;
}

double call2(Function f, double a, double b) {
  const double args[2] = {a, b};
  const MathResult r = apply_function(f, args, 2);
  EXPECT_TRUE(r.ok()) << function_info(f).name << ": " << (r.error ? r.error : "");
  return r.value;
}

bool fails(Function f, double a) {
  return !apply_function(f, &a, 1).ok();
}

bool fails2(Function f, double a, double b) {
  const double args[2] = {a, b};
  return !apply_function(f, args, 2).ok();
}

TEST(MacroMath, FunctionTableHasEveryFunctionOfSection42) {
  for (const char* name :
       {"SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "ATAN2", "SQRT", "ABS", "ROUND", "ROUND2",
        "INT", "FIX", "FUP", "LN", "EXP", "POW", "BIN", "BCD"}) {
    const FunctionInfo* f = find_function(name);
    ASSERT_NE(f, nullptr) << name;
    EXPECT_EQ(f->name, name);
    EXPECT_EQ(&function_info(f->function), f);
  }
  EXPECT_EQ(find_function("ADP"), nullptr);  // not in the spec
  EXPECT_EQ(find_function("sin"), nullptr);  // the parser upper-cases
  EXPECT_EQ(find_function("ATAN")->max_args, 2);
}

// Dafeng L6878-6886 (spec §4.2, §7.9 #72): FUP away from zero, FIX toward zero, INT half away.
TEST(MacroMath, FupFixIntExamplesL6878) {
  EXPECT_EQ(call(Function::kFup, 1.2), 2.0);
  EXPECT_EQ(call(Function::kFup, -1.2), -2.0);
  EXPECT_EQ(call(Function::kFix, 1.2), 1.0);
  EXPECT_EQ(call(Function::kFix, -1.2), -1.0);
  EXPECT_EQ(call(Function::kInt, 1.5), 2.0);
  EXPECT_EQ(call(Function::kInt, -1.5), -2.0);
}

TEST(MacroMath, RoundingEdges) {
  EXPECT_EQ(call(Function::kInt, 1.4999), 1.0);
  EXPECT_EQ(call(Function::kInt, 2.5), 3.0);
  EXPECT_EQ(call(Function::kInt, -0.4), 0.0);
  EXPECT_FALSE(std::signbit(call(Function::kInt, -0.4)));  // no "-0"
  EXPECT_EQ(call(Function::kFix, 3.0), 3.0);
  EXPECT_EQ(call(Function::kFup, 3.0), 3.0);
  EXPECT_EQ(call(Function::kFup, 0.0001), 1.0);
  EXPECT_EQ(call(Function::kFix, -0.9), 0.0);
  // Decimal intent wins over binary noise: [0.3-0.1]*10 is 1.9999999999999996 in binary.
  EXPECT_EQ(call(Function::kFix, (0.3 - 0.1) * 10.0), 2.0);
  EXPECT_EQ(call(Function::kFup, 0.1 * 3.0 * 10.0), 3.0);  // 3.0000000000000004
  EXPECT_EQ(fix(1e300), 1e300);
}

// Decision D16 (spec L6830): ROUND keeps 3 decimals, half away from zero; ROUND2 takes k.
TEST(MacroMath, RoundKeepsThreeDecimalsL6830) {
  EXPECT_EQ(call(Function::kRound, 1.23456), 1.235);
  EXPECT_EQ(call(Function::kRound, 1.2344), 1.234);
  EXPECT_EQ(call(Function::kRound, 2.0005), 2.001);  // 2000.4999999999998 increments
  EXPECT_EQ(call(Function::kRound, -2.0005), -2.001);
  EXPECT_EQ(call(Function::kRound, 7.0), 7.0);
  EXPECT_EQ(call2(Function::kRound2, 2.675, 2), 2.68);
  EXPECT_EQ(call2(Function::kRound2, 1.25, 1), 1.3);
  EXPECT_EQ(call2(Function::kRound2, -1.25, 1), -1.3);
  EXPECT_EQ(call2(Function::kRound2, 2.5, 0), 3.0);
  EXPECT_EQ(call2(Function::kRound2, 1.23456789, 6), 1.234568);
  EXPECT_TRUE(fails2(Function::kRound2, 1.0, -1));
  EXPECT_TRUE(fails2(Function::kRound2, 1.0, 16));
  EXPECT_TRUE(fails2(Function::kRound2, 1.0, 1.5));
}

TEST(MacroMath, TrigonometryInDegreesExactAtSpecialAngles) {
  EXPECT_EQ(call(Function::kSin, 0), 0.0);
  EXPECT_EQ(call(Function::kSin, 30), 0.5);
  EXPECT_EQ(call(Function::kSin, 90), 1.0);
  EXPECT_EQ(call(Function::kSin, 150), 0.5);
  EXPECT_EQ(call(Function::kSin, 180), 0.0);
  EXPECT_EQ(call(Function::kSin, 210), -0.5);
  EXPECT_EQ(call(Function::kSin, 270), -1.0);
  EXPECT_EQ(call(Function::kSin, -90), -1.0);
  EXPECT_EQ(call(Function::kSin, 720 + 30), 0.5);
  EXPECT_EQ(call(Function::kCos, 0), 1.0);
  EXPECT_EQ(call(Function::kCos, 60), 0.5);
  EXPECT_EQ(call(Function::kCos, 90), 0.0);
  EXPECT_EQ(call(Function::kCos, 120), -0.5);
  EXPECT_EQ(call(Function::kCos, 180), -1.0);
  EXPECT_EQ(call(Function::kCos, 270), 0.0);
  EXPECT_EQ(call(Function::kCos, -60), 0.5);
  EXPECT_EQ(call(Function::kTan, 45), 1.0);
  EXPECT_EQ(call(Function::kTan, 135), -1.0);
  EXPECT_EQ(call(Function::kTan, 0), 0.0);
  EXPECT_TRUE(fails(Function::kTan, 90));
  EXPECT_TRUE(fails(Function::kTan, -270));
  // gsk D3-9: the argument is in degrees; 90°30' is 90.5.
  EXPECT_NEAR(call(Function::kSin, 90.5), std::sin(90.5 * std::numbers::pi / 180), 1e-15);
  EXPECT_NEAR(call(Function::kSin, 20), 0.3420201433256687, 1e-15);
  EXPECT_NEAR(call(Function::kCos, 50), 0.6427876096865394, 1e-15);
  EXPECT_NEAR(call(Function::kTan, 3), 0.05240777928304121, 1e-16);
  EXPECT_TRUE(fails(Function::kSin, INFINITY));
}

// Dafeng L6853-6858: ASIN -90..90, ACOS 0..180; gsk D3-9: ASIN[2], ACOS[1.5] are P/S 111.
TEST(MacroMath, InverseTrigonometryRangesL6853) {
  EXPECT_EQ(call(Function::kAsin, 1), 90.0);
  EXPECT_EQ(call(Function::kAsin, -1), -90.0);
  EXPECT_EQ(call(Function::kAsin, 0.5), 30.0);
  EXPECT_EQ(call(Function::kAsin, -0.5), -30.0);  // gsk D3-9 with NAT = 1
  EXPECT_NEAR(call(Function::kAsin, 0.3), 17.457603123722095, 1e-12);
  EXPECT_EQ(call(Function::kAcos, -1), 180.0);  // gsk D3-9
  EXPECT_EQ(call(Function::kAcos, 1), 0.0);
  EXPECT_EQ(call(Function::kAcos, 0), 90.0);
  EXPECT_EQ(call(Function::kAcos, 0.5), 60.0);
  EXPECT_EQ(call(Function::kAcos, -0.5), 120.0);
  EXPECT_NEAR(call(Function::kAcos, 0.3), 72.54239687627791, 1e-12);
  EXPECT_EQ(call(Function::kAsin, 1.0 + 2e-16), 90.0);  // a few ulps beyond count as 1
  EXPECT_TRUE(fails(Function::kAsin, 2));
  EXPECT_TRUE(fails(Function::kAsin, -1.000001));
  EXPECT_TRUE(fails(Function::kAcos, 1.5));
  EXPECT_TRUE(fails(Function::kAcos, NAN));
}

// Dafeng L6804: ATAN2[#j,#k], #j opposite, #k adjacent; ATAN[#j] is the one-argument form.
TEST(MacroMath, ArcTangentForms) {
  EXPECT_EQ(call(Function::kAtan, 1), 45.0);
  EXPECT_EQ(call(Function::kAtan, -1), -45.0);
  EXPECT_EQ(call(Function::kAtan, 0), 0.0);
  EXPECT_NEAR(call(Function::kAtan, 1e30), 90.0, 1e-12);
  EXPECT_EQ(call2(Function::kAtan2, 1, 1), 45.0);
  EXPECT_EQ(call2(Function::kAtan2, 1, -1), 135.0);
  EXPECT_EQ(call2(Function::kAtan2, -1, -1), -135.0);
  EXPECT_EQ(call2(Function::kAtan2, -1, 1), -45.0);
  EXPECT_EQ(call2(Function::kAtan2, 1, 0), 90.0);
  EXPECT_EQ(call2(Function::kAtan2, -1, 0), -90.0);
  EXPECT_EQ(call2(Function::kAtan2, 0, -1), 180.0);
  EXPECT_EQ(call2(Function::kAtan2, 0, 1), 0.0);
  EXPECT_NEAR(call2(Function::kAtan2, 1, std::sqrt(3.0)), 30.0, 1e-12);
  EXPECT_EQ(call2(Function::kAtan, 1, -1), 135.0);  // ATAN[j,k] = ATAN2[j,k]
  EXPECT_TRUE(fails2(Function::kAtan2, 0, 0));
}

TEST(MacroMath, OtherFunctions) {
  EXPECT_EQ(call(Function::kSqrt, 16), 4.0);
  EXPECT_EQ(call(Function::kSqrt, 0), 0.0);
  EXPECT_TRUE(fails(Function::kSqrt, -1));
  EXPECT_EQ(call(Function::kAbs, -3.5), 3.5);
  EXPECT_EQ(call(Function::kAbs, 3.5), 3.5);
  EXPECT_EQ(call(Function::kLn, 1), 0.0);
  EXPECT_NEAR(call(Function::kLn, std::numbers::e), 1.0, 1e-15);
  EXPECT_TRUE(fails(Function::kLn, 0));
  EXPECT_TRUE(fails(Function::kLn, -2));
  EXPECT_EQ(call(Function::kExp, 0), 1.0);
  EXPECT_NEAR(call(Function::kExp, 1), std::numbers::e, 1e-15);
  EXPECT_EQ(call2(Function::kPow, 2, 10), 1024.0);
  EXPECT_EQ(call2(Function::kPow, -2, 3), -8.0);
  EXPECT_EQ(call2(Function::kPow, 9, 0.5), 3.0);
  EXPECT_EQ(call2(Function::kPow, 0, 0), 1.0);
  EXPECT_TRUE(fails2(Function::kPow, -8, 1.0 / 3.0));
  EXPECT_TRUE(fails2(Function::kPow, 0, -1));
}

// BIN and BCD (gsk A.7.4, FANUC set): BCD -> binary and binary -> BCD.
TEST(MacroMath, BinAndBcd) {
  EXPECT_EQ(call(Function::kBcd, 1234), 4660.0);  // 0x1234
  EXPECT_EQ(call(Function::kBin, 4660), 1234.0);
  EXPECT_EQ(call(Function::kBcd, 0), 0.0);
  EXPECT_EQ(call(Function::kBcd, 99999999), 2576980377.0);  // 0x99999999
  EXPECT_EQ(call(Function::kBin, 2576980377.0), 99999999.0);
  EXPECT_TRUE(fails(Function::kBin, 10));  // 0xA is not a BCD digit
  EXPECT_TRUE(fails(Function::kBin, -1));
  EXPECT_TRUE(fails(Function::kBcd, 100000000));
  EXPECT_TRUE(fails(Function::kBcd, 1.5));
}

TEST(MacroMath, BitIntegers) {
  EXPECT_EQ(to_bit_integer(5.0), 5);
  EXPECT_EQ(to_bit_integer(5.5), 6);
  EXPECT_EQ(to_bit_integer(-5.5), -6);
  EXPECT_EQ(to_bit_integer(9007199254740991.0), 9007199254740991);
  EXPECT_FALSE(to_bit_integer(9007199254740992.0 * 2));
  EXPECT_FALSE(to_bit_integer(NAN));
}

// Dafeng L6671-6676 (§7.9 #71): a value in an address is truncated to the least increment;
// gsk B.4 item 6 / D3-7: rounded.
TEST(MacroMath, WordValueTruncatedOrRoundedL6671) {
  EXPECT_EQ(quantize_word_value(12.3455, 3, WordRounding::kTruncate), 12.345);
  EXPECT_EQ(quantize_word_value(-12.3455, 3, WordRounding::kTruncate), -12.345);
  EXPECT_EQ(quantize_word_value(12.3456, 3, WordRounding::kRound), 12.346);
  EXPECT_EQ(quantize_word_value(-12.3456, 3, WordRounding::kRound), -12.346);
  EXPECT_EQ(quantize_word_value(1.001, 3, WordRounding::kTruncate), 1.001);  // 1000.99999...
  EXPECT_EQ(quantize_word_value(12.3455, 4, WordRounding::kTruncate), 12.3455);
  EXPECT_EQ(quantize_word_value(0.0004, 3, WordRounding::kTruncate), 0.0);
  EXPECT_FALSE(std::signbit(quantize_word_value(-0.0004, 3, WordRounding::kTruncate)));
}

}  // namespace
}  // namespace mcnc::interp::macro
