// `mcnc status` against a live machine: it joins the machine's domain as a viewer and prints
// what the channel and the axes say while a program runs.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <regex>
#include <utility>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

TEST(Status, PrintsTheRunningChannelAndWhereItsAxesStand) {
  TestMachine machine("small_lathe.yaml", 83);
  const std::string program = machine.file("dwell.nc");
  // A long dwell after the move: the machine stays up, its positions fixed, until stopped.
  std::ofstream(program) << "G00 X10 Z-5\nG04 X600\nM30\n";
  Background running({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + program},
                     machine.domain(), machine.file("run.log"));
  RunResult status;
  const bool seen = eventually(
      [&] {
        status = run({bin("mcnc"), "status", machine.path(), "--wait-ms", "2000"}, machine.domain(),
                     30s);
        return status.exit_code == 0 && status.out.find("line 2") != std::string::npos;
      },
      60s);
  running.kill(SIGINT);
  running.wait(30s);
  ASSERT_TRUE(seen) << status.out << status.err;
  EXPECT_TRUE(std::regex_search(status.out, std::regex("CH1  running  block 2/[0-9]+  line 2\\n")))
      << status.out;
  // X1 is programmed in diameter: its slide stands at the radius. The drives stand within
  // their in-position width.
  for (const auto& [axis, at] : {std::pair{"X1", 5.0}, std::pair{"Z1", -5.0}}) {
    std::smatch m;
    const std::regex line(std::string(axis) + R"( +CH1 +cmd (-?[0-9.]+)  act (-?[0-9.]+))");
    ASSERT_TRUE(std::regex_search(status.out, m, line)) << axis << "\n" << status.out;
    EXPECT_DOUBLE_EQ(std::stod(m[1]), at) << axis;
    EXPECT_NEAR(std::stod(m[2]), at, 0.0005) << axis;
  }
}

TEST(Status, NoMachineOnTheDomainIsExitOneNamingWhatWasNotHeard) {
  TestMachine machine("small_lathe.yaml", 84);
  const RunResult r =
      run({bin("mcnc"), "status", machine.path(), "--wait-ms", "300"}, machine.domain(), 30s);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("CH1  no status"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("X1   no feedback"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("is small_lathe running?"), std::string::npos) << r.err;
}

}  // namespace
