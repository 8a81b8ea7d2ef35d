#include "channel/interp/macro/macro_value.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::interp::macro {
namespace {

const MacroValue kNull = MacroValue::null();
const MacroValue kZero = MacroValue::of(0.0);
const MacroValue kOne = MacroValue::of(1.0);
const MacroValue kMinusOne = MacroValue::of(-1.0);

TEST(MacroValue, DefaultIsNullAndCountsAsZero) {
  const MacroValue v;
  EXPECT_TRUE(v.is_null());
  EXPECT_EQ(v.number(), 0.0);
  EXPECT_EQ(v, kNull);
}

TEST(MacroValue, IdentitySeparatesNullFromZero) {
  EXPECT_FALSE(kZero.is_null());
  EXPECT_EQ(kZero.number(), 0.0);
  EXPECT_NE(kNull, kZero);
  EXPECT_EQ(kZero, MacroValue::of(-0.0));
  EXPECT_EQ(MacroValue::of(2.5), MacroValue::of(2.5));
  EXPECT_NE(MacroValue::of(2.5), MacroValue::of(2.25));
}

// Dafeng L6439-6445, gsk B.4 item 8a: a null value removes its address word; 0 does not.
TEST(MacroValue, NullWordDisappearsZeroWordStays) {
  EXPECT_FALSE(as_word_value(kNull).has_value());
  ASSERT_TRUE(as_word_value(kZero).has_value());
  EXPECT_EQ(*as_word_value(kZero), 0.0);
  EXPECT_EQ(*as_word_value(MacroValue::of(100.0)), 100.0);
}

// Dafeng L6455-6468: ==/!= tell null from 0; >=, >, <=, < treat null as 0.
TEST(MacroValue, DafengComparisonTableL6455) {
  // #1=#0: #1==#0 holds, #1==0 does not, #1!=0 holds, #1>=0 holds.
  EXPECT_TRUE(compare(CompareOp::kEq, kNull, kNull));
  EXPECT_FALSE(compare(CompareOp::kEq, kNull, kZero));
  EXPECT_TRUE(compare(CompareOp::kNe, kNull, kZero));
  EXPECT_TRUE(compare(CompareOp::kGe, kNull, kZero));
}

struct Row {
  CompareOp op;
  MacroValue a;
  MacroValue b;
  bool as_zero;  // VacantOrdering::kAsZero (Dafeng, default)
  bool literal;  // VacantOrdering::kLiteralGskTable
};

TEST(MacroValue, EveryComparisonWithNullUnderBothOrderings) {
  const Row rows[] = {
      {CompareOp::kEq, kNull, kNull, true, true},
      {CompareOp::kEq, kNull, kZero, false, false},
      {CompareOp::kEq, kZero, kNull, false, false},
      {CompareOp::kEq, kZero, kZero, true, true},
      {CompareOp::kNe, kNull, kNull, false, false},
      {CompareOp::kNe, kNull, kZero, true, true},
      {CompareOp::kNe, kZero, kNull, true, true},
      {CompareOp::kGt, kNull, kNull, false, false},
      {CompareOp::kGt, kZero, kNull, false, false},
      {CompareOp::kGt, kNull, kZero, false, false},
      {CompareOp::kGt, kOne, kNull, true, true},
      {CompareOp::kGt, kNull, kMinusOne, true, true},
      {CompareOp::kGe, kNull, kNull, true, true},
      {CompareOp::kGe, kNull, kZero, true, false},
      {CompareOp::kGe, kZero, kNull, true, false},  // the configurable cell of gsk B.4 8c
      {CompareOp::kGe, kOne, kNull, true, true},
      {CompareOp::kGe, kNull, kOne, false, false},
      {CompareOp::kLt, kNull, kZero, false, false},
      {CompareOp::kLt, kNull, kOne, true, true},
      {CompareOp::kLt, kMinusOne, kNull, true, true},
      {CompareOp::kLe, kNull, kNull, true, true},
      {CompareOp::kLe, kNull, kZero, true, false},
      {CompareOp::kLe, kZero, kNull, true, false},
      {CompareOp::kLe, kNull, kMinusOne, false, false},
  };
  int i = 0;
  for (const Row& r : rows) {
    EXPECT_EQ(compare(r.op, r.a, r.b, VacantOrdering::kAsZero), r.as_zero) << "row " << i;
    EXPECT_EQ(compare(r.op, r.a, r.b, VacantOrdering::kLiteralGskTable), r.literal) << "row " << i;
    ++i;
  }
}

// gsk B.4 item 8c, the seed's literal table (with the NE row read as `#1 NE 0`, its [PROPOSAL]).
TEST(MacroValue, GskSeedTableUnderLiteralOrdering) {
  const auto lit = VacantOrdering::kLiteralGskTable;
  EXPECT_TRUE(compare(CompareOp::kEq, kNull, kNull, lit));   // #1 EQ #0, #1 vacant
  EXPECT_FALSE(compare(CompareOp::kEq, kZero, kNull, lit));  // #1 EQ #0, #1 = 0
  EXPECT_TRUE(compare(CompareOp::kNe, kNull, kZero, lit));   // #1 NE 0, #1 vacant
  EXPECT_FALSE(compare(CompareOp::kNe, kZero, kZero, lit));  // #1 NE 0, #1 = 0
  EXPECT_TRUE(compare(CompareOp::kGe, kNull, kNull, lit));   // #1 GE #0, #1 vacant
  EXPECT_FALSE(compare(CompareOp::kGe, kZero, kNull, lit));  // #1 GE #0, #1 = 0
  EXPECT_FALSE(compare(CompareOp::kGt, kNull, kNull, lit));  // #1 GT #0, #1 vacant
  EXPECT_FALSE(compare(CompareOp::kGt, kZero, kNull, lit));  // #1 GT #0, #1 = 0
}

TEST(MacroValue, NumericComparisonsWithoutNull) {
  const MacroValue two = MacroValue::of(2.0);
  EXPECT_TRUE(compare(CompareOp::kGt, two, kOne));
  EXPECT_FALSE(compare(CompareOp::kGt, kOne, two));
  EXPECT_TRUE(compare(CompareOp::kGe, two, two));
  EXPECT_TRUE(compare(CompareOp::kLt, kOne, two));
  EXPECT_TRUE(compare(CompareOp::kLe, two, two));
  EXPECT_FALSE(compare(CompareOp::kLe, two, kOne));
  EXPECT_TRUE(compare(CompareOp::kNe, kOne, two));
}

TEST(MacroValue, AlarmFormatsIntoItsOwnBuffer) {
  const MacroAlarm a = make_alarm(3112, 7, "%s by zero", "division");
  EXPECT_TRUE(a);
  EXPECT_EQ(a.number, 3112);
  EXPECT_EQ(a.column, 7);
  EXPECT_EQ(a.text(), "division by zero");
  EXPECT_FALSE(MacroAlarm{});
  const std::string long_text(300, 'x');
  const MacroAlarm cut = make_alarm(1, 0, "%s", long_text.c_str());
  EXPECT_EQ(cut.text().size(), cut.text_buffer.size() - 1);
}

}  // namespace
}  // namespace mcnc::interp::macro
