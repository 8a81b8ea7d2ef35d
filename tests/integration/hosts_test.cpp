// A machine across hosts (issue 22). The cell of three hosts (launch/machines/cell_3ncu.yaml:
// the twin turret, its loader on a third host, Z3 a link axis) run on one host gives the twin
// turret's traces event for event, in the part transfer of launch/programs (G144 in CH3,
// G140/G141/G142 of A1, G04.1) and in CT-G1141-01 (G114.1 of S2 to S1): the file's hosts
// change where processes run, never what the machine does.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace mcnc::test;
using namespace std::chrono_literals;

namespace {

std::vector<nlohmann::json> run_programs(const std::string& machine_file, int domain,
                                         const std::string& ch1, const std::string& ch2) {
  TestMachine machine(machine_file, domain);
  const std::string trace = machine.file("trace.jsonl");
  const RunResult r = run({bin("mcnc"), "run", machine.path(), "--trace", trace, "--program",
                           "CH1=" + source(ch1), "--program", "CH2=" + source(ch2)},
                          -1, 300s);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return trace_until_end(read_trace(trace));
}

void expect_same_trace(const std::vector<nlohmann::json>& turret,
                       const std::vector<nlohmann::json>& cell) {
  ASSERT_GT(turret.size(), 1000U);
  ASSERT_EQ(turret.size(), cell.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < turret.size() && differ < 5; ++i) {
    if (turret[i] != cell[i]) {
      ++differ;
      ADD_FAILURE() << "event " << i << "\n" << turret[i].dump() << "\n" << cell[i].dump();
    }
  }
}

std::size_t count(const std::vector<nlohmann::json>& trace, const std::string& ev,
                  const std::string& key, const std::string& value) {
  std::size_t n = 0;
  for (const nlohmann::json& e : trace) {
    n += e["ev"] == ev && e.value(key, "") == value && e["cycle"] != 0 ? 1 : 0;
  }
  return n;
}

}  // namespace

TEST(Hosts, TheCellOfThreeHostsOnOneHostRunsAsTheTwinTurret) {
  const std::string ch1 = "launch/programs/part_transfer_ch1.nc";
  const std::string ch2 = "launch/programs/part_transfer_ch2.nc";
  const auto cell = run_programs("cell_3ncu.yaml", 161, ch1, ch2);
  expect_same_trace(run_programs("twin_turret.yaml", 160, ch1, ch2), cell);
  EXPECT_GE(count(cell, "owner", "axis", "A1"), 2U) << "A1 lent from ncu1 to ncu2 and back";
  EXPECT_EQ(count(cell, "sync_arrive", "ch", "CH2"), 2U);

  const std::string g1141 = "tests/integration/programs/g1141/";
  const auto coupled = run_programs("cell_3ncu.yaml", 163, g1141 + "ch1.nc", g1141 + "ch2.nc");
  expect_same_trace(run_programs("twin_turret.yaml", 162, g1141 + "ch1.nc", g1141 + "ch2.nc"),
                    coupled);
  EXPECT_EQ(count(coupled, "couple", "slave", "S2"), 1U) << "S2 on ncu2 follows S1 on ncu1";
}
