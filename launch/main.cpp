// mcnc-launch: starts and supervises every process of a machine file and runs it.
#include "common/log/logging.hpp"
#include "launch/run_command.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"mcnc-launch: start, supervise and stop every process of a machine"};
  mcnc::launch::RunArguments args;
  mcnc::launch::add_run_options(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // a bad command line is bad input
  }
  mcnc::log::setup("launch", args.log_level);
  return mcnc::launch::execute_run(args);
}
