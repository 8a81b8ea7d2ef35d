// The twin turret's coordination examples across hosts (issue 22): each run on one host, then
// with the same machine split over simulated hosts, gives the same trace event for event, and
// the coordination it shows really crossed from one host to another. Splits of cell_3ncu other
// than its own file's (hosts_test.cpp runs that one), so that each kind of traffic crosses:
//  - two hosts: the upper turret with the loader, whose Z3 hangs on the lower turret's bus (a
//    link axis); the PLC and the HMI with the lower turret;
//  - three hosts: each turret on a host of its own, the loader, the PLC and the HMI on a third.
#include "harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

using namespace mcnc::test;

namespace {

const std::vector<HostPart> kTwoHosts{{"ncu1", "CH1, X1, Z1, A1, S1, can0, CH3, X3, can2"},
                                      {"ncu2", "CH2, X2, Z2, S2, Z3, can1, plc, hmi"}};
const std::vector<HostPart> kThreeHosts{{"ncu1", "CH1, X1, Z1, A1, S1, can0"},
                                        {"ncu2", "CH2, X2, Z2, S2, Z3, can1"},
                                        {"ncu3", "CH3, X3, can2, plc, hmi"}};

// At each of the marks P1..P`marks` the channel that arrived first waited until its partner
// arrived, on another host, and only then went on.
void expect_marks_released_across_hosts(const HostsRun& run, int marks) {
  for (int p = 1; p <= marks; ++p) {
    std::vector<nlohmann::json> arrivals;
    for (const nlohmann::json& e : events(run.trace, "sync_arrive")) {
      if (e["p"] == p) {
        arrivals.push_back(e);
      }
    }
    ASSERT_EQ(arrivals.size(), 2U) << "P" << p;
    const std::string waiter = arrivals.front()["ch"];
    const std::string partner = arrivals.back()["ch"];
    EXPECT_LT(arrivals.front()["cycle"], arrivals.back()["cycle"]) << "P" << p;
    EXPECT_FALSE(run.host_of(waiter).empty()) << waiter;
    EXPECT_NE(run.host_of(waiter), run.host_of(partner)) << "P" << p;
    std::size_t released = 0;
    for (const nlohmann::json& e : events(run.trace, "sync_release", waiter)) {
      if (e["p"] == p) {
        EXPECT_GE(e["cycle"], arrivals.back()["cycle"]) << e.dump();
        ++released;
      }
    }
    EXPECT_EQ(released, 1U) << waiter << " at P" << p;
  }
}

// The last position commanded to `axis` in a trace.
double last_position(const std::vector<nlohmann::json>& trace, const std::string& axis) {
  const std::vector<nlohmann::json> pos = events(trace, "pos", axis);
  return pos.empty() ? std::nan("") : pos.back()["cmd"].get<double>();
}

// CH1's A1 lent to CH2 and given back: its node, on CH1's host, took its owner from the other.
void expect_a1_lent_across_hosts(const HostsRun& run) {
  std::vector<nlohmann::json> owners;
  for (const nlohmann::json& e : events(run.trace, "owner", "A1")) {
    if (e["cycle"] != 0) {
      owners.push_back(e["owner"]);
    }
  }
  EXPECT_EQ(owners, (std::vector<nlohmann::json>{nullptr, "CH2", "CH1"}));
  EXPECT_EQ(run.host_of("A1"), run.host_of("CH1"));
  EXPECT_NE(run.host_of("A1"), run.host_of("CH2"));
}

// The example run on one host, then across each split of `splits`: the same trace each time,
// and `crossed` asserts on each run across hosts what crossed them.
void expect_same_across_hosts(const std::string& machine_file, int domain,
                              const std::vector<std::vector<HostPart>>& splits,
                              const std::map<std::string, std::string>& programs,
                              const std::function<void(const HostsRun&)>& crossed) {
  const auto one_host = run_programs(machine_file, domain, programs);
  for (const std::vector<HostPart>& hosts : splits) {
    SCOPED_TRACE(std::to_string(hosts.size()) + " hosts");
    const HostsRun across = run_across_hosts(machine_file, domain, hosts, programs);
    expect_same_trace(one_host, across.trace);
    crossed(across);
  }
}

}  // namespace

