// The tool table as a value: what an offset amounts to on an axis (geometry plus wear), for the
// lathe's T offsets and the mill's G43/G44 length.
#include "channel/interp/state/tool_table.hpp"

#include <gtest/gtest.h>

namespace mcnc::interp::state {
namespace {

ToolTable table() {
  ToolTable::Offsets geometry{};
  ToolTable::Offsets wear{};
  geometry[3] = {.x = 10.0, .z = -4.0, .y = 1.5, .radius = 0.4, .tip = 3};
  wear[3] = {.x = 0.2, .z = 0.1, .y = -0.5, .radius = 0.02, .tip = 7};
  return ToolTable(geometry, wear);
}

TEST(ToolTable, TheLatheOffsetIsGeometryPlusWearWithXHalvedOnADiameterAxis) {
  ToolTable t = table();
  EXPECT_EQ(t.lathe_offset('X', true), 0.0);  // no offset selected
  t.offset = 3;
  EXPECT_DOUBLE_EQ(t.lathe_offset('X', true), 5.1);
  EXPECT_DOUBLE_EQ(t.lathe_offset('X', false), 10.2);
  EXPECT_DOUBLE_EQ(t.lathe_offset('Z', true), -3.9);
  EXPECT_DOUBLE_EQ(t.lathe_offset('Y', true), 1.0);
  EXPECT_EQ(t.lathe_offset('C', true), 0.0);
}

TEST(ToolTable, TheMillLengthActsOnZUnderG43OrG44Only) {
  ToolTable t = table();
  t.length_offset = 3;
  EXPECT_EQ(t.mill_length('Z'), 0.0);  // G49
  t.length_sign = 1;                   // G43
  EXPECT_DOUBLE_EQ(t.mill_length('Z'), -3.9);
  EXPECT_EQ(t.mill_length('X'), 0.0);
  t.length_sign = -1;  // G44
  EXPECT_DOUBLE_EQ(t.mill_length('Z'), 3.9);
  t.length_offset = 0;  // no H
  EXPECT_EQ(t.mill_length('Z'), 0.0);
}

TEST(ToolTable, TheNoseRadiusAddsTheWearAndTheTipIsTheGeometrys) {
  ToolTable t = table();
  EXPECT_DOUBLE_EQ(t.radius(3), 0.42);
  EXPECT_EQ(t.tip(3), 3);
  t.values(false, 3).radius = 0.1;  // G10 / #2xxx write the wear
  EXPECT_DOUBLE_EQ(t.radius(3), 0.5);
  EXPECT_EQ(t.values(true, 3).x, 10.0);
}

}  // namespace
}  // namespace mcnc::interp::state
