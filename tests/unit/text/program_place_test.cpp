#include "common/text/program_place.hpp"

#include <gtest/gtest.h>

using mcnc::text::program_place;

TEST(ProgramPlace, FileLineAndColumnAsCompilersPrintThem) {
  EXPECT_EQ(program_place("progs/O2000.nc", 3, 10), "progs/O2000.nc:3:10");
  EXPECT_EQ(program_place("main.nc", 7, 0), "main.nc:7");
  EXPECT_EQ(program_place("", 7, 2), "line 7");
  EXPECT_EQ(program_place("main.nc", 0, 0), "");
}