// The barrier example (launch/programs/twin_turret_ch*.nc): CH2 waits at P1 for CH1's left end,
// CH1 at P2 for CH2's groove; CH1's G144 has the loader put the blank in first. And what the
// barrier shows of shared variables (tests/integration/programs/shared_vars), on three hosts:
// CH1 writes #500 and #20000 before P1, CH2 moves by them after it and writes #501 before P2,
// which CH1 moves to after P2 (the visibility rule, docs/multichannel.md).
TEST(HostsExamples, TheTwinTurretsBarriersAndWhatTheyShowOfSharedVariablesHoldAcrossHosts) {
  expect_same_across_hosts("cell_3ncu.yaml", 185, {kTwoHosts, kThreeHosts},
                           {{"CH1", "launch/programs/twin_turret_ch1.nc"},
                            {"CH2", "launch/programs/twin_turret_ch2.nc"}},
                           [](const HostsRun& run) { expect_marks_released_across_hosts(run, 2); });
  expect_same_across_hosts(
      "cell_3ncu.yaml", 185, {kThreeHosts},
      {{"CH1", "tests/integration/programs/shared_vars/ch1.nc"},
       {"CH2", "tests/integration/programs/shared_vars/ch2.nc"}},
      [](const HostsRun& run) {
        expect_marks_released_across_hosts(run, 2);
        EXPECT_NEAR(last_position(run.trace, "Z2"), 12.5, 1e-9) << "#500 from CH1";
        EXPECT_NEAR(last_position(run.trace, "X2"), 20.0, 1e-9) << "X40 in diameter: #20000";
        EXPECT_NEAR(last_position(run.trace, "Z1"), 4.5, 1e-9) << "#501 from CH2";
      });
}

// CT-G140-01 (tests/integration/programs/g140): CH1 releases A1, CH2 acquires it, turns it and
// gives it back; each continues from where the other left it (#5003).
TEST(HostsExamples, AnAxisExchangedAcrossTwoAndThreeHostsStaysWithItsNode) {
  expect_same_across_hosts("cell_3ncu.yaml", 186, {kTwoHosts, kThreeHosts},
                           {{"CH1", "tests/integration/programs/g140/ch1.nc"},
                            {"CH2", "tests/integration/programs/g140/ch2.nc"}},
                           [](const HostsRun& run) {
                             expect_a1_lent_across_hosts(run);
                             EXPECT_NEAR(last_position(run.trace, "A1"), 45.0, 1e-9)
                                 << "30 from CH2, then 15 more";
                             expect_marks_released_across_hosts(run, 2);
                           });
}

// The part transfer (launch/programs/part_transfer_ch*.nc) on two hosts; hosts_test.cpp runs it
// on cell_3ncu's three. Here CH1's G144 stays on its host, and Z3 is CH3's link axis.
TEST(HostsExamples, ThePartTransferRunsAcrossTwoHosts) {
  expect_same_across_hosts(
      "cell_3ncu.yaml", 188, {kTwoHosts},
      {{"CH1", "launch/programs/part_transfer_ch1.nc"},
       {"CH2", "launch/programs/part_transfer_ch2.nc"}},
      [](const HostsRun& run) {
        expect_marks_released_across_hosts(run, 2);
        expect_a1_lent_across_hosts(run);
        // The loader went up (O3100: Z80), then down to the chuck (Z10) on Z3, whose node is
        // on the other host.
        const std::vector<nlohmann::json> z3 = events(run.trace, "pos", "Z3");
        const auto up = std::find_if(z3.begin(), z3.end(), [](const nlohmann::json& e) {
          return e["cmd"].get<double>() > 79.9;
        });
        ASSERT_NE(up, z3.end());
        const auto bottom =
            std::min_element(up, z3.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
              return a["cmd"].get<double>() < b["cmd"].get<double>();
            });
        EXPECT_NEAR((*bottom)["cmd"].get<double>(), 10.0, 1e-9);
        EXPECT_NE(run.host_of("Z3"), run.host_of("CH3"));
      });
}

// CT-G514-01 (tests/integration/programs/g514) on the gantry cell split in two: the gantry's Z,
// on the loader's bus, on the second host. G51.4 couples it to X on the first, and Z follows
// X's increments from there until G50.4 releases it.
TEST(HostsExamples, AnAxisFollowsItsMasterOnAnotherHost) {
  expect_same_across_hosts(
      "gantry_cell.yaml", 189,
      {{{"ncu1", "CH1, X, Y, X1, can0, plc, hmi"}, {"ncu2", "CH2, Z, Z2, can1"}}},
      {{"CH1", "tests/integration/programs/g514/ct_g514_01.nc"}}, [](const HostsRun& run) {
        EXPECT_EQ(count(run.trace, "couple", "src", "Z"), 1U);
        EXPECT_EQ(count(run.trace, "decouple", "src", "Z"), 1U);
        EXPECT_NE(run.host_of("Z"), run.host_of("X"));
        EXPECT_NEAR(last_position(run.trace, "X"), 30.0, 1e-9);
        EXPECT_NEAR(last_position(run.trace, "Z"), 10.0, 1e-9) << "X's first increment";
      });
}
