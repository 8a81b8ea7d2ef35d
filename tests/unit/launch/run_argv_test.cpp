// What a host's launcher service is asked to run is the asker's options, read back the same.
#include "launch/run_command.hpp"

#include <gtest/gtest.h>
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

using mcnc::launch::RunArguments;

namespace {

RunArguments parse(std::vector<std::string> argv) {
  CLI::App app;
  RunArguments args;
  mcnc::launch::add_run_options(app, args);
  std::vector<const char*> c{"run"};
  for (const auto& a : argv) {
    c.push_back(a.c_str());
  }
  app.parse(static_cast<int>(c.size()), const_cast<char**>(c.data()));
  return args;
}

void expect_same(const RunArguments& a, const RunArguments& b) {
  EXPECT_EQ(a.programs, b.programs);
  EXPECT_EQ(a.clock, b.clock);
  EXPECT_EQ(a.pace, b.pace);
  EXPECT_EQ(a.trace_path, b.trace_path);
  EXPECT_EQ(a.trace_pos_every, b.trace_pos_every);
  EXPECT_EQ(a.report_dir, b.report_dir);
  EXPECT_EQ(a.log_level, b.log_level);
  EXPECT_DOUBLE_EQ(a.timeout_s, b.timeout_s);
  EXPECT_DOUBLE_EQ(a.start_timeout_s, b.start_timeout_s);
  EXPECT_EQ(a.drive_faults, b.drive_faults);
  EXPECT_EQ(a.drive_sdo_refusals, b.drive_sdo_refusals);
  EXPECT_EQ(a.operator_script, b.operator_script);
  EXPECT_EQ(a.program_dir, b.program_dir);
  EXPECT_EQ(a.retained_file, b.retained_file);
  EXPECT_EQ(a.hmi, b.hmi);
  EXPECT_EQ(a.manual_start, b.manual_start);
}

RunArguments round_trip(const RunArguments& a) {
  std::vector<std::string> argv{"m.yaml"};
  const std::vector<std::string> rest = mcnc::launch::run_argv(a);
  argv.insert(argv.end(), rest.begin(), rest.end());
  return parse(argv);
}

}  // namespace

TEST(RunArgv, EveryOptionComesBackAsItWasGiven) {
  const RunArguments a = parse({"m.yaml",
                                "--program",
                                "CH1=a.nc",
                                "--program",
                                "CH2=b b.nc",
                                "--clock",
                                "realtime",
                                "--pace",
                                "--trace",
                                "t.jsonl",
                                "--trace-pos-every",
                                "3",
                                "--report",
                                "rep",
                                "--log-level",
                                "debug",
                                "--timeout",
                                "12.5",
                                "--start-timeout",
                                "240",
                                "--drive-fault",
                                "can0:1:overcurrent@100",
                                "--drive-refuse-sdo",
                                "can0:2:0x6065",
                                "--operator",
                                "reset@30",
                                "--operator",
                                "feed_override=50:CH1@10",
                                "--progdir",
                                "p",
                                "--retained",
                                "r.txt",
                                "--hmi",
                                "127.0.0.1:9000",
                                "--manual-start",
                                "--host",
                                "ncu2",
                                "--services"});
  const RunArguments b = round_trip(a);
  expect_same(a, b);
  EXPECT_TRUE(b.host.empty()) << "each service names its own host";
  EXPECT_FALSE(b.services) << "a service runs the run, it does not ask for it again";
}

TEST(RunArgv, DefaultsStayDefaultsAndTheHmiWithoutAnAddressStaysSo) {
  const RunArguments none = parse({"m.yaml"});
  EXPECT_DOUBLE_EQ(none.start_timeout_s, 60.0) << "the start-up limit of every machine until now";
  expect_same(none, round_trip(none));
  const RunArguments hmi = parse({"m.yaml", "--hmi"});
  expect_same(hmi, round_trip(hmi));
}
