#pragma once
// The options and the run shared by `mcnc-launch` and `mcnc run`: parse the program and clock
// options, check every input before anything starts (exit 2 on bad input), launch, print
// progress, and write the report.
#include <map>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace mcnc::launch {

struct RunArguments {
  std::string machine_path;
  std::vector<std::string> programs;  // CH=FILE
  std::string clock = "lockstep";
  bool pace = false;
  std::string trace_path;
  int trace_pos_every = 10;
  std::string report_dir;
  std::string log_level;
  double timeout_s = 0.0;
  double start_timeout_s = 60.0;                // --start-timeout: every process ready within it
  std::vector<std::string> drive_faults;        // BUS:NODE:KIND@SYNC (fault injection)
  std::vector<std::string> drive_sdo_refusals;  // BUS:NODE:INDEX (fault injection)
  std::vector<std::string> operator_script;     // ACTION[:CHANNEL]@CYCLE (scripted operator)
  std::string program_dir;                      // --progdir: overrides machine.program_dir
  std::string retained_file;                    // --retained: overrides machine.retained_file
  std::string hmi;            // --hmi: serve the operator HMI on this HOST:PORT ("" none)
  bool manual_start = false;  // --manual-start: the channels wait for CYCLE START
  std::string host;           // --host: on a machine of several hosts, this launcher's host
  bool serve = false;         // --serve: be --host's launcher service (launch/host_service.hpp)
  bool services = false;      // --services: ask every host's service for the run
};

void add_run_options(CLI::App& app, RunArguments& args);
// The options of `args` as a command line that add_run_options() reads back into the same
// arguments, without the machine, --host, --serve and --services: what a host's service is
// asked to run.
std::vector<std::string> run_argv(const RunArguments& args);
// Returns the process exit code: 0 every program ended without alarm, 1 alarm or failure,
// 2 bad input.
int execute_run(const RunArguments& args);

}  // namespace mcnc::launch
