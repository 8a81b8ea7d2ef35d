// The traces of the multi-channel spec examples, cycle for cycle, against goldens kept from
// before the interpreter left the channel's cycle (issue 23): the read-ahead thread must change
// nothing a run does in lockstep. Each golden is the trace up to the run's end, one event a line
// (tests/fixtures/traces/). MCNC_WRITE_GOLDEN=1 writes them anew instead of comparing: only for
// a change that means to change a run, said in its commit.
#include "harness.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

struct Example {
  std::string name;
  std::string machine;
  std::map<std::string, std::string> programs;  // channel -> program (source tree path)
  std::string progdir;                          // source tree path; "" for none
  int domain;
};

std::vector<nlohmann::json> run_example(const Example& x) {
  TestMachine machine(x.machine, x.domain);
  const std::string trace = machine.file("trace.jsonl");
  std::vector<std::string> argv{bin("mcnc"), "run", machine.path(), "--trace", trace};
  for (const auto& [ch, program] : x.programs) {
    argv.push_back("--program");
    argv.push_back(ch + "=" + source(program));
  }
  if (!x.progdir.empty()) {
    argv.push_back("--progdir");
    argv.push_back(source(x.progdir));
  }
  const RunResult r = run(argv, -1, 300s);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return trace_until_end(read_trace(trace));
}

void expect_golden(const Example& x) {
  const std::vector<nlohmann::json> trace = run_example(x);
  ASSERT_GT(trace.size(), 100U);
  const std::string golden = source("tests/fixtures/traces/" + x.name + ".jsonl");
  const char* write = std::getenv("MCNC_WRITE_GOLDEN");
  if (write != nullptr && std::string(write) == "1") {
    std::ofstream out(golden);
    for (const nlohmann::json& e : trace) {
      out << e.dump() << "\n";
    }
    return;
  }
  const std::vector<nlohmann::json> expected = read_trace(golden);
  ASSERT_FALSE(expected.empty()) << golden;
  EXPECT_EQ(trace.size(), expected.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < trace.size() && i < expected.size() && differ < 5; ++i) {
    if (trace[i] != expected[i]) {
      ++differ;
      ADD_FAILURE() << x.name << ", event " << i << "\ngolden: " << expected[i].dump()
                    << "\nnow:    " << trace[i].dump();
    }
  }
}

}  // namespace

TEST(GoldenTrace, TwinTurretBarriers) {
  expect_golden({"twin_turret",
                 "twin_turret.yaml",
                 {{"CH1", "launch/programs/twin_turret_ch1.nc"},
                  {"CH2", "launch/programs/twin_turret_ch2.nc"}},
                 "",
                 190});
}

TEST(GoldenTrace, PartTransfer) {
  expect_golden({"part_transfer",
                 "twin_turret.yaml",
                 {{"CH1", "launch/programs/part_transfer_ch1.nc"},
                  {"CH2", "launch/programs/part_transfer_ch2.nc"}},
                 "",
                 191});
}

TEST(GoldenTrace, AxisExchangeG140) {
  expect_golden({"g140",
                 "twin_turret.yaml",
                 {{"CH1", "tests/integration/programs/g140/ch1.nc"},
                  {"CH2", "tests/integration/programs/g140/ch2.nc"}},
                 "",
                 192});
}

TEST(GoldenTrace, SpindleSyncG1141) {
  expect_golden({"g1141",
                 "twin_turret.yaml",
                 {{"CH1", "tests/integration/programs/g1141/ch1.nc"},
                  {"CH2", "tests/integration/programs/g1141/ch2.nc"}},
                 "",
                 193});
}

TEST(GoldenTrace, ThreeChannelMarksG041) {
  expect_golden({"g041",
                 "three_channel.yaml",
                 {{"CH1", "tests/integration/programs/g041/O1001.nc"},
                  {"CH2", "tests/integration/programs/g041/O1002.nc"},
                  {"CH3", "tests/integration/programs/g041/O1003.nc"}},
                 "",
                 194});
}

TEST(GoldenTrace, CallInAnotherChannelG144) {
  expect_golden({"g144_wait",
                 "three_channel.yaml",
                 {{"CH1", "tests/integration/programs/g144_wait/O1000.nc"}},
                 "tests/integration/programs/g144_wait/",
                 195});
}
